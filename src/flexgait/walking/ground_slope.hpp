#pragma once
/// \file ground_slope.hpp
/// A sole flat on a plane z = z0 + g·(x, y) (docs/guide/humanoid.md: a controller told the floor, on a ramp).
///
/// The sole's z axis is the plane's normal n = (−g_x, −g_y, 1)/‖·‖; its x axis is the plane's
/// tangent above its heading ψ, x ∝ (cos ψ, sin ψ, g·(cos ψ, sin ψ)); and y = n × x (G2).
/// Conversely a sole of attitude R lies on the plane of gradient g = −(n_x, n_y)/n_z (G1).
#include <Eigen/Dense>

namespace flexgait::walking {

/// The attitude (G2) of a sole of heading yaw [rad] lying flat on a plane of gradient g. On level
/// ground (g = 0) it is R_z(yaw) exactly.
Eigen::Matrix3d sole_attitude(const Eigen::Vector2d& gradient, double yaw);

/// The gradient g (G1) of the plane a sole of attitude R lies flat on (its z axis upward).
Eigen::Vector2d ground_gradient_of(const Eigen::Matrix3d& sole_R);

}  // namespace flexgait::walking
