#include "flexgait/walking/planned_motion.hpp"

#include <cmath>
#include <numbers>

#include "flexgait/walking/rotation.hpp"

namespace flexgait::walking {
namespace {

/// The pelvis is placed by Newton's method on its xy with one Jacobian ∂c/∂p (the COM's move
/// per pelvis move, the soles held; ≈ 0.8 I, the legs' links move less than the trunk), taken at
/// a centre pose by differences of this step [m] (and kept while it serves: it changes slowly
/// with the legs' pose); two steps from a guess millimetres off leave < 1e-7 m, and what they
/// leave varies smoothly with s (planned_motion_test).
constexpr double kJacobianStep = 1e-3;
constexpr int kNewtonSteps = 2;

/// The legs' IK for the soles with the pelvis at `pelvis`; with `com`, the model's COM's xy.
void place(const RobotModel& model, RobotModelData& data, const std::array<Pose, 2>& soles, Pose& pelvis,
           humanoid::JointVector& q, Eigen::Vector2d* com) {
  std::array<IkStatus, 2> ik{};
  solve_com_pose(model, data, Eigen::Vector2d::Zero(), soles, pelvis, q, ik, 1, com != nullptr);
  if (com) *com = center_of_mass(model, data).head<2>();
}

}  // namespace

void solve_com_pose(const RobotModel& model, RobotModelData& data, const Eigen::Vector2d& com,
                    const std::array<Pose, 2>& soles, Pose& pelvis, humanoid::JointVector& q,
                    std::array<IkStatus, 2>& ik, int iterations, bool kinematics) {
  for (int it = 0; it < iterations; ++it) {
    for (int side = 0; side < 2; ++side) {
      const Pose local{pelvis.R.transpose() * (soles[side].p - pelvis.p), pelvis.R.transpose() * soles[side].R};
      const IkSolution s = leg_inverse_kinematics(model.leg[side], local);
      ik[side] = s.status;
      for (int i = 0; i < humanoid::kLegJoints; ++i) q[humanoid::leg_first_joint(side) + i] = s.q[i];
    }
    q[humanoid::kWaistYaw] = 0.0;
    if (it + 1 == iterations) break;
    forward_kinematics(model, data, pelvis, q);
    const Vector3d c = center_of_mass(model, data);
    pelvis.p.x() += com.x() - c.x();
    pelvis.p.y() += com.y() - c.y();
  }
  if (kinematics) forward_kinematics(model, data, pelvis, q);
}

double heading_of(const std::array<Pose, 2>& soles) {
  const Vector3d heading = soles[0].R.col(0) + soles[1].R.col(0);
  return std::atan2(heading.y(), heading.x());
}

PlannedMotion planned_motion(const PlanPoseInputs& in, double t, double h, const Pose& guess, RobotModelData& data,
                             Eigen::Matrix2d& inverse, bool refresh) {
  std::array<Pose, 3> pelvis;
  std::array<humanoid::JointVector, 3> q;
  std::array<double, 3> yaw{};
  for (int i : {1, 0, 2}) {  // the centre first: its Jacobian serves all three
    const double s = (i - 1) * h;
    const FeetTarget feet = feet_target(*in.plan, in.swing_height, t + s);
    const Eigen::Vector2d target = Eigen::Vector2d(in.cart[0](0) + s * in.cart[0](1) + 0.5 * s * s * in.cart[0](2),
                                                   in.cart[1](0) + s * in.cart[1](1) + 0.5 * s * s * in.cart[1](2)) +
                                   in.com_offset;
    yaw[i] = heading_of(feet.sole);
    Pose& p = pelvis[i];
    p.R = rot_z(yaw[i]) * in.tilt;
    p.p = guess.p + s * Vector3d(in.cart[0](1), in.cart[1](1), 0.0);
    p.p.z() = in.pelvis_height + feet.floor_z;
    q[i] = {};
    Eigen::Vector2d c;
    place(*in.model, data, feet.sole, p, q[i], &c);
    if (i == 1 && refresh) {
      Eigen::Matrix2d J;
      for (int axis = 0; axis < 2; ++axis) {
        Pose moved = p;
        moved.p(axis) += kJacobianStep;
        Eigen::Vector2d c_moved;
        place(*in.model, data, feet.sole, moved, q[i], &c_moved);
        J.col(axis) = (c_moved - c) / kJacobianStep;
      }
      inverse = J.inverse();
    }
    for (int step = 0; step < kNewtonSteps; ++step) {
      p.p.head<2>() += inverse * (target - c);
      place(*in.model, data, feet.sole, p, q[i], step + 1 < kNewtonSteps ? &c : nullptr);
    }
  }
  PlannedMotion m;
  const double h2 = h * h;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    m.velocity[j] = (q[2][j] - q[0][j]) / (2 * h);
    m.acceleration[j] = (q[2][j] - 2 * q[1][j] + q[0][j]) / h2;
  }
  m.pelvis.velocity = (pelvis[2].p - pelvis[0].p) / (2 * h);
  m.pelvis.acceleration = (pelvis[2].p - 2 * pelvis[1].p + pelvis[0].p) / h2;
  // The heading turns about the world's z (R = R_z(yaw) · tilt, the tilt constant).
  const double up = std::remainder(yaw[2] - yaw[1], 2 * std::numbers::pi);
  const double down = std::remainder(yaw[1] - yaw[0], 2 * std::numbers::pi);
  m.pelvis.angular_velocity = Vector3d(0, 0, (up + down) / (2 * h));
  m.pelvis.angular_acceleration = Vector3d(0, 0, (up - down) / h2);
  m.com_acceleration = Vector3d(in.cart[0](2), in.cart[1](2), 0.0);
  m.valid = true;
  return m;
}

}  // namespace flexgait::walking
