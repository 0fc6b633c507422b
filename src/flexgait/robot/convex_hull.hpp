#pragma once
/// \file convex_hull.hpp
/// The convex hull of points in a plane (Andrew's monotone chain: A. M. Andrew, "Another efficient
/// algorithm for convex hulls in two dimensions", Information Processing Letters 9, 1979).
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace flexgait::humanoid {

/// Andrew's monotone chain on `points[0, n)` (sorted in place by x, then y): the hull's corners
/// written to `out` (room for 2 n points), counter-clockwise from the lowest x (then lowest y),
/// collinear points left out; returns how many. Fewer than three points: copied sorted. `Point`:
/// any type with p[0], p[1] (std::array<double, 2>, Eigen::Vector2d). Allocates nothing.
template <class Point>
std::size_t convex_hull_into(Point* points, std::size_t n, Point* out) {
  std::sort(points, points + n,
            [](const Point& a, const Point& b) { return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]); });
  if (n < 3) {
    std::copy(points, points + n, out);
    return n;
  }
  const auto cross = [](const Point& o, const Point& a, const Point& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    while (k >= 2 && cross(out[k - 2], out[k - 1], points[i]) <= 0) --k;
    out[k++] = points[i];
  }
  for (std::size_t i = n - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(out[k - 2], out[k - 1], points[i]) <= 0) --k;
    out[k++] = points[i];
  }
  return k - 1;
}

/// The corners of the convex hull of `points`, counter-clockwise from the lowest x (then lowest
/// y), collinear points left out; fewer than three points are returned sorted.
std::vector<std::array<double, 2>> convex_hull(std::vector<std::array<double, 2>> points);

/// The area of a simple polygon (shoelace formula), positive when counter-clockwise [m^2].
double polygon_area(const std::vector<std::array<double, 2>>& polygon);

}  // namespace flexgait::humanoid
