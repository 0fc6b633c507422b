#pragma once
/// \file sensors.hpp
/// What the robot's controller can read (spec humanoid.md, "Sensors"): motor-side encoders, the
/// ankle force/torque sensors and the pelvis IMU. The plant fills these; a controller is handed
/// nothing else (no simulator types here).
#include <array>

#include "flexgait/humanoid/joints.hpp"

namespace flexgait::humanoid {

struct ForceTorque {
  std::array<double, 3> force{};   ///< on the foot from the leg, in the sensor (foot) frame [N]
  std::array<double, 3> torque{};  ///< [Nm]
};

struct Imu {
  std::array<double, 4> quat{1, 0, 0, 0};  ///< pelvis orientation (w, x, y, z), world frame
  std::array<double, 3> gyro{};            ///< angular rate in the pelvis frame [rad/s]
  std::array<double, 3> accel{};           ///< specific force in the pelvis frame [m/s^2]
};

/// What the robot's controller can read.
struct SensorReadings {
  double t = 0;                   ///< [s]
  JointVector encoder{};          ///< motor-side encoders, quantised [rad]
  std::array<ForceTorque, 2> ft;  ///< left, right ankle F/T
  Imu imu;
};

}  // namespace flexgait::humanoid
