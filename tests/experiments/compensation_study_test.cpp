// The thesis's walking experiments as sets of walks (experiments/compensation_study.hpp): the
// compensation study's nine cases differ from the base in their compensation alone; the mismatch
// study scales the twin's true stiffness and pairs off with both; the comparison's headline cuts
// are 1 − on/off of the cases' metrics.
#include "flexgait/experiments/compensation_study.hpp"

#include "flexgait/experiments/walk_output.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace flexgait::experiments {
namespace {

using compensation::CompensationMode;
using compensation::GravityForm;
using compensation::LoadModel;

TEST(CompensationStudy, CasesDifferInTheirCompensationAlone) {
  WalkRunParams base;
  base.walk.steps = 7;
  base.plant.k_joint = 1234.0;
  const auto cases = compensation_cases(base);
  struct Expected {
    const char* name;
    CompensationMode mode;
    LoadModel load;
  };
  const Expected expected[] = {{"off", CompensationMode::kOff, LoadModel::kGravity},
                               {"both", CompensationMode::kBoth, LoadModel::kGravity},
                               {"both-thesis-form", CompensationMode::kBoth, LoadModel::kGravity},
                               {"robotis", CompensationMode::kRobotis, LoadModel::kGravity},
                               {"talos", CompensationMode::kTalos, LoadModel::kGravity},
                               {"both-measured", CompensationMode::kBoth, LoadModel::kMeasured},
                               {"both-dynamic", CompensationMode::kBoth, LoadModel::kDynamic},
                               {"both-dynamic-horizontal", CompensationMode::kBoth, LoadModel::kDynamic},
                               {"both-dynamic-horizontal-lag", CompensationMode::kBoth, LoadModel::kDynamic}};
  ASSERT_EQ(cases.size(), std::size(expected));
  for (std::size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(cases[i].name, expected[i].name);
    EXPECT_EQ(cases[i].params.control.mode, expected[i].mode) << cases[i].name;
    EXPECT_EQ(cases[i].params.control.load_model, expected[i].load) << cases[i].name;
    EXPECT_EQ(cases[i].params.walk.steps, 7) << cases[i].name;
    EXPECT_EQ(cases[i].params.plant.k_joint, 1234.0) << cases[i].name;
  }
  EXPECT_EQ(cases[1].params.control.gravity, GravityForm::kFull);
  EXPECT_EQ(cases[2].params.control.gravity, GravityForm::kThesis);
  const std::size_t horizontal = cases.size() - 2;  // both-dynamic-horizontal, then the same with the gears' lag
  for (std::size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(cases[i].params.control.plan_horizontal_force, i < horizontal ? 0.0 : 1.0) << cases[i].name;
    // Only the last case believes the gears' lag, at the twin's damping with the short F/T low-pass.
    const bool lag = i + 1 == cases.size();
    EXPECT_EQ(cases[i].params.control.gear_damping, lag ? base.plant.gear_damping : 0.0) << cases[i].name;
    EXPECT_EQ(cases[i].params.control.load_filter_time, lag ? 0.02 : base.control.load_filter_time) << cases[i].name;
  }
}

// `humanoid walk` left at its defaults runs the default case both-dynamic-horizontal-lag (its name in summary.json):
// the dynamic loads, the plan's whole ground wrench, the gears' damping believed at the plant's, the short F/T
// low-pass; the keys a user sets stay as set, and off and the field's baselines keep the thesis's static model.
TEST(CompensationStudy, TheWalksDefaultIsTheStudysDefaultCase) {
  const auto resolved = [](const std::vector<std::string>& sets) {
    return walk_run_from_config(resolve_config(walk_run_schema(), std::nullopt, sets));
  };
  const WalkRunParams d = resolved({});
  EXPECT_EQ(compensation_case_name(d), "both-dynamic-horizontal-lag");
  EXPECT_EQ(d.control.load_model, LoadModel::kDynamic);
  EXPECT_EQ(d.control.plan_horizontal_force, 1.0);
  EXPECT_EQ(d.control.gear_damping, d.plant.gear_damping);
  EXPECT_GT(d.control.gear_damping, 0.0);
  EXPECT_EQ(d.control.load_filter_time, compensation::kLagLoadFilterTime);
  // With the output compensator the controller's kinematic estimators read its link angles; dcm balance runs
  // the same case; the input compensator alone has no estimate to give.
  EXPECT_TRUE(d.control.compensated_feedback);
  const WalkRunParams dcm = resolved({"balance.mode=dcm"});
  EXPECT_EQ(compensation_case_name(dcm), "both-dynamic-horizontal-lag");
  EXPECT_TRUE(dcm.control.compensated_feedback);
  EXPECT_FALSE(resolved({"control.compensation=input"}).control.compensated_feedback);
  EXPECT_FALSE(resolved({"control.compensated_feedback=false"}).control.compensated_feedback);
  // The study's case of that name is the same compensation.
  const auto cases = compensation_cases(d);
  const StudyCase& best = cases.back();
  EXPECT_EQ(best.name, compensation_case_name(d));
  EXPECT_EQ(best.params.control.load_model, d.control.load_model);
  EXPECT_EQ(best.params.control.plan_horizontal_force, d.control.plan_horizontal_force);
  EXPECT_EQ(best.params.control.gear_damping, d.control.gear_damping);
  EXPECT_EQ(best.params.control.load_filter_time, d.control.load_filter_time);
  // What is set stays; what follows from it is resolved with it.
  EXPECT_EQ(compensation_case_name(resolved({"control.load_model=measured"})), "both-measured-lag");
  EXPECT_EQ(compensation_case_name(resolved({"control.gear_damping=0"})), "both-dynamic-horizontal");
  EXPECT_EQ(resolved({"control.gear_damping=0"}).control.load_filter_time, compensation::kStaticLoadFilterTime);
  EXPECT_EQ(compensation_case_name(resolved({"control.plan_horizontal_force=0.5"})), "both-dynamic-horizontal-0.5-lag");
  EXPECT_EQ(compensation_case_name(resolved({"control.gear_damping=40"})), "both-dynamic-horizontal-lag-40");
  EXPECT_EQ(compensation_case_name(resolved({"control.load_model=gravity", "control.gravity_model=thesis"})),
            "both-thesis-form-lag");
  for (const char* mode : {"off", "robotis", "talos"}) {
    const WalkRunParams b = resolved({std::string("control.compensation=") + mode});
    EXPECT_EQ(compensation_case_name(b), mode);
    EXPECT_EQ(b.control.load_model, LoadModel::kGravity) << mode;
    EXPECT_EQ(b.control.gear_damping, 0.0) << mode;
    EXPECT_EQ(b.control.load_filter_time, compensation::kStaticLoadFilterTime) << mode;
  }
  // The name is written in summary.json.
  WalkResult r;
  r.metrics.compensation_case = compensation_case_name(d);
  const auto summary = nlohmann::json::parse(walk_summary_json(r));
  EXPECT_EQ(summary.at("compensation_case"), "both-dynamic-horizontal-lag");
}

TEST(CompensationStudy, MismatchScalesTheTrueStiffnessOnly) {
  WalkRunParams base;
  base.plant.k_joint = 1000.0;
  const auto cases = mismatch_cases(base, {0.5, 1.25});
  ASSERT_EQ(cases.size(), 4u);
  EXPECT_EQ(cases[0].name, "k050-off");
  EXPECT_EQ(cases[1].name, "k050-both");
  EXPECT_EQ(cases[3].name, "k125-both");
  EXPECT_EQ(cases[0].params.plant.k_joint, 500.0);
  EXPECT_EQ(cases[3].params.plant.k_joint, 1250.0);
  EXPECT_EQ(cases[3].params.control.k_joint, base.control.k_joint);  // the belief stays
  EXPECT_EQ(cases[0].params.control.mode, CompensationMode::kOff);
  EXPECT_EQ(cases[1].params.control.mode, CompensationMode::kBoth);
}

TEST(CompensationStudy, ComparisonCutsAreOneMinusOnOverOff) {
  const auto cases = compensation_cases(WalkRunParams{});
  std::vector<WalkResult> results(cases.size());
  results[0].metrics.pelvis_roll_error_max = 0.05;   // off
  results[1].metrics.pelvis_roll_error_max = 0.004;  // both
  results[0].metrics.zmp_single_support_rms_y = 0.02;
  results[1].metrics.zmp_single_support_rms_y = 0.015;
  const nlohmann::ordered_json j = compensation_comparison(cases, results);
  EXPECT_NEAR(j["pelvis_roll_error_max_cut"].get<double>(), 1 - 0.004 / 0.05, 1e-15);
  EXPECT_NEAR(j["zmp_single_support_rms_y_cut"].get<double>(), 1 - 0.015 / 0.02, 1e-15);
  EXPECT_EQ(j["pelvis_roll_error_max_off"], 0.05);
}

}  // namespace
}  // namespace flexgait::experiments
