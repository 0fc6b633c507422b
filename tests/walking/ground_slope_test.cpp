// A sole flat on a plane (ground_slope.hpp (G1), (G2)): exact identities to rounding (1e-15 on
// unit-size quantities, 1e-12 on gradients after a division by n_z ≥ 0.9).
#include <gtest/gtest.h>

#include <cmath>

#include "flexgait/walking/ground_slope.hpp"
#include "flexgait/walking/rotation.hpp"

namespace flexgait::walking {
namespace {

TEST(GroundSlope, LevelGroundIsTheHeadingRotationToTheBit) {
  for (const double yaw : {0.0, 0.3, -2.0, 3.1}) EXPECT_EQ(sole_attitude(Eigen::Vector2d::Zero(), yaw), rot_z(yaw));
}

TEST(GroundSlope, RampAlongXIsAPitchAboutTheSoleY) {
  // Down a ramp of angle α along +x (z = −x tan α): the sole is R_y(α), toe down.
  const double a = 0.0873;
  const Eigen::Matrix3d R = sole_attitude(Eigen::Vector2d(-std::tan(a), 0), 0.0);
  EXPECT_LT((R - rot_y(a)).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(GroundSlope, AttitudeIsARotationOnThePlaneWithItsHeadingAndGivesTheGradientBack) {
  for (const Eigen::Vector2d& g : {Eigen::Vector2d(0.1, -0.05), Eigen::Vector2d(-0.2, 0.3), Eigen::Vector2d(0.0, 0.15)})
    for (const double yaw : {0.0, 0.7, -1.9}) {
      const Eigen::Matrix3d R = sole_attitude(g, yaw);
      EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-15);
      EXPECT_NEAR(R.determinant(), 1.0, 1e-15);
      // x and y lie in the plane: dz = g · (dx, dy) along each.
      for (int c = 0; c < 2; ++c) EXPECT_NEAR(R(2, c), g.dot(R.col(c).head<2>()), 1e-15);
      // The heading: x's horizontal projection points along yaw.
      EXPECT_NEAR(std::atan2(R(1, 0), R(0, 0)), yaw, 1e-15);
      EXPECT_LT((ground_gradient_of(R) - g).cwiseAbs().maxCoeff(), 1e-12);
    }
}

}  // namespace
}  // namespace flexgait::walking
