#include "flexgait/walking/leg_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flexgait::walking {

LegGeometry leg_geometry(const humanoid::RobotParams& r, int side) {
  LegGeometry g;
  g.hip = Vector3d(0, side == 0 ? r.hip_yaw_offset_y : -r.hip_yaw_offset_y, -r.hip_axes_depth);
  g.thigh = r.thigh;
  g.shank = r.shank;
  g.ankle_to_sole = r.ankle_to_sole;
  return g;
}

Pose leg_forward_kinematics(const LegGeometry& leg, const LegAngles& q) {
  const Matrix3d Rh = rot_z(q[0]) * rot_x(q[1]);
  const Vector3d down = -Vector3d::UnitZ();
  Pose sole;
  sole.R = Rh * rot_y(q[2] + q[3] + q[4]) * rot_x(q[5]);
  const Vector3d ankle = leg.hip + Rh * (rot_y(q[2]) * (leg.thigh * down) + rot_y(q[2] + q[3]) * (leg.shank * down));
  sole.p = ankle + sole.R * (leg.ankle_to_sole * down);
  return sole;
}

IkSolution leg_inverse_kinematics(const LegGeometry& leg, const Pose& sole) {
  IkSolution out;
  const double A = leg.thigh, B = leg.shank;
  const Vector3d ankle = sole.p + sole.R * Vector3d(0, 0, leg.ankle_to_sole);
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
  auto& q = out.q;
  // Knee from the law of cosines: C² = A² + B² + 2AB cos q4.
  q[3] = std::acos(std::clamp((C * C - A * A - B * B) / (2 * A * B), -1.0, 1.0));
  // Ankle roll: (r_y, r_z) = v_z (sin q6, cos q6). Of the two solutions take |q6| ≤ π/2 (v_z < 0
  // only when the hip is below the ankle in the foot frame).
  q[5] = std::atan(r.y() / r.z());
  if (!std::isfinite(q[5])) q[5] = std::copysign(0.5 * std::numbers::pi, r.y());
  const double vx = r.x(), vz = r.y() * std::sin(q[5]) + r.z() * std::cos(q[5]);
  // (v_x, v_z) is (−A sin q4, A cos q4 + B) rotated by −q5 about y.
  q[4] = std::atan2(-A * std::sin(q[3]), A * std::cos(q[3]) + B) - std::atan2(vx, vz);
  // Rz(q1) Rx(q2) Ry(q3) = R_foot Rx(q6)ᵀ Ry(q4 + q5)ᵀ.
  const Matrix3d M = sole.R * rot_x(-q[5]) * rot_y(-(q[3] + q[4]));
  q[0] = std::atan2(-M(0, 1), M(1, 1));
  q[1] = std::atan2(M(2, 1), -M(0, 1) * std::sin(q[0]) + M(1, 1) * std::cos(q[0]));
  q[2] = std::atan2(-M(2, 0), M(2, 2));
  return out;
}

}  // namespace flexgait::walking
