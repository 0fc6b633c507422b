// One resolved configuration into everything a wheel run needs (rimless/wheel_setup.hpp): the
// analysis schema holds the wheel's and every analysis's keys; wheel_setup reads the records, runs
// the cross-field checks, and blames an infeasible start on the first key the user set.
#include "flexgait/rimless/wheel_setup.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace flexgait::rimless {
namespace {

Config configured(const std::vector<std::string>& sets) {
  return resolve_config(rimless_analysis_schema(), std::nullopt, sets);
}

std::string refused_key(const std::vector<std::string>& sets) {
  try {
    wheel_setup(configured(sets));
  } catch (const ConfigError& e) {
    return e.key();
  }
  return "";
}

TEST(WheelSetup, AnalysisSchemaHoldsTheWheelAndEveryAnalysis) {
  const Schema s = rimless_analysis_schema();
  for (const char* key : {"rimless.K", "initial.beta", "sim.steps", "analysis.robustness.max_steps",
                          "analysis.orbit.record", "analysis.basin.tolerance"})
    EXPECT_NE(s.find(key), nullptr) << key;
}

TEST(WheelSetup, ReadsTheRecordsOfTheConfiguration) {
  const WheelSetup s =
      wheel_setup(configured({"rimless.K=2000", "initial.omega=1.1", "sim.steps=7", "sim.model=rigid"}));
  EXPECT_EQ(s.wheel.K, 2000.0);
  EXPECT_EQ(s.initial.omega, 1.1);
  EXPECT_EQ(s.sim.steps, 7);
  EXPECT_EQ(s.sim.model, Model::Rigid);
  EXPECT_EQ(s.config.origin("rimless.K"), "--set");
}

TEST(WheelSetup, CrossFieldChecksNameTheirKey) {
  EXPECT_EQ(refused_key({"rimless.mu_s=0.2", "rimless.mu_k=0.3"}), "rimless.mu_k");
  EXPECT_EQ(refused_key({"initial.beta=0.5"}), "initial.beta");  // |β| >= π/10
}

TEST(WheelSetup, InfeasibleFlexibleStartBlamesTheFirstKeyTheUserSet) {
  // A soft leg (m g / K = 0.2 m) with 10 legs puts the neighbouring feet below the ground: the
  // check's own key is rimless.legs, but the user set only rimless.K (then only rimless.m).
  EXPECT_EQ(refused_key({"rimless.K=49.05"}), "rimless.K");
  EXPECT_EQ(refused_key({"rimless.m=20"}), "rimless.m");
  // The rigid model has no compression: nothing to refuse.
  EXPECT_EQ(refused_key({"rimless.K=49.05", "sim.model=rigid"}), "");
}

}  // namespace
}  // namespace flexgait::rimless
