#include "flexgait/walking/robot_model_dynamics.hpp"

namespace flexgait::walking {

namespace {

/// Body i's velocities and accelerations from its parent's (gravity as the pelvis's upward acceleration).
[[gnu::always_inline]] inline void forward_step(const RobotModel& model, const RobotModelData& kinematics,
                                                const BaseMotion& base, const humanoid::JointVector& qd,
                                                const humanoid::JointVector& qdd, RobotDynamicsData& data,
                                                double gravity, int i) {
  const auto& b = model.bodies[i];
  const Pose& f = kinematics.frame[i];
  if (b.parent < 0) {
    data.angular_velocity[i] = base.angular_velocity;
    data.velocity[i] = base.velocity;
    data.angular_acceleration[i] = base.angular_acceleration;
    data.acceleration[i] = base.acceleration + Vector3d(0, 0, gravity * model.gravity);
    return;
  }
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

}  // namespace

void forward_motion(const RobotModel& model, const RobotModelData& kinematics, const BaseMotion& base,
                    const humanoid::JointVector& qd, const humanoid::JointVector& qdd, RobotDynamicsData& data,
                    double gravity) {
  for (int i = 0; i < kBodies; ++i) forward_step(model, kinematics, base, qd, qdd, data, gravity, i);
}

void inverse_dynamics(const RobotModel& model, const RobotModelData& kinematics, const BaseMotion& base,
                      const humanoid::JointVector& qd, const humanoid::JointVector& qdd, RobotDynamicsData& data,
                      const FootWrenches& feet, double gravity) {
  for (int i = 0; i < kBodies; ++i) {
    forward_step(model, kinematics, base, qd, qdd, data, gravity, i);
    // The body's inertial wrench about its origin: F at the centre c, N about it.
    const auto& b = model.bodies[i];
    const Pose& f = kinematics.frame[i];
    const Vector3d& w = data.angular_velocity[i];
    const Vector3d& alpha = data.angular_acceleration[i];
    const Vector3d c = f.R * b.com;
    const Vector3d F = b.mass * (data.acceleration[i] + alpha.cross(c) + w.cross(w.cross(c)));
    const Matrix3d I = f.R * b.inertia * f.R.transpose();
    data.body_wrench[i] = {F, I * alpha + w.cross(I * w) + c.cross(F)};
  }
  inverse_dynamics_with_feet(model, kinematics, data, feet);
}

void inverse_dynamics_with_feet(const RobotModel& model, const RobotModelData& kinematics, RobotDynamicsData& data,
                                const FootWrenches& feet) {
  data.joint_wrench = data.body_wrench;
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

namespace flexgait::walking {

LegTorqueDerivative inverse_dynamics_derivative(const RobotModel& model, const RobotModelData& kinematics,
                                                const humanoid::JointVector& qd, const humanoid::JointVector& qdd,
                                                const RobotDynamicsData& data, const FootWrenches& feet, int side) {
  constexpr int kChain = 7;  // the leg's six jointed bodies, then the foot (robot_model.hpp's layout)
  const int b0 = 2 + 7 * side;
  // The primal pass's quantities per body of the chain: world axis u (0 if rigid), r = p_m − p_parent,
  // c = R com, the joint's rate and acceleration, the parent's ω and α, the body's own force F.
  std::array<Vector3d, kChain> u, r, c, w_parent, alpha_parent, force, Iw, Ialpha;
  std::array<Matrix3d, kChain> inertia;  // world frame, about the centre of mass
  std::array<double, kChain> rate{}, accel{};
  std::array<int, kChain> role{};
  for (int m = 0; m < kChain; ++m) {
    const int i = b0 + m;
    const auto& b = model.bodies[static_cast<std::size_t>(i)];
    const Pose& f = kinematics.frame[static_cast<std::size_t>(i)];
    u[m] = b.joint >= 0 ? Vector3d(f.R * b.axis) : Vector3d::Zero();
    rate[m] = b.joint >= 0 ? qd[b.joint] : 0.0;
    accel[m] = b.joint >= 0 ? qdd[b.joint] : 0.0;
    role[m] = b.joint >= 0 ? b.joint - humanoid::leg_first_joint(side) : -1;
    r[m] = f.p - kinematics.frame[static_cast<std::size_t>(b.parent)].p;
    c[m] = f.R * b.com;
    w_parent[m] = data.angular_velocity[static_cast<std::size_t>(b.parent)];
    alpha_parent[m] = data.angular_acceleration[static_cast<std::size_t>(b.parent)];
    const Vector3d& w = data.angular_velocity[static_cast<std::size_t>(i)];
    const Vector3d& alpha = data.angular_acceleration[static_cast<std::size_t>(i)];
    force[m] = b.mass * (data.acceleration[static_cast<std::size_t>(i)] + alpha.cross(c[m]) + w.cross(w.cross(c[m])));
    inertia[m] = f.R * b.inertia * f.R.transpose();
    Iw[m] = inertia[m] * w;
    Ialpha[m] = inertia[m] * alpha;
  }
  const bool given = feet.given[static_cast<std::size_t>(side)];
  LegTorqueDerivative G = LegTorqueDerivative::Zero();
  std::array<Vector3d, kChain> dF, dN, dr;
  for (int k = 0; k < kChain - 1; ++k) {
    if (role[k] < 0) continue;
    const Vector3d& uk = u[k];
    // Forward: the tangents of the parent's ω, α and origin acceleration (zero above k).
    Vector3d dw = Vector3d::Zero(), dalpha = Vector3d::Zero(), da = Vector3d::Zero();
    for (int m = k; m < kChain; ++m) {
      const int i = b0 + m;
      const auto& b = model.bodies[static_cast<std::size_t>(i)];
      const Vector3d du = m > k ? Vector3d(uk.cross(u[m])) : Vector3d::Zero();
      dr[m] = m > k ? Vector3d(uk.cross(r[m])) : Vector3d::Zero();
      const Vector3d& wp = w_parent[m];
      da += dalpha.cross(r[m]) + alpha_parent[m].cross(dr[m]) + dw.cross(wp.cross(r[m])) +
            wp.cross(dw.cross(r[m]) + wp.cross(dr[m]));
      dalpha += du * accel[m] + dw.cross(u[m] * rate[m]) + wp.cross(du * rate[m]);
      dw += du * rate[m];
      if (m == kChain - 1 && given) {  // the reading turns with the foot
        dF[m] = uk.cross(feet.wrench[static_cast<std::size_t>(side)].force);
        dN[m] = uk.cross(feet.wrench[static_cast<std::size_t>(side)].moment);
        continue;
      }
      const Vector3d& w = data.angular_velocity[static_cast<std::size_t>(i)];
      const Vector3d& alpha = data.angular_acceleration[static_cast<std::size_t>(i)];
      const Vector3d dc = uk.cross(c[m]);
      dF[m] = b.mass * (da + dalpha.cross(c[m]) + alpha.cross(dc) + dw.cross(w.cross(c[m])) +
                        w.cross(dw.cross(c[m]) + w.cross(dc)));
      // δ(I x) = δI x + I δx with δI x = u_k × (I x) − I (u_k × x).
      const Vector3d dIalpha = uk.cross(Ialpha[m]) + inertia[m] * (dalpha - uk.cross(alpha));
      const Vector3d dIw = uk.cross(Iw[m]) + inertia[m] * (dw - uk.cross(w));
      dN[m] = dIalpha + dw.cross(Iw[m]) + w.cross(dIw) + dc.cross(force[m]) + c[m].cross(dF[m]);
    }
    // Backward: the subtree wrench's tangent (δf, δn about p_m), up to the leg's first body.
    Vector3d df = Vector3d::Zero(), dn = Vector3d::Zero();
    for (int m = kChain - 1; m >= 0; --m) {
      if (m < kChain - 1) {
        const Vector3d& f_child = data.joint_wrench[static_cast<std::size_t>(b0 + m + 1)].force;
        dn += (m + 1 > k ? Vector3d(dr[m + 1].cross(f_child)) : Vector3d::Zero()) + r[m + 1].cross(df);
      }
      if (m >= k) {
        df += dF[m];
        dn += dN[m];
      }
      if (role[m] < 0) continue;
      const Vector3d du = m > k ? Vector3d(uk.cross(u[m])) : Vector3d::Zero();
      G(role[m], role[k]) = du.dot(data.joint_wrench[static_cast<std::size_t>(b0 + m)].moment) + u[m].dot(dn);
    }
  }
  return G;
}

}  // namespace flexgait::walking
