// The stiffness bench recovers the plant's k_joint, and the compensated command removes the sag.
#include "flexgait/experiments/stiffness_bench.hpp"

#include <gtest/gtest.h>

#include <cmath>

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
  }
}

}  // namespace
}  // namespace flexgait::experiments
