#pragma once
/// \file capture_point_bound.hpp
/// The capture-point bound of a push (docs/guide/humanoid.md): the largest impulse an ankle strategy absorbs
/// without a step. In the linear inverted pendulum (COM height z_c, ω0 = √(g / z_c)) the capture
/// point ξ = c + ċ / ω0 must stay inside the support polygon for the robot to stop without a
/// step (Pratt et al. 2006; Englsberger et al. 2015). From rest with the COM's ground projection
/// c, a push giving the velocity Δv in the unit direction u moves ξ to c + (Δv / ω0) u, which is
/// still inside while Δv ≤ ω0 d, d the distance from c along u to the polygon's edge:
///
///   Δv_max = ω0 d,   impulse_max = m Δv_max.
#include <Eigen/Dense>

#include <vector>

namespace flexgait::experiments {

/// Distance from p along the direction `direction` (any length > 0) to the boundary of the
/// convex polygon (counter-clockwise) [m]; 0 when p is outside or the polygon has fewer than three
/// corners. Throws std::invalid_argument for a zero direction.
double distance_to_edge(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p,
                        const Eigen::Vector2d& direction);

struct CapturePointBound {
  double omega0 = 0;    ///< √(g / z_c) [1/s]
  double distance = 0;  ///< d: COM ground projection to the polygon's edge along the push [m]
  double delta_v = 0;   ///< ω0 d [m/s]
  double impulse = 0;   ///< m ω0 d [N s]
};

/// \param mass m [kg]; \param com_height z_c above the floor [m]; \param gravity g [m/s^2]
/// \param com the COM's ground projection [m]; \param direction the push's horizontal direction
CapturePointBound capture_point_bound(double mass, double com_height, double gravity,
                                      const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& com,
                                      const Eigen::Vector2d& direction);

}  // namespace flexgait::experiments
