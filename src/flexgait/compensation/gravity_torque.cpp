#include "flexgait/compensation/gravity_torque.hpp"

#include <algorithm>

namespace flexgait::compensation {

using walking::Vector3d;

double weight_split(const Eigen::Vector2d& point, const Eigen::Vector2d& left, const Eigen::Vector2d& right) {
  const Eigen::Vector2d span = left - right;
  const double n2 = span.squaredNorm();
  if (n2 < 1e-18) return 0.5;
  return std::clamp((point - right).dot(span) / n2, 0.0, 1.0);  // eq. 5
}

FootLoads support_loads(const Eigen::Vector2d& point, const std::array<walking::Pose, 2>& soles,
                        const std::array<bool, 2>& swinging, const std::array<walking::SolePolygon, 2>& sole_polygon) {
  double mu = 0.5;
  if (swinging[0] != swinging[1])
    mu = swinging[1] ? 1.0 : 0.0;  // single support: all on the stance foot
  else
    mu = weight_split(point, soles[0].p.head<2>(), soles[1].p.head<2>());
  FootLoads loads;
  loads.share = {mu, 1.0 - mu};  // eq. 6
  const Eigen::Vector2d unexplained = point - (mu * soles[0].p.head<2>() + (1.0 - mu) * soles[1].p.head<2>());
  for (int side = 0; side < 2; ++side) {
    const Vector3d local = soles[side].R.transpose() * Vector3d(unexplained.x(), unexplained.y(), 0);
    loads.cop[side] = walking::nearest_point(sole_polygon[static_cast<std::size_t>(side)], local.head<2>());
  }
  return loads;
}

FootLoads com_loads(const walking::RobotModel& model, const walking::RobotModelData& data,
                    const std::array<bool, 2>& swinging) {
  return support_loads(walking::center_of_mass(model, data).head<2>(),
                       {walking::sole_pose(model, data, 0), walking::sole_pose(model, data, 1)}, swinging,
                       model.sole_polygon);
}

humanoid::JointVector gravity_torque(const walking::RobotModel& model, const walking::RobotModelData& data,
                                     const FootLoads& loads, GravityForm form) {
  const double weight = model.total_mass * model.gravity;
  humanoid::JointVector tau{};
  for (int side = 0; side < 2; ++side) {
    walking::LegTorque leg = walking::LegTorque::Zero();
    if (form == GravityForm::kFull) leg = walking::leg_gravity_torque(model, data, side);
    if (loads.share[side] > 0) {
      // Eq. 4: the ground's push F on the foot is carried by the joints as −Jᵀ F.
      const walking::Pose sole = walking::sole_pose(model, data, side);
      const Vector3d point = form == GravityForm::kThesis
                                 ? sole.p
                                 : Vector3d(sole.p + sole.R * Vector3d(loads.cop[side].x(), loads.cop[side].y(), 0));
      const walking::LegJacobian J = walking::leg_jacobian(model, data, side, point);
      leg -= J.topRows<3>().transpose() * Vector3d(0, 0, loads.share[side] * weight);
    }
    for (int i = 0; i < humanoid::kLegJoints; ++i) tau[humanoid::leg_first_joint(side) + i] = leg(i);
  }
  return tau;
}

walking::LegTorqueDerivative gravity_torque_derivative(const walking::RobotModel& model,
                                                       const walking::RobotModelData& data, const FootLoads& loads,
                                                       GravityForm form, int side) {
  const int b0 = 2 + 7 * side;  // the leg's six jointed bodies, then the foot (robot_model.hpp's layout)
  // From the foot up: Σ ψ and Σ ψ x of the loads below each joint, so that Φ_i = Σ ψ x − (Σ ψ) p_i.
  double weight_below = 0;
  Vector3d moment_below = Vector3d::Zero();
  if (loads.share[side] > 0) {
    const walking::Pose sole = walking::sole_pose(model, data, side);
    const Vector3d point = form == GravityForm::kThesis
                               ? sole.p
                               : Vector3d(sole.p + sole.R * Vector3d(loads.cop[side].x(), loads.cop[side].y(), 0));
    const double push = -loads.share[side] * model.total_mass * model.gravity;
    weight_below += push;
    moment_below += push * point;
  }
  std::array<Vector3d, 6> u, phi;
  std::array<int, 6> role{};
  for (int m = 6; m >= 0; --m) {
    const auto& b = model.bodies[static_cast<std::size_t>(b0 + m)];
    if (form == GravityForm::kFull) {
      weight_below += b.mass * model.gravity;
      moment_below += b.mass * model.gravity * data.com_world[static_cast<std::size_t>(b0 + m)];
    }
    if (m == 6) continue;
    const walking::Pose& f = data.frame[static_cast<std::size_t>(b0 + m)];
    u[m] = data.axis[static_cast<std::size_t>(b0 + m)];
    phi[m] = moment_below - weight_below * f.p;
    role[m] = b.joint - humanoid::leg_first_joint(side);
  }
  walking::LegTorqueDerivative G;
  for (int d = 0; d < 6; ++d)
    for (int s = 0; s <= d; ++s) {
      const double g = u[d].z() * u[s].dot(phi[d]) - u[s].dot(u[d]) * phi[d].z();
      G(role[s], role[d]) = G(role[d], role[s]) = g;
    }
  return G;
}

}  // namespace flexgait::compensation
