// The capture-point bound against hand computations: the distance along a direction to
// the edge of the feet's support polygon, and m ω0 d.
#include "flexgait/experiments/capture_point_bound.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "flexgait/experiments/support_polygon.hpp"
#include "flexgait/walking/rotation.hpp"

namespace flexgait::experiments {
namespace {

// The feet side by side: soles 0.22 m × 0.15 m centred at (0, ±0.093).
std::vector<Eigen::Vector2d> feet_together() {
  return support_polygon({walking::Pose{Eigen::Vector3d(0, 0.093, 0), walking::rot_z(0)},
                          walking::Pose{Eigen::Vector3d(0, -0.093, 0), walking::rot_z(0)}},
                         0.22, 0.15);
}

TEST(CapturePointBound, DistanceToTheEdgeOfTheFeet) {
  const auto poly = feet_together();  // x in [-0.11, 0.11], y in [-0.168, 0.168]
  const Eigen::Vector2d mid(0.01, 0.0);
  EXPECT_NEAR(distance_to_edge(poly, mid, {1, 0}), 0.10, 1e-12);
  EXPECT_NEAR(distance_to_edge(poly, mid, {-3, 0}), 0.12, 1e-12);  // the direction's length does not count
  EXPECT_NEAR(distance_to_edge(poly, mid, {0, 1}), 0.168, 1e-12);
  // Diagonal: the ray leaves through the front edge at x = 0.11, after 0.10 √2.
  EXPECT_NEAR(distance_to_edge(poly, mid, {1, 1}), 0.10 * std::sqrt(2.0), 1e-12);
  // Outside the polygon: nothing to absorb.
  EXPECT_EQ(distance_to_edge(poly, Eigen::Vector2d(0.2, 0), {1, 0}), 0.0);
  EXPECT_THROW(distance_to_edge(poly, mid, {0, 0}), std::invalid_argument);
}

TEST(CapturePointBound, ImpulseIsMassTimesOmegaTimesDistance) {
  // By hand: m = 57 kg, z_c = 0.81 m, g = 9.81 m/s² → ω0 = √(9.81 / 0.81) = 3.48010... 1/s;
  // COM 1 cm behind the middle, pushed forward: d = 0.12 m, Δv = 0.417612 m/s, 23.8039 N s.
  const CapturePointBound b = capture_point_bound(57.0, 0.81, 9.81, feet_together(), {-0.01, 0}, {1, 0});
  EXPECT_NEAR(b.omega0, 3.4801021696, 1e-9);
  EXPECT_NEAR(b.distance, 0.12, 1e-12);
  EXPECT_NEAR(b.delta_v, 0.4176122604, 1e-9);
  EXPECT_NEAR(b.impulse, 23.80389884, 1e-7);
  EXPECT_THROW(capture_point_bound(0.0, 0.81, 9.81, feet_together(), {0, 0}, {1, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace flexgait::experiments
