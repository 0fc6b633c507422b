// The support polygon and the margin of a point in it (experiments/support_polygon.hpp), by hand:
// one sole is its rectangle; two soles side by side make the hull of their outer corners; a
// turned sole turns its corners; the margin is the distance to the nearest edge, negative outside.
#include "flexgait/experiments/support_polygon.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace flexgait::experiments {
namespace {

constexpr double kLength = 0.2, kWidth = 0.1;

walking::Pose sole(double x, double y, double yaw) {
  return walking::Pose{Eigen::Vector3d(x, y, 0.0), walking::rot_z(yaw)};
}

// Signed area by the shoelace formula: positive for counter-clockwise corners.
double signed_area(const std::vector<Eigen::Vector2d>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return 0.5 * a;
}

TEST(SupportPolygon, OneSoleIsItsRectangleAndTheMarginItsInnerDistance) {
  const auto poly = support_polygon({sole(0.3, -0.1, 0.0)}, kLength, kWidth);
  ASSERT_EQ(poly.size(), 4u);
  EXPECT_NEAR(signed_area(poly), kLength * kWidth, 1e-15);  // counter-clockwise, the sole's area
  for (const auto& c : poly) {
    EXPECT_NEAR(std::abs(c.x() - 0.3), 0.1, 1e-15);
    EXPECT_NEAR(std::abs(c.y() + 0.1), 0.05, 1e-15);
  }
  // Sums and differences of numbers of order 0.1: 1e-15 m.
  EXPECT_NEAR(support_margin(poly, {0.3, -0.1}), 0.05, 1e-15);   // centre: half the width
  EXPECT_NEAR(support_margin(poly, {0.39, -0.1}), 0.01, 1e-15);  // near the toe
  EXPECT_NEAR(support_margin(poly, {0.5, -0.1}), -0.1, 1e-15);   // 0.1 m beyond the toe
  EXPECT_NEAR(support_margin(poly, {0.3, 0.0}), -0.05, 1e-15);   // beside it
}

TEST(SupportPolygon, TwoSolesSideBySideMakeOneRectangle) {
  // Feet at y = ±0.1 with 0.1 m wide soles: the hull is 0.2 long and 0.3 wide.
  const auto poly = support_polygon({sole(0.0, 0.1, 0.0), sole(0.0, -0.1, 0.0)}, kLength, kWidth);
  EXPECT_NEAR(signed_area(poly), 0.2 * 0.3, 1e-15);
  EXPECT_NEAR(support_margin(poly, {0.0, 0.0}), 0.1, 1e-15);  // the toe and heel edges are nearest
  EXPECT_NEAR(support_margin(poly, {0.05, 0.12}), 0.03, 1e-15);
}

TEST(SupportPolygon, ATurnedSoleTurnsItsCorners) {
  const auto poly = support_polygon({sole(0.0, 0.0, 0.5 * std::numbers::pi)}, kLength, kWidth);
  // Turned a quarter: 0.2 along y, 0.1 along x.
  EXPECT_NEAR(support_margin(poly, {0.0, 0.09}), 0.01, 1e-15);
  EXPECT_NEAR(support_margin(poly, {0.09, 0.0}), -0.04, 1e-15);
  // Turned 30°: the toe corner (0.1, 0.05) goes to (0.1 cos 30° − 0.05 sin 30°, 0.1 sin 30° + 0.05 cos 30°).
  const double a = std::numbers::pi / 6;
  const auto turned = support_polygon({sole(0.0, 0.0, a)}, kLength, kWidth);
  bool found = false;
  for (const auto& c : turned)
    found |=
        (c - Eigen::Vector2d(0.1 * std::cos(a) - 0.05 * std::sin(a), 0.1 * std::sin(a) + 0.05 * std::cos(a))).norm() <
        1e-15;
  EXPECT_TRUE(found);
}

TEST(SupportPolygon, NoSoleOnTheFloorHasNoMargin) {
  EXPECT_TRUE(std::isnan(support_margin(support_polygon({}, kLength, kWidth), {0.0, 0.0})));
}

}  // namespace
}  // namespace flexgait::experiments
