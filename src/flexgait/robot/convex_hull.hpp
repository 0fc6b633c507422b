#pragma once
/// \file convex_hull.hpp
/// The convex hull of points in a plane (Andrew's monotone chain: A. M. Andrew, "Another efficient
/// algorithm for convex hulls in two dimensions", Information Processing Letters 9, 1979).
#include <array>
#include <vector>

namespace flexgait::humanoid {

/// The corners of the convex hull of `points`, counter-clockwise from the lowest x (then lowest
/// y), collinear points left out; fewer than three points are returned sorted.
std::vector<std::array<double, 2>> convex_hull(std::vector<std::array<double, 2>> points);

/// The area of a simple polygon (shoelace formula), positive when counter-clockwise [m^2].
double polygon_area(const std::vector<std::array<double, 2>>& polygon);

}  // namespace flexgait::humanoid
