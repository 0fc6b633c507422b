#include "flexgait/walking/planned_motion.hpp"

#include <algorithm>
#include <cmath>

#include "flexgait/walking/rotation.hpp"

namespace flexgait::walking {
namespace {

/// The pelvis is placed by Newton's method on its xy with one Jacobian ∂c/∂p (the COM's move
/// per pelvis move, the soles held; ≈ 0.8 I, the legs' links move less than the trunk): the last
/// pose's exact one, or by differences of this step [m] at the guess; it changes slowly with the
/// legs' pose. From a guess millimetres off, three steps at most meet kPlanComTolerance (two leave
/// ~1e-9 m; planned_motion_test); from the last period's pose carried forward by its motion, the guess
/// is micrometres off and one step, or none, meets it.
constexpr double kJacobianStep = 1e-3;
constexpr int kNewtonSteps = 3;

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

PlannedMotion planned_motion(const PlanPoseInputs& in, double t, const Pose& guess, RobotModelData& data,
                             Eigen::Matrix2d& inverse, bool refresh) {
  const RobotModel& model = *in.model;
  // The pose at t: the pelvis's xy by Newton on the COM's miss.
  const FeetTarget feet = feet_target(*in.plan, in.swing_height, t);
  const Eigen::Vector2d target = Eigen::Vector2d(in.cart[0](0), in.cart[1](0)) + in.com_offset;
  Pose p;
  p.R = rot_z(heading_of(feet.sole)) * in.tilt;
  p.p = guess.p;
  p.p.z() = in.pelvis_height + feet.floor_z;
  humanoid::JointVector q{};
  Eigen::Vector2d c;
  place(model, data, feet.sole, p, q, &c);
  if (refresh) {
    Eigen::Matrix2d J;
    for (int axis = 0; axis < 2; ++axis) {
      Pose moved = p;
      moved.p(axis) += kJacobianStep;
      Eigen::Vector2d c_moved;
      place(model, data, feet.sole, moved, q, &c_moved);
      J.col(axis) = (c_moved - c) / kJacobianStep;
    }
    inverse = J.inverse();
    place(model, data, feet.sole, p, q, &c);  // (back to the guess's pose: Newton may take no step)
  }
  for (int step = 0; step < kNewtonSteps && (target - c).lpNorm<Eigen::Infinity>() > kPlanComTolerance; ++step) {
    p.p.head<2>() += inverse * (target - c);
    place(model, data, feet.sole, p, q, &c);  // (the last: the pose's kinematics, for the rates below)
  }
  // Its rates. The pelvis: z on the floor's height, the heading ψ = atan2(h_y, h_x) of h = x₀ + x₁ (the soles'
  // x axes, ẋ = ω × x): ψ̇ = (h × ḣ)_z / |h|², ψ̈ = (h × ḧ)_z / |h|² − 2 ψ̇ (h · ḣ) / |h|² (horizontal parts).
  const FeetMotion fm = feet_motion(*in.plan, in.swing_height, t);
  Vector3d h = Vector3d::Zero(), dh = Vector3d::Zero(), ddh = Vector3d::Zero();
  for (int side = 0; side < 2; ++side) {
    const Vector3d x = feet.sole[side].R.col(0), w = fm.angular_velocity[side];
    h += x;
    dh += w.cross(x);
    ddh += fm.angular_acceleration[side].cross(x) + w.cross(w.cross(x));
  }
  const double h2 = h.x() * h.x() + h.y() * h.y();
  const double yaw_rate = (h.x() * dh.y() - h.y() * dh.x()) / h2;
  const double yaw_acceleration =
      (h.x() * ddh.y() - h.y() * ddh.x()) / h2 - 2 * yaw_rate * (h.x() * dh.x() + h.y() * dh.y()) / h2;
  PlannedMotion m;
  m.pelvis.angular_velocity = Vector3d(0, 0, yaw_rate);  // R = R_z(ψ) · tilt, the tilt constant
  m.pelvis.angular_acceleration = Vector3d(0, 0, yaw_acceleration);
  m.pelvis.velocity = Vector3d(0, 0, fm.floor_velocity);
  m.pelvis.acceleration = Vector3d(0, 0, fm.floor_acceleration);
  // The legs, each sole's twist V = J q̇ + (the pelvis's rigid motion carried to the sole), J the leg's Jacobian
  // of its sole point (robot_model.hpp); the classical accelerations likewise, A = J q̈ + the bias of q̈ = 0. The
  // COM: ċ = v_p + ω_p × (c − p) + Σ J_c q̇ with J_c's column j = a_j × (Σ_{k below j} m_k (c_k − p_j)) / M; the
  // pelvis's unknown horizontal velocity enters through I − Σ J_c J⁻¹[I; 0] (the COM's move per pelvis move with
  // the soles held: the exact form of the Newton's ∂c/∂p), and its acceleration through the same matrix.
  using Matrix6x2 = Eigen::Matrix<double, 6, 2>;
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  std::array<Eigen::PartialPivLU<LegJacobian>, 2> lu;
  std::array<Eigen::Matrix<double, 2, 6>, 2> Jc;  // (the horizontal rows: the COM's height is not held)
  std::array<Matrix6x2, 2> per_pelvis;  // J⁻¹[I; 0] (x and y): the legs' rates per unit pelvis velocity, negated
  std::array<Vector3d, 2> sole;
  Eigen::Matrix2d A = Eigen::Matrix2d::Identity();  // (x and y)
  const Vector3d c_world = center_of_mass(model, data);
  for (int side = 0; side < 2; ++side) {
    sole[side] = sole_pose(model, data, side).p;
    lu[side].compute(leg_jacobian(model, data, side, sole[side]));
    const int b0 = 2 + 7 * side;
    Vector3d moment = Vector3d::Zero();
    double mass = 0;
    for (int i = 6; i >= 0; --i) {
      const auto& b = model.bodies[b0 + i];
      moment += b.mass * data.com_world[b0 + i];
      mass += b.mass;
      if (b.joint < 0) continue;
      const Vector3d& a = data.axis[b0 + i];
      Jc[side].col(b.joint - humanoid::leg_first_joint(side)) =
          a.cross(moment - mass * data.frame[b0 + i].p).head<2>() / model.total_mass;
    }
    for (int axis = 0; axis < 2; ++axis) per_pelvis[side].col(axis) = lu[side].solve(Vector6d::Unit(axis));
    A -= Jc[side] * per_pelvis[side];
  }
  const Eigen::Matrix2d A_inverse = A.inverse();
  // The COM's move per pelvis rotation φ (the origin and the soles held): φ × (c − p) and the legs' rates
  // J⁻¹(−[φ × (s − p); φ]) through J_c (carried_pelvis's next guess).
  for (int k = 0; k < 3; ++k) {
    const Vector3d e = Vector3d::Unit(k);
    Eigen::Vector2d move = e.cross(c_world - p.p).head<2>();
    for (int side = 0; side < 2; ++side) {
      Vector6d turn;
      turn << -e.cross(sole[side] - p.p), -e;
      move += Jc[side] * lu[side].solve(turn);
    }
    m.com_per_rotation.col(k) = move;
  }
  // Velocities: q̇ = J⁻¹(V_s − [v_p + ω_p × (s − p); ω_p]), v_p = (v_xy, ż) with v_xy from the COM's ċ.
  const Vector3d& wp = m.pelvis.angular_velocity;
  std::array<Vector6d, 2> rate0;  // with v_xy = 0
  Eigen::Vector2d c_dot0 = (m.pelvis.velocity + wp.cross(c_world - p.p)).head<2>();
  for (int side = 0; side < 2; ++side) {
    Vector6d V;
    V << fm.velocity[side] - m.pelvis.velocity - wp.cross(sole[side] - p.p), fm.angular_velocity[side] - wp;
    rate0[side] = lu[side].solve(V);
    c_dot0 += Jc[side] * rate0[side];
  }
  const Eigen::Vector2d v_xy = A_inverse * (Eigen::Vector2d(in.cart[0](1), in.cart[1](1)) - c_dot0);
  m.pelvis.velocity.head<2>() = v_xy;
  for (int side = 0; side < 2; ++side) {
    const Vector6d rate = rate0[side] - per_pelvis[side] * v_xy;
    for (int i = 0; i < humanoid::kLegJoints; ++i) m.velocity[humanoid::leg_first_joint(side) + i] = rate(i);
  }
  // Accelerations: the bias (q̈ = 0, the pelvis's horizontal acceleration 0) by the model's forward pass, the COM's
  // Σ m_i (a_i + α_i × c_i + ω_i × (ω_i × c_i)) / M with c_i the centre from the origin.
  RobotDynamicsData dyn;
  forward_motion(model, data, m.pelvis, m.velocity, humanoid::JointVector{}, dyn, 0.0);
  Vector3d c_ddot = Vector3d::Zero();
  for (int i = 0; i < kBodies; ++i) {
    const Vector3d c = data.com_world[i] - data.frame[i].p, &w = dyn.angular_velocity[i];
    c_ddot += model.bodies[i].mass * (dyn.acceleration[i] + dyn.angular_acceleration[i].cross(c) + w.cross(w.cross(c)));
  }
  Eigen::Vector2d c_ddot0 = c_ddot.head<2>() / model.total_mass;
  std::array<Vector6d, 2> accel0;
  for (int side = 0; side < 2; ++side) {
    const int foot = model.foot[side];
    const Vector3d r = sole[side] - data.frame[foot].p;
    const Vector3d& w = dyn.angular_velocity[foot];
    const Vector3d& alpha = dyn.angular_acceleration[foot];
    Vector6d bias;
    bias << dyn.acceleration[foot] + alpha.cross(r) + w.cross(w.cross(r)), alpha;
    Vector6d a;
    a << fm.acceleration[side], fm.angular_acceleration[side];
    accel0[side] = lu[side].solve(a - bias);
    c_ddot0 += Jc[side] * accel0[side];
  }
  const Eigen::Vector2d a_xy = A_inverse * (Eigen::Vector2d(in.cart[0](2), in.cart[1](2)) - c_ddot0);
  m.pelvis.acceleration.head<2>() = a_xy;
  for (int side = 0; side < 2; ++side) {
    const Vector6d accel = accel0[side] - per_pelvis[side] * a_xy;
    for (int i = 0; i < humanoid::kLegJoints; ++i) m.acceleration[humanoid::leg_first_joint(side) + i] = accel(i);
  }
  m.com_position = Vector3d(target.x(), target.y(), 0.0);
  m.com_velocity = Vector3d(in.cart[0](1), in.cart[1](1), 0.0);
  m.com_acceleration = Vector3d(in.cart[0](2), in.cart[1](2), 0.0);
  m.pelvis_position = p.p;
  m.pelvis_attitude = p.R;
  m.valid = std::all_of(m.acceleration.begin(), m.acceleration.end(), [](double a) { return std::isfinite(a); }) &&
            A_inverse.allFinite();
  if (!m.valid) return PlannedMotion{};  // a singular leg (a straight knee): no motion to give
  inverse = A_inverse;                   // (∂c/∂p)⁻¹ at this pose, for the next
  return m;
}

Vector3d carried_pelvis(const PlannedMotion& last, double T, const Eigen::Vector2d& com, const Matrix3d& attitude,
                        const Eigen::Matrix2d& inverse) {
  Vector3d p = last.pelvis_position + T * last.pelvis.velocity + 0.5 * T * T * last.pelvis.acceleration;
  const Vector3d carried_com = last.com_position + T * last.com_velocity + 0.5 * T * T * last.com_acceleration;
  const double heading_turn = T * last.pelvis.angular_velocity.z() + 0.5 * T * T * last.pelvis.angular_acceleration.z();
  const Vector3d phi = rotation_vector(attitude * (rot_z(heading_turn) * last.pelvis_attitude).transpose());
  p.head<2>() += inverse * (com - carried_com.head<2>() - last.com_per_rotation * phi);
  return p;
}

}  // namespace flexgait::walking
