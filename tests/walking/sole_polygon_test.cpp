// The sole polygon (walking/sole_polygon.hpp): a rectangle's nearest point is the componentwise
// clamp to the last bit, and the general polygon code on the same rectangle agrees with it to
// round-off; for an octagon the nearest point of an outside point lies on the edge and is nearer
// than any other edge point (checked against a dense sampling of the edges), and is a corner or the
// foot of the perpendicular; inside points are their own nearest point with the distance to the
// nearest edge line; the hull contains every point it is made of; a sole moved in by a margin has
// its corners exactly that far inside.
#include "flexgait/walking/sole_polygon.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace flexgait::walking {
namespace {

using Eigen::Vector2d;

// The octagon of tests/humanoid/data/octagon_sphere_feet.xml: the 0.18 x 0.10 m rectangle with its
// corners cut 30 mm along and 20 mm across.
std::vector<Vector2d> octagon_points() {
  return {Vector2d(0.09, 0.03),  Vector2d(0.09, -0.03),  Vector2d(0.06, 0.05),  Vector2d(0.06, -0.05),
          Vector2d(-0.06, 0.05), Vector2d(-0.06, -0.05), Vector2d(-0.09, 0.03), Vector2d(-0.09, -0.03)};
}

double cross(const Vector2d& a, const Vector2d& b, const Vector2d& p) {
  return (b - a).x() * (p - a).y() - (b - a).y() * (p - a).x();
}

TEST(SolePolygon, RectangleNearestPointIsTheComponentwiseClampToTheLastBit) {
  const double length = 0.22, width = 0.15;
  const SolePolygon r = rectangle_sole(length, width);
  ASSERT_TRUE(r.rectangle);
  // The same rectangle from its corners and an interior point is recognised as one.
  const SolePolygon from_points = polygon_sole({Vector2d(0.11, 0.075), Vector2d(-0.11, 0.075), Vector2d(0.0, 0.01),
                                                Vector2d(-0.11, -0.075), Vector2d(0.11, -0.075)});
  EXPECT_TRUE(from_points.rectangle);
  EXPECT_EQ(from_points.half, r.half);
  SolePolygon general = r;  // the polygon code on the same corners
  general.rectangle = false;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (int i = 0; i < 2000; ++i) {
    const Vector2d p(u(rng), u(rng));
    const Vector2d q = nearest_point(r, p);
    // 0 ULP: the controller's former arithmetic for its rectangle.
    EXPECT_EQ(q.x(), std::clamp(p.x(), -0.5 * length, 0.5 * length));
    EXPECT_EQ(q.y(), std::clamp(p.y(), -0.5 * width, 0.5 * width));
    EXPECT_EQ(contains(r, p), std::abs(p.x()) <= 0.5 * length && std::abs(p.y()) <= 0.5 * width);
    EXPECT_EQ(contains_scaled(r, p, 0.3), std::abs(p.x()) <= 0.3 * length && std::abs(p.y()) <= 0.3 * width);
    // The general code: a + t (b − a) on an edge rounds once per operation (1e-16 m on 0.1 m).
    EXPECT_LT((nearest_point(general, p) - q).norm(), 1e-16);
    EXPECT_NEAR(signed_distance(general, p), signed_distance(r, p), 1e-16);
  }
}

TEST(SolePolygon, OctagonHullKeepsEveryPointAndIsNotItsBoundingRectangle) {
  const SolePolygon s = polygon_sole(octagon_points());
  EXPECT_FALSE(s.rectangle);
  ASSERT_EQ(s.corners.size(), 8u);
  const std::size_t n = s.corners.size();
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_GT(cross(s.corners[i], s.corners[(i + 1) % n], s.corners[(i + 2) % n]), 0.0);  // convex, ccw
    for (const Vector2d& p : octagon_points()) EXPECT_GE(cross(s.corners[i], s.corners[(i + 1) % n], p), 0.0);
  }
  for (const Vector2d& p : octagon_points()) EXPECT_TRUE(contains(s, p));
  // The bounding rectangle's corner lies outside, as far as the cut edge's line from it.
  const Vector2d corner(0.09, 0.05);
  EXPECT_FALSE(contains(s, corner));
  const Vector2d a(0.06, 0.05), b(0.09, 0.03);
  EXPECT_NEAR(signed_distance(s, corner), -std::abs(cross(a, b, corner)) / (b - a).norm(), 1e-17);
}

TEST(SolePolygon, OctagonNearestPointIsTheNearestEdgePoint) {
  const SolePolygon s = polygon_sole(octagon_points());
  const std::size_t n = s.corners.size();
  // Dense edge samples: 2000 per edge (the longest 0.12 m: spacing h ≤ 6e-5 m), so a sample lies
  // within s = h/2 along the edge of the true nearest point: its distance exceeds the true one d by
  // at most √(d² + s²) − d ≤ s²/(2d); no sample may be nearer than the answer.
  std::vector<Vector2d> samples;
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k <= 2000; ++k)
      samples.push_back(s.corners[i] + (k / 2000.0) * (s.corners[(i + 1) % n] - s.corners[i]));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  int outside = 0;
  for (int i = 0; i < 400; ++i) {
    const Vector2d p(u(rng), u(rng));
    const Vector2d q = nearest_point(s, p);
    if (contains(s, p)) {
      EXPECT_EQ(q, p);
      double line = INFINITY;
      for (std::size_t k = 0; k < n; ++k)
        line = std::min(
            line, cross(s.corners[k], s.corners[(k + 1) % n], p) / (s.corners[(k + 1) % n] - s.corners[k]).norm());
      EXPECT_EQ(signed_distance(s, p), line);
      EXPECT_GE(signed_distance(s, p), 0.0);
      continue;
    }
    ++outside;
    EXPECT_NEAR(signed_distance(s, q), 0.0, 1e-17);  // on the boundary (round-off of a 0.1 m edge)
    EXPECT_NEAR(signed_distance(s, p), -(p - q).norm(), 1e-17);
    double best = INFINITY;
    for (const Vector2d& x : samples) best = std::min(best, (x - p).norm());
    EXPECT_LE((q - p).norm(), best + 1e-15);  // (round-off of the samples' arithmetic)
    const double d = (q - p).norm(), s_max = 0.5 * 0.12 / 2000;
    EXPECT_LE(best, d + s_max * s_max / (2 * d) + 1e-15);
    // A corner, or the foot of the perpendicular on the edge it lies on.
    bool corner = false, foot = false;
    for (std::size_t k = 0; k < n; ++k) {
      const Vector2d &a = s.corners[k], &b = s.corners[(k + 1) % n];
      corner = corner || q == a;
      const double on_line = std::abs(cross(a, b, q)) / (b - a).norm();
      foot = foot || (on_line < 1e-17 && std::abs((p - q).dot(b - a)) < 1e-15);
    }
    EXPECT_TRUE(corner || foot) << p.transpose();
  }
  EXPECT_GT(outside, 200);  // most samples of the 0.4 m square lie outside the 0.18 m sole
}

TEST(SolePolygon, InsetCornersLieTheMarginInside) {
  const SolePolygon s = polygon_sole(octagon_points());
  const double margin = 0.02;
  const SolePolygon in = inset(s, margin);
  ASSERT_EQ(in.corners.size(), 8u);
  // Each corner is where two edges moved in by the margin meet: that far from the sole's edge.
  for (const Vector2d& c : in.corners) EXPECT_NEAR(signed_distance(s, c), margin, 1e-16);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (int i = 0; i < 1000; ++i) {
    const Vector2d p(u(rng), u(rng));
    if (std::abs(signed_distance(s, p) - margin) > 1e-12) {
      EXPECT_EQ(contains(in, p), signed_distance(s, p) > margin) << p.transpose();
    }
  }
  // A rectangle: half − margin, floored at 0; past the inner radius, one point.
  const SolePolygon r = inset(rectangle_sole(0.22, 0.15), margin);
  EXPECT_TRUE(r.rectangle);
  EXPECT_EQ(r.half, Vector2d(0.5 * 0.22 - margin, 0.5 * 0.15 - margin));
  EXPECT_EQ(inset(rectangle_sole(0.22, 0.03), margin).half.y(), 0.0);
  const SolePolygon point = inset(s, 0.06);
  ASSERT_EQ(point.corners.size(), 1u);
  EXPECT_LT(point.corners[0].norm(), 1e-17);  // the octagon's corners' mean: its centre
  EXPECT_EQ(nearest_point(point, Vector2d(1, 1)), point.corners[0]);
}

}  // namespace
}  // namespace flexgait::walking
