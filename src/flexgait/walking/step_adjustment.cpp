#include "flexgait/walking/step_adjustment.hpp"

#include <algorithm>
#include <cmath>

namespace flexgait::walking {
namespace {

/// World → the frame of a footprint's heading (rotation only).
Eigen::Vector2d to_local(const Eigen::Vector2d& v, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {c * v.x() + s * v.y(), -s * v.x() + c * v.y()};
}
Eigen::Vector2d to_world(const Eigen::Vector2d& v, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

}  // namespace

Eigen::Vector2d dcm_error_beyond_sole(const Eigen::Vector2d& e, const Footprint& stance, const Eigen::Vector2d& half) {
  const Eigen::Vector2d local = to_local(e, stance.yaw);
  const Eigen::Vector2d delta(std::clamp(local.x(), -half.x(), half.x()), std::clamp(local.y(), -half.y(), half.y()));
  return to_world(local - delta, stance.yaw);
}

Footprint adjusted_landing(const Footprint& planned, const Footprint& stance, int swing, const Eigen::Vector2d& beyond,
                           double omega, double tau, const StepLimits& limits) {
  const Eigen::Vector2d shift = to_local(beyond * std::exp(omega * std::max(tau, 0.0)), stance.yaw);  // (S2)
  const Eigen::Vector2d planned_local =
      to_local(Eigen::Vector2d(planned.x - stance.x, planned.y - stance.y), stance.yaw);
  Eigen::Vector2d land = planned_local + shift.cwiseMax(-limits.limit).cwiseMin(limits.limit);
  // The swing foot on its own side (left: +y of the stance heading), at least min_width across.
  const double side = swing == 0 ? 1.0 : -1.0;
  land.y() = side * std::clamp(side * land.y(), limits.min_width, std::max(limits.min_width, limits.reach));
  // Within reach: shorten along the heading first (the width keeps the feet apart).
  if (land.norm() > limits.reach) {
    const double along = std::sqrt(std::max(0.0, limits.reach * limits.reach - land.y() * land.y()));
    land.x() = std::clamp(land.x(), -along, along);
  }
  Footprint out = planned;
  const Eigen::Vector2d world = to_world(land, stance.yaw);
  out.x = stance.x + world.x();
  out.y = stance.y + world.y();
  return out;
}

}  // namespace flexgait::walking
