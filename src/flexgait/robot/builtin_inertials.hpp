#pragma once
/// \file builtin_inertials.hpp
/// The builtin robot's rigid bodies with THORMANG3's real inertials (thormang3_inertials.hpp), in
/// the builtin twin's body frames (model_xml.hpp; the controller's make_robot_model reads the same):
///
/// - a leg body is one ROBOTIS link, its centre of mass moved from ROBOTIS's link frame to ours by
///   that frame's origin in ours (ROBOTIS puts the hip-roll and ankle-roll frames 0.057 m forward
///   on their x axes, the thigh and ankle-pitch frames 0.033 m and the shank frame 0.093 m outward
///   on their y axes, the foot frame ankle_to_sole − 0.0275 m below the ankle);
/// - the chest (the waist joint's body) is the torso, the head and both arms, rigid: the arms in
///   ROBOTIS's zero pose turned 90° about each shoulder-roll axis, so that they hang at the sides
///   with the forearms forward;
/// - the mass beyond the table's 42.533 kg (batteries and computers, robot.total_mass) goes half to
///   the pelvis and half to the chest, as point masses at the pelvis's and the torso's centres of
///   mass (spec: "put it in the pelvis/torso").
#include <array>

#include "flexgait/robot/robot_params.hpp"

namespace flexgait::humanoid {

struct BodyInertial {
  double mass = 0;                  ///< [kg]
  std::array<double, 3> com{};      ///< in the body frame [m]
  std::array<double, 6> inertia{};  ///< about the centre of mass, body axes: ixx, ixy, ixz, iyy, iyz, izz [kg m^2]
};

struct BuiltinInertials {
  BodyInertial pelvis, chest;
  /// Left, right: hip yaw, hip roll, thigh, shank, ankle pitch, ankle roll, foot.
  std::array<std::array<BodyInertial, 7>, 2> leg;
};

/// Throws std::invalid_argument when robot.total_mass is below the table's sum.
BuiltinInertials builtin_inertials(const RobotParams& robot);

}  // namespace flexgait::humanoid
