#pragma once
/// \file support_polygon.hpp
/// The support polygon of the soles on the floor (convex hull of their polygons' corners) and the signed
/// distance of a point to its boundary: > 0 inside, < 0 outside [m].
#include <Eigen/Dense>

#include <vector>

#include "flexgait/walking/leg_kinematics.hpp"
#include "flexgait/walking/sole_polygon.hpp"

namespace flexgait::experiments {

/// Convex hull (counter-clockwise) of the corners of the given soles: `shapes[i]` (its sole frame)
/// placed at `soles[i]` (the two the same size).
std::vector<Eigen::Vector2d> support_polygon(const std::vector<walking::Pose>& soles,
                                             const std::vector<const walking::SolePolygon*>& shapes);
/// The same for soles that are each the rectangle length × width [m].
std::vector<Eigen::Vector2d> support_polygon(const std::vector<walking::Pose>& soles, double length, double width);

/// Signed distance from p to the boundary of the convex polygon (ccw): positive inside [m]; NaN
/// when the polygon has fewer than three corners (no sole on the floor: the margin is undefined).
double support_margin(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);

}  // namespace flexgait::experiments
