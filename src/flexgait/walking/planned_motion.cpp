#include "flexgait/walking/planned_motion.hpp"

#include <cmath>
#include <numbers>

#include "flexgait/walking/rotation.hpp"

namespace flexgait::walking {
namespace {

/// Fixed-point rounds of each planned pose: from a guess a few millimetres off, the COM's miss
/// shrinks ~50× per round (moving the pelvis moves the COM by all but the legs' share), so four
/// leave < 1e-9 m, 1e-5 rad/s² of the accelerations at h = 0.01 s.
constexpr int kPlanIterations = 5;

}  // namespace

void solve_com_pose(const RobotModel& model, RobotModelData& data, const Eigen::Vector2d& com,
                    const std::array<Pose, 2>& soles, Pose& pelvis, humanoid::JointVector& q,
                    std::array<IkStatus, 2>& ik, int iterations) {
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
  forward_kinematics(model, data, pelvis, q);
}

double heading_of(const std::array<Pose, 2>& soles) {
  const Vector3d heading = soles[0].R.col(0) + soles[1].R.col(0);
  return std::atan2(heading.y(), heading.x());
}

PlannedMotion planned_motion(const PlanPoseInputs& in, double t, double h, const Pose& guess, RobotModelData& data) {
  std::array<Pose, 3> pelvis;
  std::array<humanoid::JointVector, 3> q;
  std::array<double, 3> yaw{};
  std::array<IkStatus, 2> ik{};
  for (int i = 0; i < 3; ++i) {
    const double s = (i - 1) * h;
    const FeetTarget feet = feet_target(*in.plan, in.swing_height, t + s);
    const Eigen::Vector2d com =
        Eigen::Vector2d(in.cart[0](0) + s * in.cart[0](1) + 0.5 * s * s * in.cart[0](2),
                        in.cart[1](0) + s * in.cart[1](1) + 0.5 * s * s * in.cart[1](2)) +
        in.com_offset;
    yaw[i] = heading_of(feet.sole);
    pelvis[i].R = rot_z(yaw[i]) * in.tilt;
    pelvis[i].p = guess.p + s * Vector3d(in.cart[0](1), in.cart[1](1), 0.0);
    pelvis[i].p.z() = in.pelvis_height + feet.floor_z;
    q[i] = {};
    solve_com_pose(*in.model, data, com, feet.sole, pelvis[i], q[i], ik, kPlanIterations);
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
