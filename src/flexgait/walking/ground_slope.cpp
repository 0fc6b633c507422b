#include "flexgait/walking/ground_slope.hpp"

#include <cmath>

#include "flexgait/walking/rotation.hpp"

namespace flexgait::walking {

Eigen::Matrix3d sole_attitude(const Eigen::Vector2d& gradient, double yaw) {
  if (gradient.isZero(0.0)) return rot_z(yaw);  // level: the plan's attitude as it always was, to the bit
  const Eigen::Vector2d heading(std::cos(yaw), std::sin(yaw));
  const Eigen::Vector3d z = Eigen::Vector3d(-gradient.x(), -gradient.y(), 1.0).normalized();
  const Eigen::Vector3d x = Eigen::Vector3d(heading.x(), heading.y(), gradient.dot(heading)).normalized();  // (G2)
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = z.cross(x);
  R.col(2) = z;
  return R;
}

Eigen::Vector2d ground_gradient_of(const Eigen::Matrix3d& sole_R) {
  const Eigen::Vector3d n = sole_R.col(2);
  return Eigen::Vector2d(-n.x() / n.z(), -n.y() / n.z());  // (G1)
}

}  // namespace flexgait::walking
