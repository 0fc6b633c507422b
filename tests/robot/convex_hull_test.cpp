// The convex hull of points in a plane: a square's corners counter-clockwise from the lowest x,
// interior and edge points left out; every point on the hull's inner side (the hull contains
// them); the area by the shoelace formula, signed by orientation.
#include "flexgait/robot/convex_hull.hpp"

#include <gtest/gtest.h>

#include <random>

namespace flexgait::humanoid {
namespace {

using Point = std::array<double, 2>;

double cross(const Point& o, const Point& a, const Point& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

TEST(ConvexHull, ASquaresCornersCounterClockwiseWithoutInteriorOrEdgePoints) {
  const std::vector<Point> hull =
      convex_hull({{0.5, 0.5}, {1, 1}, {0, 1}, {0.5, 0}, {1, 0}, {0, 0}, {0.25, 0.75}, {1, 0.5}});
  const std::vector<Point> corners{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(hull, corners);
  EXPECT_DOUBLE_EQ(polygon_area(hull), 1.0);
  EXPECT_DOUBLE_EQ(polygon_area({{0, 0}, {0, 1}, {1, 1}, {1, 0}}), -1.0);  // clockwise: negative
}

TEST(ConvexHull, ContainsEveryPointOfARandomCloud) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  std::vector<Point> points(200);
  for (Point& p : points) p = {u(rng), u(rng)};
  const std::vector<Point> hull = convex_hull(points);
  ASSERT_GE(hull.size(), 3u);
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const Point& a = hull[k];
    const Point& b = hull[(k + 1) % hull.size()];
    EXPECT_GT(cross(a, b, hull[(k + 2) % hull.size()]), 0.0);         // strictly convex, counter-clockwise
    for (const Point& p : points) EXPECT_GE(cross(a, b, p), -1e-15);  // on the inner side (round-off)
  }
  EXPECT_GT(polygon_area(hull), 0.0);
  EXPECT_LT(polygon_area(hull), 0.04);  // inside the 0.2 m square
}

TEST(ConvexHull, FewerThanThreePointsComeBackSorted) {
  EXPECT_EQ(convex_hull({{1, 0}, {0, 2}}), (std::vector<Point>{{0, 2}, {1, 0}}));
  EXPECT_TRUE(convex_hull({}).empty());
}

}  // namespace
}  // namespace flexgait::humanoid
