#pragma once
/// \file joints.hpp
/// The actuated joints of the THORMANG-class twin (docs/theory/humanoid.md, "The robot"): the waist and
/// six per leg, in this order. Arms and head are rigid.
#include <array>
#include <string_view>

namespace flexgait::humanoid {

inline constexpr int kJoints = 13;
inline constexpr int kLegJoints = 6;

enum Joint : int {
  kWaistYaw = 0,
  kLeftHipYaw,
  kLeftHipRoll,
  kLeftHipPitch,
  kLeftKnee,
  kLeftAnklePitch,
  kLeftAnkleRoll,
  kRightHipYaw,
  kRightHipRoll,
  kRightHipPitch,
  kRightKnee,
  kRightAnklePitch,
  kRightAnkleRoll,
};

inline constexpr std::array<std::string_view, kJoints> kJointNames = {
    "waist_yaw", "l_hip_yaw",  "l_hip_roll",  "l_hip_pitch", "l_knee",        "l_ankle_pitch", "l_ankle_roll",
    "r_hip_yaw", "r_hip_roll", "r_hip_pitch", "r_knee",      "r_ankle_pitch", "r_ankle_roll",
};

/// First joint of a leg (side 0: left, 1: right); the leg's joints follow in kinematic order.
inline constexpr int leg_first_joint(int side) {
  return side == 0 ? kLeftHipYaw : kRightHipYaw;
}
/// Whether a joint is one of a leg's (side 0: left, 1: right).
inline constexpr bool in_leg(int joint, int side) {
  return joint >= leg_first_joint(side) && joint < leg_first_joint(side) + kLegJoints;
}

using JointVector = std::array<double, kJoints>;  ///< one value per actuated joint [rad, Nm, ...]

/// k × scale[j] for every joint (a stiffness with a per-joint factor).
inline JointVector scaled(double k, const JointVector& scale) {
  JointVector out;
  for (int j = 0; j < kJoints; ++j) out[j] = k * scale[j];
  return out;
}

}  // namespace flexgait::humanoid
