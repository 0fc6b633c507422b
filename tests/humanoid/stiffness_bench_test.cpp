// The stiffness bench recovers the plant's k_joint, and the compensated command removes the sag.
#include "flexgait/humanoid/stiffness_bench.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flexgait::humanoid {
namespace {

TEST(StiffnessBench, RecoversThePlantStiffness) {
  for (double k : {500.0, 1000.0, 3000.0}) {
    BenchParams p;
    p.actuator.k = k;
    const BenchResult r = run_stiffness_bench(p);
    // 1 % (the bound); the encoder's quantisation (1.25e-5 rad) is the main error.
    EXPECT_NEAR(r.k_fit, k, 0.01 * k) << "k = " << k;
    // The regressor is the gravity torque at the encoder angle, the sag happens at the link angle
    // (τ_g(θ_l) ≠ τ_g(θ_enc) by sin θ · τ_g / k): measured R² 0.988 (k = 500), 0.997 (1000).
    EXPECT_GT(r.r_squared, 0.98);
    // Uncompensated the arm sags by up to m g l / k; compensated it holds the pose to 1e-3 of that.
    const double sag = p.load_mass * 9.81 * p.arm_length / k;
    EXPECT_NEAR(r.max_error_uncompensated, sag, 0.05 * sag);
    EXPECT_LT(r.max_error_compensated, 0.05 * sag);
  }
}

}  // namespace
}  // namespace flexgait::humanoid
