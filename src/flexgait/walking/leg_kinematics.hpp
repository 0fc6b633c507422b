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
/// A leg of another layout (a loaded description, docs/guide/robot.md) is a general chain of six revolute
/// joints (axes and anchors at zero angles, frames parallel to the pelvis); its inverse is
/// numeric: damped least squares on the sole's pose error (Wampler 1986; Buss 2004),
///   Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e,   e = (p* − p, log(R* Rᵀ)),
/// from a bent-knee start, until |e| < 1e-12; a target it cannot reach is flagged kOutOfReach
/// with clamped_by the remaining position error.
#include <array>

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

/// Joint angles that put the sole centre at `sole` (pelvis frame). Knee ≥ 0 (forward-bent).
IkSolution leg_inverse_kinematics(const LegGeometry& leg, const Pose& sole);

/// The general chain's forward kinematics (any layout; what the numeric IK inverts).
Pose leg_chain_forward_kinematics(const LegGeometry& leg, const LegAngles& q);
/// Damped least-squares IK of the general chain (used by leg_inverse_kinematics when !analytic).
IkSolution leg_numeric_inverse_kinematics(const LegGeometry& leg, const Pose& sole);

}  // namespace flexgait::walking
