#include "flexgait/walking/robot_model_dynamics.hpp"

#include "flexgait/walking/rotation.hpp"

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
    const Vector3d& a = kinematics.axis[i];
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
                      const FootWrenches& feet, double gravity, int first) {
  for (int i = first; i < kBodies; ++i) {
    forward_step(model, kinematics, base, qd, qdd, data, gravity, i);
    // The body's inertial wrench about its origin: F at the centre c, N about it.
    const auto& b = model.bodies[i];
    const Pose& f = kinematics.frame[i];
    const Vector3d& w = data.angular_velocity[i];
    const Vector3d& alpha = data.angular_acceleration[i];
    const Vector3d c = f.R * b.com;
    const Vector3d F = b.mass * (data.acceleration[i] + alpha.cross(c) + w.cross(w.cross(c)));
    // N = R (I ω̇_b + ω_b × I ω_b) with ω_b = Rᵀω, ω̇_b = Rᵀα: the world inertia R I Rᵀ never formed.
    const Vector3d w_body = f.R.transpose() * w;
    const Vector3d N = f.R * (b.inertia * (f.R.transpose() * alpha) + w_body.cross(b.inertia * w_body));
    data.body_wrench[i] = {F, N + c.cross(F)};
  }
  inverse_dynamics_with_feet(model, kinematics, data, feet, first);
}

void inverse_dynamics_with_feet(const RobotModel& model, const RobotModelData& kinematics, RobotDynamicsData& data,
                                const FootWrenches& feet, int first) {
  if (first == 0) {
    data.joint_wrench = data.body_wrench;
    data.tau.fill(0.0);
  } else {
    for (int i = first; i < kBodies; ++i) data.joint_wrench[i] = data.body_wrench[i];
  }
  for (int side = 0; side < 2; ++side)
    if (feet.given[side]) data.joint_wrench[model.foot[side]] = feet.wrench[side];
  // Backward pass: each subtree's wrench onto its parent, moved to the parent's origin.
  for (int i = kBodies - 1; i >= first; --i) {
    const auto& b = model.bodies[i];
    const Wrench& w = data.joint_wrench[i];
    if (b.joint >= 0) data.tau[b.joint] = kinematics.axis[i].dot(w.moment);
    if (b.parent < first) continue;
    Wrench& parent = data.joint_wrench[b.parent];
    parent.force += w.force;
    parent.moment += w.moment + (kinematics.frame[i].p - kinematics.frame[b.parent].p).cross(w.force);
  }
}

}  // namespace flexgait::walking

namespace flexgait::walking {

namespace {

// Spatial vectors in the world frame about a fixed point O (Featherstone 2008, §2): a motion (ω, v), v the
// velocity of the body point at O; a force (n, f), n the moment about O.
using Spatial = Eigen::Matrix<double, 6, 1>;

Spatial spatial(const Vector3d& top, const Vector3d& bottom) {
  Spatial s;
  s << top, bottom;
  return s;
}
/// m₁ × m₂ of two motions.
Spatial cross_motion(const Spatial& a, const Spatial& b) {
  return spatial(a.head<3>().cross(b.head<3>()), a.head<3>().cross(b.tail<3>()) + a.tail<3>().cross(b.head<3>()));
}
/// m ×* f of a motion and a force.
Spatial cross_force(const Spatial& a, const Spatial& f) {
  return spatial(a.head<3>().cross(f.head<3>()) + a.tail<3>().cross(f.tail<3>()), a.head<3>().cross(f.tail<3>()));
}

/// A rigid body's (or a composite's) spatial inertia about O: its mass, first moment h = m c and rotational
/// inertia J about O.
struct SpatialInertia {
  double mass = 0;
  Vector3d h = Vector3d::Zero();
  Matrix3d J = Matrix3d::Zero();
  Spatial operator*(const Spatial& m) const {
    return spatial(J * m.head<3>() + h.cross(m.tail<3>()), mass * m.tail<3>() - h.cross(m.head<3>()));
  }
};

}  // namespace

LegTorqueDerivative inverse_dynamics_derivative(const RobotModel& model, const RobotModelData& kinematics,
                                                const RobotDynamicsData& data, const FootWrenches& feet, int side) {
  constexpr int kChain = 7;  // the leg's six jointed bodies, then the foot (robot_model.hpp's layout)
  const int b0 = 2 + 7 * side;
  const int root = model.bodies[static_cast<std::size_t>(b0)].parent;
  const Vector3d origin = kinematics.frame[static_cast<std::size_t>(root)].p;  // O: conditioning only
  // Body i's spatial velocity V and acceleration A (the time derivative of V, gravity in as the base's upward
  // acceleration) from its origin p's velocity v and acceleration a: V = (ω, v − ω × p), A = (α, a − α × p − ω × v).
  auto motion = [&](int i, Spatial& V, Spatial& A) {
    const auto k = static_cast<std::size_t>(i);
    const Vector3d p = kinematics.frame[k].p - origin;
    const Vector3d& w = data.angular_velocity[k];
    const Vector3d& alpha = data.angular_acceleration[k];
    V = spatial(w, data.velocity[k] - w.cross(p));
    A = spatial(alpha, data.acceleration[k] - alpha.cross(p) - w.cross(data.velocity[k]));
  };
  // Forward: per body the joint's motion subspace S (0 if rigid), V, A, its inertia, and per joint k
  //     W_k = S_k × V_λ(k),   U_k = S_k × A_λ(k) − W_k × V_λ(k),
  // with which turning joint k changes every body m below it by ∂V_m = S_k × V_m − W_k, ∂A_m = S_k × A_m − U_k −
  // W_k × V_m, and its spatial force F_m = I_m A_m + V_m ×* I_m V_m by
  //     ∂F_m = S_k ×* F_m − I_m U_k − B_m W_k,   B_m W = I_m (W × V_m) + W ×* (I_m V_m) + V_m ×* (I_m W)
  // (Carpentier and Mansard 2018, "Analytical derivatives of rigid body dynamics algorithms", RSS, §IV: the
  // terms S_k ×(·) are the rigid turn of everything below k).
  std::array<Spatial, kChain> S, V, A, W, U, force;
  std::array<SpatialInertia, kChain> inertia;
  std::array<int, kChain> role{};
  Spatial V_parent, A_parent;
  motion(root, V_parent, A_parent);
  const bool given = feet.given[static_cast<std::size_t>(side)];
  for (int m = 0; m < kChain; ++m) {
    const int i = b0 + m;
    const auto k = static_cast<std::size_t>(i);
    const auto& b = model.bodies[k];
    const Pose& f = kinematics.frame[k];
    const Vector3d p = f.p - origin;
    role[m] = b.joint >= 0 ? b.joint - humanoid::leg_first_joint(side) : -1;
    if (b.joint >= 0) {
      const Vector3d& u = kinematics.axis[k];
      S[m] = spatial(u, p.cross(u));
    } else {
      S[m].setZero();
    }
    motion(i, V[m], A[m]);
    W[m] = cross_motion(S[m], V_parent);
    U[m] = cross_motion(S[m], A_parent) - cross_motion(W[m], V_parent);
    V_parent = V[m];
    A_parent = A[m];
    const Wrench& n = data.joint_wrench[k];  // the subtree's wrench about p, then about O
    force[m] = spatial(n.moment + p.cross(n.force), n.force);
    if (m == kChain - 1 && given) continue;  // a reading, no inertia below the sensor
    const Vector3d c = p + f.R * b.com;
    inertia[m].mass = b.mass;
    inertia[m].h = b.mass * c;
    inertia[m].J =
        f.R * b.inertia * f.R.transpose() + b.mass * (c.squaredNorm() * Matrix3d::Identity() - c * c.transpose());
  }
  // Backward: the composites below each body, I^c = Σ I_m and B^c = Σ B_m. B_m vanishes on translations and
  // B^c (a, b) = (−P a + a × h_n, 2 a × h_p) with (h_n, h_p) = Σ I_m V_m the composite's momentum and
  //     P = Σ_m [J_m [ω_m×] − [ω_m×] J_m + v_m c̄_mᵀ + c̄_m v_mᵀ − 2 (c̄_m · v_m) 1],   c̄_m = m_m c_m,
  // (V_m = (ω_m, v_m); J_m the rotational inertia about O). Then for joints i, k of the leg (i above or at k:
  // ∂f_i/∂q_k = ∂f_k/∂q_k, the subtree's force derivative; i below k: the rigid turn of i's subtree drops out of
  // S_iᵀ f_i)
  //     ∂τ_i/∂q_k = S_iᵀ (S_k ×* f_k − I^c_k U_k − B^c_k W_k)       (i at or above k),
  //     ∂τ_i/∂q_k = −(I^c_i S_i)ᵀ U_k − (B^cᵀ_i S_i)ᵀ W_k           (i below k).
  SpatialInertia composite;
  Matrix3d P = Matrix3d::Zero();
  Spatial momentum = Spatial::Zero();
  std::array<Spatial, kChain> phi, IS;
  std::array<Vector3d, kChain> BS;  // B^cᵀ S: its linear part is zero
  for (int m = kChain - 1; m >= 0; --m) {
    if (!(m == kChain - 1 && given)) {
      const SpatialInertia& I = inertia[m];
      composite.mass += I.mass;
      composite.h += I.h;
      composite.J += I.J;
      const Vector3d w = V[m].head<3>(), v = V[m].tail<3>();
      const Matrix3d X = I.J * skew(w);
      const Matrix3d Y = v * I.h.transpose();
      P += X + X.transpose() + Y + Y.transpose();
      P.diagonal().array() -= 2 * I.h.dot(v);
      momentum += I * V[m];
    }
    if (role[m] < 0) continue;
    const Vector3d hn = momentum.head<3>(), hp = momentum.tail<3>();
    const Vector3d a = W[m].head<3>();
    const Spatial BW = spatial(-(P * a) + a.cross(hn), 2 * a.cross(hp));
    phi[m] = cross_force(S[m], force[m]) - composite * U[m] - BW;
    IS[m] = composite * S[m];
    const Vector3d sw = S[m].head<3>(), sv = S[m].tail<3>();
    BS[m] = -(P * sw) + hn.cross(sw) + 2 * hp.cross(sv);
  }
  LegTorqueDerivative G = LegTorqueDerivative::Zero();
  for (int i = 0; i < kChain; ++i) {
    if (role[i] < 0) continue;
    for (int k = 0; k < kChain; ++k) {
      if (role[k] < 0) continue;
      G(role[i], role[k]) = i <= k ? S[i].dot(phi[k]) : -IS[i].dot(U[k]) - BS[i].dot(W[k].head<3>());
    }
  }
  return G;
}

}  // namespace flexgait::walking
