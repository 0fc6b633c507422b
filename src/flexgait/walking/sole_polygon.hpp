#pragma once
/// \file sole_polygon.hpp
/// A foot's sole as a convex polygon in the sole frame (x forward, y left, origin the sole centre;
/// docs/guide/robot.md, "Feet"): the region where the ground can put the foot's centre of pressure
/// (Vukobratović and Borovac, 2004, "Zero-moment point — thirty five years of its life": the ZMP
/// stays in the convex hull of the contact points). The queries a controller asks of it: is a
/// point on it, the point of it nearest a point (a centre of pressure or a DCM offset clamped into
/// the sole), the signed distance to its edge, the sole shrunk by a margin.
///
/// The rectangle (the builtin's; a sole named or sized by the mapping; a hull that is an
/// axis-aligned rectangle) is its own case: its nearest point is the componentwise clamp
/// (std::clamp(x, −L/2, L/2), std::clamp(y, −W/2, W/2)), the arithmetic the controller had for
/// its rectangle, so a rectangle's results do not depend on its corners' order. No query allocates.
#include <Eigen/Dense>

#include <cstddef>
#include <vector>

namespace flexgait::walking {

struct SolePolygon {
  /// Counter-clockwise corners [m]; one corner: a point, two: a segment (a sole shrunk past its
  /// inner radius). For a rectangle (±half.x, ±half.y).
  std::vector<Eigen::Vector2d> corners;
  bool rectangle = false;                          ///< the corners are (±half.x, ±half.y)
  Eigen::Vector2d half = Eigen::Vector2d::Zero();  ///< a rectangle's half-extents [m] (0 otherwise)
};

/// The rectangle length × width [m] about the origin.
SolePolygon rectangle_sole(double length, double width);
/// The convex hull of `points` [m] (at least one), a rectangle when the hull is (±a, ±b) exactly.
SolePolygon polygon_sole(const std::vector<Eigen::Vector2d>& points);

/// Whether `p` [m] lies on the sole (its boundary included).
bool contains(const SolePolygon& sole, const Eigen::Vector2d& p);
/// Whether `p` lies on the sole scaled by 2 `share` about the origin (the sole centre): `share` is
/// the share of the sole's extent on each side, ½ the sole itself; a rectangle: |x| ≤ share L and
/// |y| ≤ share W.
bool contains_scaled(const SolePolygon& sole, const Eigen::Vector2d& p, double share);
/// The point of the sole nearest `p`: `p` itself on the sole, else the nearest point of its edges [m].
Eigen::Vector2d nearest_point(const SolePolygon& sole, const Eigen::Vector2d& p);
/// The point of the convex polygon `corners[0, n)` (counter-clockwise; one: a point, two: a segment)
/// nearest `p` [m]: nearest_point's general case, for corners held in a caller's buffer.
Eigen::Vector2d nearest_point(const Eigen::Vector2d* corners, std::size_t n, const Eigen::Vector2d& p);
/// The signed distance from `p` to the sole's edge: > 0 inside, < 0 outside (−|p − nearest_point|) [m].
double signed_distance(const SolePolygon& sole, const Eigen::Vector2d& p);
/// The points of the sole at least `margin` ≥ 0 inside its edges [m]: each edge moved inward by
/// `margin` (a rectangle: half − margin, not below 0). A sole whose inner radius is below `margin`
/// gives its corners' mean, one point.
SolePolygon inset(const SolePolygon& sole, double margin);

}  // namespace flexgait::walking
