// The stiffness bench recovers the plant's k_joint, and the compensated command removes the sag.
#include "flexgait/experiments/stiffness_bench.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "../support/enum_table.hpp"
#include "../support/mujoco_warnings.hpp"
#include "flexgait/core/record_json.hpp"

namespace flexgait::experiments {
namespace {

TEST(StiffnessBench, RecoversThePlantStiffness) {
  for (double k : {500.0, 1000.0, 3000.0}) {
    BenchParams p;
    p.actuator.k = k;
    const BenchResult r = run_stiffness_bench(p);
    // 1 % (the bound); the encoder's quantisation (1.25e-5 rad) is the main error.
    EXPECT_NEAR(r.k_fit, k, 0.01 * k) << "k = " << k;
    EXPECT_GT(r.r_squared, 0.9999);  // a spring: error = τ_g / k up to the encoder's quantisation
    // Uncompensated the arm sags by up to m g l / k; the compensated command (gravity torque at
    // the desired pose) leaves a second-order residual, below 5 % of the sag.
    const double sag = p.load_mass * 9.81 * p.arm_length / k;
    EXPECT_NEAR(r.max_error_uncompensated, sag, 0.05 * sag);
    EXPECT_LT(r.max_error_compensated, 0.05 * sag);
    EXPECT_FALSE(r.failure.has_value()) << r.failure_text();
  }
}

TEST(StiffnessBench, FailureNamesRoundTrip) {
  flexgait::testing::expect_enum_table_round_trips<BenchFailureReason>();
}

// summary.json's failure is made from the reason, the sweep, the pose and the detail (the text
// the bench wrote before the reasons were typed).
TEST(StiffnessBench, FailureTextComesFromTheReason) {
  BenchResult r;
  EXPECT_EQ(record_json(r)["failure"], "");
  r.failure = BenchFailure{BenchFailureReason::kMuJoCoWarning, "Nan, Inf or huge value in QACC at DOF 0",
                           BenchSweep::kUncompensated, 3};
  EXPECT_EQ(record_json(r)["failure"], "uncompensated sweep, pose 3: MuJoCo: Nan, Inf or huge value in QACC at DOF 0");
  r.failure = BenchFailure{BenchFailureReason::kDiverged, {}, BenchSweep::kCompensated, 0};
  EXPECT_EQ(r.failure_text(), "compensated sweep, pose 0: the simulation diverged: a non-finite state");
  r.failure = BenchFailure{BenchFailureReason::kNoFit, "-12.5"};
  EXPECT_EQ(r.failure_text(), "no finite positive stiffness fits the sweep (k_fit = -12.5)");
}

// A gear far too stiff for the 1 ms step (k = 1e12 Nm/rad: its period is far below the step)
// makes MuJoCo's integration blow up in the first sweep's first pose (MuJoCo warns: "Nan, Inf or
// huge value in QACC"): a physics outcome, reported as a reason, with nothing fitted.
TEST(StiffnessBench, AnUnstableGearFailsTheFirstSweep) {
  BenchParams p;
  p.actuator.k = 1e12;
  const BenchResult r = run_stiffness_bench(p);
  EXPECT_FALSE(test_support::take_mujoco_warnings().empty());  // expected here, not a test failure
  ASSERT_TRUE(r.failure.has_value());
  EXPECT_EQ(r.failure->reason, BenchFailureReason::kMuJoCoWarning) << name_of(r.failure->reason);
  EXPECT_NE(r.failure->detail, "");
  EXPECT_EQ(r.failure->sweep, BenchSweep::kUncompensated);
  EXPECT_EQ(r.failure->pose, 0);
  EXPECT_EQ(r.k_fit, 0.0);
  EXPECT_TRUE(r.compensated.empty());
}

}  // namespace
}  // namespace flexgait::experiments
