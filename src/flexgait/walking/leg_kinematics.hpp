#pragma once
/// \file leg_kinematics.hpp
/// Kinematics of one 6-DOF leg (docs/theory/humanoid.md, "The robot"): hip yaw (z), hip roll (x) and
/// hip pitch (y) axes meet at the hip point; knee (y); ankle pitch (y) and roll (x) meet at the
/// ankle point; the sole centre is ankle_to_sole below the ankle in the foot frame (shifted
/// horizontally by sole_shift there). All angles
/// zero: leg straight, foot level, frames aligned with the pelvis.
///
///   R_foot = Rz(q1) Rx(q2) Ry(q3 + q4 + q5) Rx(q6)
///   p_ankle = p_hip + Rz(q1) Rx(q2) [Ry(q3) (0, 0, −thigh) + Ry(q3 + q4) (0, 0, −shank)]
///
/// The inverse is analytic (Kajita et al., "Introduction to Humanoid Robotics", §2.5): the ankle
/// angles and the knee from the hip seen from the foot, then the hip angles from the remaining
/// rotation. A target out of reach is clamped to the nearest reachable pose and flagged.
///
/// A leg as a description file has it: each axis may point either way (sign: +1 along the
/// layout's axis, −1 against it; the analytic solution is taken in the layout's angles s·q and
/// turned back), and the knee bends the way its range allows (the branch whose knee angle has
/// room in the range: forward, knee ≥ 0 in the layout's angles, unless the range only allows the
/// other way).
///
/// A leg of another layout (a loaded description, docs/guide/robot.md: axes not along the layout's, offsets between the
/// hip or ankle axes, the hip or ankle joints in another order from the pelvis) is a general chain of six revolute
/// joints (axes and anchors at zero angles, frames parallel to the pelvis, in the chain's order;
/// role[i] names the joint at chain position i); its inverse is numeric: damped least squares on
/// the sole's pose error (Wampler 1986; Buss 2004),
///   Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e,   e = (p* − p, log(R* Rᵀ)),
/// from the nearest analytic leg's solution (same signs, same knee branch), until |e| < 1e-12; a
/// target it cannot reach is flagged kOutOfReach with clamped_by the remaining position error.
#include <array>
#include <limits>

#include "flexgait/robot/robot_params.hpp"
#include "flexgait/walking/rotation.hpp"

namespace flexgait::walking {

using LegAngles = std::array<double, 6>;  ///< hip yaw, roll, pitch, knee, ankle pitch, roll [rad]

struct LegGeometry {
  Vector3d hip{0, 0.093, -0.093};  ///< hip point in the pelvis frame [m]
  double thigh = 0.3;              ///< [m]
  double shank = 0.3;              ///< [m]
  double ankle_to_sole = 0.1145;   ///< ankle axes (the F/T sensor) to the sole [m]
  /// The sole centre's shift from straight below the ankle, foot frame (x, y; z = 0) [m] (the
  /// builtin's: robot.sole_offset_y outward).
  Vector3d sole_shift = Vector3d::Zero();
  /// The analytic layout above applies; otherwise the general chain below and the numeric IK.
  bool analytic = true;
  std::array<Vector3d, 6> axis{};    ///< general chain: unit joint axes at zero angles (pelvis frame)
  std::array<Vector3d, 6> anchor{};  ///< joint i's anchor from joint i−1's (joint 0: from the pelvis origin) [m]
  Vector3d sole = Vector3d::Zero();  ///< sole centre from joint 6's anchor [m]
  /// General chain: the sole frame's orientation at zero angles (a foot printed slightly tilted:
  /// below 1e-3 rad, RobotModel); identity unless sole_tilted.
  Matrix3d sole_R = Matrix3d::Identity();
  bool sole_tilted = false;
  /// General chain: the joint (LegAngles index: hip yaw, roll, pitch, knee, ankle pitch, roll) at
  /// each position from the pelvis. The three hip joints come first, then the knee, then the ankle's.
  std::array<int, 6> role{0, 1, 2, 3, 4, 5};
  static constexpr double kNoLimit = std::numeric_limits<double>::infinity();
  /// Per joint (LegAngles order): +1 when its axis points along the layout's (z, x, y, y, y, x), −1 against.
  std::array<double, 6> sign{1, 1, 1, 1, 1, 1};
  /// Per joint (LegAngles order): the range [rad]; ±∞ for a joint without one.
  std::array<double, 6> lower{-kNoLimit, -kNoLimit, -kNoLimit, -kNoLimit, -kNoLimit, -kNoLimit};
  std::array<double, 6> upper{kNoLimit, kNoLimit, kNoLimit, kNoLimit, kNoLimit, kNoLimit};

  /// +1 when the knee bends forward (knee ≥ 0 in the layout's angles) within its range, −1 when the
  /// range only allows the other way.
  double knee_branch() const;
};

/// The leg of `side` (0 left, 1 right) of this robot.
LegGeometry leg_geometry(const humanoid::RobotParams& robot, int side);

/// The sole centre's pose in the pelvis frame.
Pose leg_forward_kinematics(const LegGeometry& leg, const LegAngles& q);

enum class IkStatus {
  kOk,
  kOutOfReach,  ///< hip-to-ankle distance beyond thigh + shank: clamped to the straight knee
  kTooClose,    ///< below |thigh − shank|: clamped to the fully folded knee
};

struct IkSolution {
  LegAngles q{};
  IkStatus status = IkStatus::kOk;
  double clamped_by = 0;  ///< how far the ankle target was moved to be reachable [m]
};

/// Joint angles that put the sole centre at `sole` (pelvis frame). The knee on the branch its
/// range allows (LegGeometry::knee_branch; the builtin: knee ≥ 0, forward-bent).
IkSolution leg_inverse_kinematics(const LegGeometry& leg, const Pose& sole);

/// The general chain's forward kinematics (any layout; what the numeric IK inverts).
Pose leg_chain_forward_kinematics(const LegGeometry& leg, const LegAngles& q);
/// The general chain at angles q: the sole's pose and the Jacobian of the sole's twist (the sole
/// centre's velocity, then the angular velocity; pelvis frame) in the joint rates, columns in
/// chain order (LegGeometry::role).
struct LegChainJacobian {
  Pose sole;
  Eigen::Matrix<double, 6, 6> J;
};
LegChainJacobian leg_chain_jacobian(const LegGeometry& leg, const LegAngles& q);
/// Damped least-squares IK of the general chain (used by leg_inverse_kinematics when !analytic).
IkSolution leg_numeric_inverse_kinematics(const LegGeometry& leg, const Pose& sole);

}  // namespace flexgait::walking
