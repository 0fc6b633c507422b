// Capture-point step adjustment: no shift while the DCM error stays inside the sole,
// the shift (S2) when it leaves, and whatever the error the landing stays within reach and on
// its own side of the stance foot (the feet never cross).
#include "flexgait/walking/step_adjustment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace flexgait::walking {
namespace {

const Eigen::Vector2d kHalf(0.11, 0.075);  // the builtin's sole half-extents [m]

TEST(StepAdjustment, NothingBeyondTheSoleWhileTheErrorIsInside) {
  const Footprint stance{0.3, -0.093, 0.4};
  for (const Eigen::Vector2d& e : {Eigen::Vector2d(0.1, 0.0), Eigen::Vector2d(-0.05, 0.07), Eigen::Vector2d(0, 0)})
    EXPECT_EQ(dcm_error_beyond_sole(e, Footprint{0, 0, 0}, kHalf), Eigen::Vector2d::Zero());
  // Along a turned sole: 0.1 m along its heading is inside, 0.1 m across is not.
  const Eigen::Vector2d along(std::cos(0.4), std::sin(0.4)), across(-std::sin(0.4), std::cos(0.4));
  EXPECT_LT(dcm_error_beyond_sole(0.1 * along, stance, kHalf).norm(), 1e-15);
  EXPECT_NEAR((dcm_error_beyond_sole(0.1 * across, stance, kHalf) - 0.025 * across).norm(), 0.0, 1e-15);
}

TEST(StepAdjustment, ShiftIsTheErrorBeyondTheSoleGrownToTouchdown) {
  // Stance right foot, left foot planned 0.1 m ahead: a forward error 2 cm beyond the toe, 0.3 s
  // before touchdown at ω = 3.5 1/s, moves the landing by 0.02 e^{1.05} forward (S2).
  const Footprint stance{0, -0.093, 0}, planned{0.1, 0.093, 0};
  const Eigen::Vector2d beyond = dcm_error_beyond_sole(Eigen::Vector2d(0.13, 0), stance, kHalf);
  EXPECT_NEAR(beyond.x(), 0.02, 1e-15);
  const Footprint to = adjusted_landing(planned, stance, 0, beyond, 3.5, 0.3, StepLimits{});
  EXPECT_NEAR(to.x, 0.1 + 0.02 * std::exp(1.05), 1e-12);
  EXPECT_DOUBLE_EQ(to.y, 0.093);
  EXPECT_DOUBLE_EQ(to.yaw, planned.yaw);
}

TEST(StepAdjustment, LandingWithinReachNeverCrossing) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const StepLimits limits{0.25, 0.4, 0.17};
  for (int i = 0; i < 20000; ++i) {
    const int swing = i % 2;
    const double side = swing == 0 ? 1.0 : -1.0;
    const Footprint stance{u(rng), u(rng), 3 * u(rng)};
    const double c = std::cos(stance.yaw), s = std::sin(stance.yaw);
    const double ax = 0.2 * u(rng), ay = side * (0.186 + 0.05 * u(rng));  // a planned landing in the stance frame
    const Footprint planned{stance.x + c * ax - s * ay, stance.y + s * ax + c * ay, stance.yaw};
    const Eigen::Vector2d beyond(0.5 * u(rng), 0.5 * u(rng));
    const Footprint to = adjusted_landing(planned, stance, swing, beyond, 3.5, 0.6 * (u(rng) + 1), limits);
    const double dx = to.x - stance.x, dy = to.y - stance.y;
    const double along = c * dx + s * dy, across = -s * dx + c * dy;
    EXPECT_LE(std::hypot(dx, dy), limits.reach + 1e-12);    // within reach
    EXPECT_GE(side * across, limits.min_width - 1e-12);     // on its own side, feet apart
    EXPECT_LE(std::abs(along - ax), limits.limit + 1e-12);  // the bounded shift along the heading
  }
}

}  // namespace
}  // namespace flexgait::walking
