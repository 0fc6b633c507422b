#pragma once
/// \file sensor_ids.hpp
/// The robot's sensors by name (what a controller's health checks report on) and its joints by
/// name as configuration values. How the twin's sensors fail is the twin's (twin/sensor_faults.hpp).
#include <array>
#include <string_view>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/robot/joints.hpp"

namespace flexgait::humanoid {

/// The joints by name (e.g. the key plant.faults.encoder.joint).
constexpr std::array<EnumName<Joint>, kJoints> enum_names(Joint) {
  return {{{kWaistYaw, kJointNames[0]},
           {kLeftHipYaw, kJointNames[1]},
           {kLeftHipRoll, kJointNames[2]},
           {kLeftHipPitch, kJointNames[3]},
           {kLeftKnee, kJointNames[4]},
           {kLeftAnklePitch, kJointNames[5]},
           {kLeftAnkleRoll, kJointNames[6]},
           {kRightHipYaw, kJointNames[7]},
           {kRightHipRoll, kJointNames[8]},
           {kRightHipPitch, kJointNames[9]},
           {kRightKnee, kJointNames[10]},
           {kRightAnklePitch, kJointNames[11]},
           {kRightAnkleRoll, kJointNames[12]}}};
}

/// The robot's sensors, in this order (names as in the keys plant.faults.<name>.*).
enum SensorId : int { kFtLeft = 0, kFtRight, kGyro, kAccel, kAhrs, kEncoder, kSensors };
inline constexpr std::array<std::string_view, kSensors> kSensorNames = {"ft_left", "ft_right", "gyro",
                                                                        "accel",   "ahrs",     "encoder"};

}  // namespace flexgait::humanoid
