#include "flexgait/walking/robot_model_dynamics.hpp"

namespace flexgait::walking {

void inverse_dynamics(const RobotModel& model, const RobotModelData& kinematics, const BaseMotion& base,
                      const humanoid::JointVector& qd, const humanoid::JointVector& qdd, RobotDynamicsData& data,
                      const FootWrenches& feet, double gravity) {
  // Forward pass: velocities and accelerations (gravity as the pelvis's upward acceleration).
  for (int i = 0; i < kBodies; ++i) {
    const auto& b = model.bodies[i];
    const Pose& f = kinematics.frame[i];
    if (b.parent < 0) {
      data.angular_velocity[i] = base.angular_velocity;
      data.velocity[i] = base.velocity;
      data.angular_acceleration[i] = base.angular_acceleration;
      data.acceleration[i] = base.acceleration + Vector3d(0, 0, gravity * kGravity);
    } else {
      const int p = b.parent;
      const Vector3d r = f.p - kinematics.frame[p].p;
      const Vector3d& wp = data.angular_velocity[p];
      Vector3d w = wp, alpha = data.angular_acceleration[p];
      if (b.joint >= 0) {
        const Vector3d a = f.R * b.axis;
        w += a * qd[b.joint];
        alpha += a * qdd[b.joint] + wp.cross(a * qd[b.joint]);
      }
      data.angular_velocity[i] = w;
      data.angular_acceleration[i] = alpha;
      data.velocity[i] = data.velocity[p] + wp.cross(r);
      data.acceleration[i] = data.acceleration[p] + data.angular_acceleration[p].cross(r) + wp.cross(wp.cross(r));
    }
    // The body's inertial wrench about its origin: F at the centre c, N about it.
    const Vector3d& w = data.angular_velocity[i];
    const Vector3d& alpha = data.angular_acceleration[i];
    const Vector3d c = f.R * b.com;
    const Vector3d F = b.mass * (data.acceleration[i] + alpha.cross(c) + w.cross(w.cross(c)));
    const Matrix3d I = f.R * b.inertia * f.R.transpose();
    data.joint_wrench[i] = {F, I * alpha + w.cross(I * w) + c.cross(F)};
  }
  for (int side = 0; side < 2; ++side)
    if (feet.given[side]) data.joint_wrench[model.foot[side]] = feet.wrench[side];
  // Backward pass: each subtree's wrench onto its parent, moved to the parent's origin.
  data.tau.fill(0.0);
  for (int i = kBodies - 1; i >= 0; --i) {
    const auto& b = model.bodies[i];
    const Wrench& w = data.joint_wrench[i];
    if (b.joint >= 0) data.tau[b.joint] = (kinematics.frame[i].R * b.axis).dot(w.moment);
    if (b.parent < 0) continue;
    Wrench& parent = data.joint_wrench[b.parent];
    parent.force += w.force;
    parent.moment += w.moment + (kinematics.frame[i].p - kinematics.frame[b.parent].p).cross(w.force);
  }
}

}  // namespace flexgait::walking
