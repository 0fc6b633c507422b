#include "flexgait/walking/leg_kinematics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace flexgait::walking {

LegGeometry leg_geometry(const humanoid::RobotParams& r, int side) {
  LegGeometry g;
  g.hip = Vector3d(0, side == 0 ? r.hip_yaw_offset_y : -r.hip_yaw_offset_y, -r.hip_axes_depth);
  g.thigh = r.thigh;
  g.shank = r.shank;
  g.ankle_to_sole = r.ankle_to_sole;
  g.sole_shift = Vector3d(0, side == 0 ? r.sole_offset_y : -r.sole_offset_y, 0);
  return g;
}

double LegGeometry::knee_branch() const {
  // The knee's range in the layout's angles (s·q): forward unless it leaves more room backward.
  const double a = sign[3] * lower[3], b = sign[3] * upper[3];
  return std::max(a, b) >= -std::min(a, b) ? 1.0 : -1.0;
}

Pose leg_forward_kinematics(const LegGeometry& leg, const LegAngles& q_file) {
  if (!leg.analytic) return leg_chain_forward_kinematics(leg, q_file);
  LegAngles q;  // the layout's angles
  for (std::size_t i = 0; i < 6; ++i) q[i] = leg.sign[i] * q_file[i];
  const Matrix3d Rh = rot_z(q[0]) * rot_x(q[1]);
  const Vector3d down = -Vector3d::UnitZ();
  Pose sole;
  sole.R = Rh * rot_y(q[2] + q[3] + q[4]) * rot_x(q[5]);
  const Vector3d ankle = leg.hip + Rh * (rot_y(q[2]) * (leg.thigh * down) + rot_y(q[2] + q[3]) * (leg.shank * down));
  sole.p = ankle + sole.R * (leg.ankle_to_sole * down + leg.sole_shift);
  return sole;
}

Pose leg_chain_forward_kinematics(const LegGeometry& leg, const LegAngles& q) {
  Pose f;
  for (std::size_t i = 0; i < 6; ++i) {
    f.p += f.R * leg.anchor[i];
    f.R = f.R * Eigen::AngleAxisd(q[static_cast<std::size_t>(leg.role[i])], leg.axis[i]).toRotationMatrix();
  }
  f.p += f.R * leg.sole;
  if (leg.sole_tilted) f.R = f.R * leg.sole_R;
  return f;
}

LegChainJacobian leg_chain_jacobian(const LegGeometry& leg, const LegAngles& q) {
  LegChainJacobian out;
  // Frames of the joints and the sole.
  std::array<Pose, 6> frame;
  Pose f;
  for (std::size_t i = 0; i < 6; ++i) {
    f.p += f.R * leg.anchor[i];
    frame[i] = f;
    f.R = f.R * Eigen::AngleAxisd(q[static_cast<std::size_t>(leg.role[i])], leg.axis[i]).toRotationMatrix();
  }
  const Vector3d p = f.p + f.R * leg.sole;
  if (leg.sole_tilted) f.R = f.R * leg.sole_R;
  out.sole = {p, f.R};
  for (int i = 0; i < 6; ++i) {
    const Pose& fi = frame[static_cast<std::size_t>(i)];
    const Vector3d a = fi.R * leg.axis[static_cast<std::size_t>(i)];
    out.J.block<3, 1>(0, i) = a.cross(p - fi.p);
    out.J.block<3, 1>(3, i) = a;
  }
  return out;
}

IkSolution leg_numeric_inverse_kinematics(const LegGeometry& leg, const Pose& sole) {
  IkSolution out;
  LegAngles& q = out.q;
  // Start from the analytic solution of the nearest analytic leg (hip at the first three anchors,
  // thigh and shank as the chain's lengths, the sole where it is from the last anchor): the forward-bent branch, a few
  // Newton steps away.
  LegGeometry near;
  near.hip = leg.anchor[0] + leg.anchor[1] + leg.anchor[2];
  near.thigh = leg.anchor[3].norm();
  near.shank = leg.anchor[4].norm();
  const Vector3d to_sole = leg.anchor[5] + leg.sole;  // from the last joint's anchor
  near.ankle_to_sole = -to_sole.z();
  near.sole_shift = Vector3d(to_sole.x(), to_sole.y(), 0);
  near.sign = leg.sign;  // the same knee branch, in the file's angles
  near.lower = leg.lower;
  near.upper = leg.upper;
  q = leg_inverse_kinematics(near, sole).q;
  constexpr double kLambda2 = 1e-4;  // damping λ² far from the target: bounds steps near singularities
  constexpr double kMaxStep = 0.2;   // largest joint step per iteration [rad]
  constexpr int kIterations = 100;
  Eigen::Matrix<double, 6, 1> e;
  for (int it = 0; it < kIterations; ++it) {
    const LegChainJacobian now = leg_chain_jacobian(leg, q);
    const Eigen::AngleAxisd w(Matrix3d(sole.R * now.sole.R.transpose()));
    e.head<3>() = sole.p - now.sole.p;
    e.tail<3>() = w.angle() * w.axis();
    if (e.norm() < 1e-12) return out;
    const Eigen::Matrix<double, 6, 6>& J = now.J;
    // Undamped near the solution (exact Newton steps), damped far from it.
    const double lambda2 = e.norm() > 1e-4 ? kLambda2 : 0.0;
    Eigen::Matrix<double, 6, 1> dq =
        J.transpose() * (J * J.transpose() + lambda2 * Eigen::Matrix<double, 6, 6>::Identity()).ldlt().solve(e);
    if (dq.cwiseAbs().maxCoeff() > kMaxStep) dq *= kMaxStep / dq.cwiseAbs().maxCoeff();
    for (int i = 0; i < 6; ++i) q[static_cast<std::size_t>(leg.role[static_cast<std::size_t>(i)])] += dq(i);
  }
  out.status = IkStatus::kOutOfReach;
  out.clamped_by = e.head<3>().norm();
  return out;
}

IkSolution leg_inverse_kinematics(const LegGeometry& leg, const Pose& sole) {
  if (!leg.analytic) return leg_numeric_inverse_kinematics(leg, sole);
  IkSolution out;
  const double A = leg.thigh, B = leg.shank;
  const Vector3d ankle = sole.p + sole.R * (Vector3d(0, 0, leg.ankle_to_sole) - leg.sole_shift);
  // The hip seen from the foot: r = R_footᵀ (p_hip − p_ankle) = Rx(−q6) v, v = (v_x, 0, v_z).
  Vector3d r = sole.R.transpose() * (leg.hip - ankle);
  double C = r.norm();
  const double c_max = A + B, c_min = std::abs(A - B) + 1e-9;
  if (C > c_max) {
    out.status = IkStatus::kOutOfReach;
    out.clamped_by = C - c_max;
    r *= c_max / C;
    C = c_max;
  } else if (C < c_min) {
    out.status = IkStatus::kTooClose;
    out.clamped_by = c_min - C;
    r *= c_min / std::max(C, 1e-12);
    C = c_min;
  }
  auto& q = out.q;  // the layout's angles, turned into the file's at the end
  // The angles' sines and cosines come from the same algebra as the angles (no sin or cos of an angle just
  // found: a leg's IK was ~10 % of the walking loop's own time, most of it in libm).
  // Knee from the law of cosines: C² = A² + B² + 2AB cos q4, on the branch the range allows.
  const double knee = leg.knee_branch();
  const double c3 = std::clamp((C * C - A * A - B * B) / (2 * A * B), -1.0, 1.0);
  const double s3 = knee * std::sqrt((1 - c3) * (1 + c3));
  q[3] = knee * std::acos(c3);
  // Ankle roll: (r_y, r_z) = v_z (sin q6, cos q6). Of the two solutions take |q6| ≤ π/2 (v_z < 0
  // only when the hip is below the ankle in the foot frame): cos q6 = |r_z| / h, sin q6 = sgn(r_z) r_y / h.
  q[5] = std::atan(r.y() / r.z());
  if (!std::isfinite(q[5])) q[5] = std::copysign(0.5 * std::numbers::pi, r.y());
  const double h = std::sqrt(r.y() * r.y() + r.z() * r.z());
  const double c6 = h > 0 ? std::abs(r.z()) / h : 0.0;
  const double s6 = h > 0 ? std::copysign(1.0, r.z()) * r.y() / h : std::copysign(1.0, r.y());
  const double vx = r.x(), vz = r.y() * s6 + r.z() * c6;
  // (v_x, v_z) is (−A sin q4, A cos q4 + B) rotated by −q5 about y: q5 = α − β, α the angle of
  // (A cos q4 + B, −A sin q4), β that of (v_z, v_x).
  const double ax = A * c3 + B, ay = -A * s3;
  q[4] = std::atan2(ay, ax) - std::atan2(vx, vz);
  // cos and sin of q4 + q5 = q4 + α − β, the product of the unit vectors (cos, sin) of q4 and α with β's conjugate.
  // (The unit vector of atan2(y, x): (1, 0) at the origin, where atan2 is 0.)
  const auto unit = [](double x, double y) {
    const double n = std::sqrt(x * x + y * y);
    return n > 0 ? std::array<double, 2>{x / n, y / n} : std::array<double, 2>{1.0, 0.0};
  };
  const auto [ca, sa] = unit(ax, ay);
  const auto [cb, sb] = unit(vz, vx);
  const double c4a = c3 * ca - s3 * sa, s4a = c3 * sa + s3 * ca;  // q4 + α
  const double c45 = c4a * cb + s4a * sb, s45 = s4a * cb - c4a * sb;
  // Rz(q1) Rx(q2) Ry(q3) = R_foot Rx(q6)ᵀ Ry(q4 + q5)ᵀ.
  Matrix3d Rx6, Ry45;
  Rx6 << 1, 0, 0, 0, c6, s6, 0, -s6, c6;
  Ry45 << c45, 0, -s45, 0, 1, 0, s45, 0, c45;
  const Matrix3d M = sole.R * Rx6 * Ry45;
  // q1 = atan2(−M01, M11); then −M01 sin q1 + M11 cos q1 = √(M01² + M11²).
  q[0] = std::atan2(-M(0, 1), M(1, 1));
  q[1] = std::atan2(M(2, 1), std::sqrt(M(0, 1) * M(0, 1) + M(1, 1) * M(1, 1)));
  q[2] = std::atan2(-M(2, 0), M(2, 2));
  for (std::size_t i = 0; i < 6; ++i) q[i] *= leg.sign[i];
  return out;
}

}  // namespace flexgait::walking
