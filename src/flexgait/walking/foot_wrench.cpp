#include "flexgait/walking/foot_wrench.hpp"

#include "flexgait/walking/robot_model.hpp"

namespace flexgait::walking {

FootContact foot_contact(const humanoid::ForceTorque& ft, const Eigen::Matrix3d& sole_R, double d, double foot_mass,
                         double gravity, const Eigen::Vector2d& s) {
  const Eigen::Vector3d weight = sole_R.transpose() * Eigen::Vector3d(0, 0, -gravity * foot_mass);
  const Eigen::Vector3d f = -Eigen::Vector3d(ft.force.data()) - weight;
  const Eigen::Vector3d tau = -Eigen::Vector3d(ft.torque.data());
  FootContact c;
  c.normal_force = f.z();
  c.force = f;
  if (f.z() > 1e-9) c.cop = Eigen::Vector2d((-tau.y() - d * f.x()) / f.z(), (tau.x() - d * f.y()) / f.z());
  c.torque = Eigen::Vector2d(tau.x() - d * f.y(), tau.y() + d * f.x());
  if (s.x() != 0 || s.y() != 0) {  // about the sole centre (no arithmetic for an unshifted sole: same bits)
    c.cop -= s;
    c.torque -= Eigen::Vector2d(s.y() * f.z(), -s.x() * f.z());
  }
  return c;
}

}  // namespace flexgait::walking
