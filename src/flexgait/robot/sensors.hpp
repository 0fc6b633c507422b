#pragma once
/// \file sensors.hpp
/// What the robot's controller can read (docs/theory/humanoid.md, "The robot"): motor-side encoders, the
/// servos' torque from their motor current, the ankle force/torque sensors and the pelvis IMU. The plant fills these; a
/// controller is handed nothing else (no simulator types here).
///
/// Each reading carries the time its values were measured (`stamp`): a reading whose stamp lags
/// the controller's time is stale (a dropped or late sample, sensor_faults.hpp). Readings may be
/// NaN when a sensor fails; a controller must check them (walking/sensor_health.hpp).
#include <array>

#include "flexgait/robot/joints.hpp"

namespace flexgait::humanoid {

struct ForceTorque {
  std::array<double, 3> force{};   ///< on the foot from the leg, in the sensor (foot) frame [N]
  std::array<double, 3> torque{};  ///< [Nm]
  double stamp = 0;                ///< when measured [s]
};

struct Imu {
  std::array<double, 4> quat{1, 0, 0, 0};  ///< AHRS output: pelvis orientation (w, x, y, z), world frame
  std::array<double, 3> gyro{};            ///< angular rate in the pelvis frame [rad/s]
  std::array<double, 3> accel{};           ///< specific force in the pelvis frame [m/s^2] (+g up at rest)
  /// The pelvis's turn since the last reading, as a rotation vector in the pelvis frame, integrated inside the IMU
  /// at its own rate (a strapdown IMU's delta angle; gyro_stamp) [rad]. One rate sample per control period aliases
  /// the rate's ripple at the control frequency (the servos' steps) into a drift; the delta angle does not.
  std::array<double, 3> delta_angle{};
  double quat_stamp = 0, gyro_stamp = 0, accel_stamp = 0;  ///< when measured [s]
};

/// What the robot's controller can read.
struct SensorReadings {
  double t = 0;                 ///< [s]
  JointVector encoder{};        ///< motor-side encoders, quantised [rad]
  JointVector encoder_stamp{};  ///< when each was measured [s]
  /// Each servo's torque from its motor current, at the gear's output, averaged over the control period (the
  /// driver's anti-aliasing before the controller samples it; read with the encoders) [Nm]. It drives the rotor
  /// and the gear: τ_gear = τ_motor − J_m θ̈_m.
  JointVector motor_torque{};
  std::array<ForceTorque, 2> ft;  ///< left, right ankle F/T
  Imu imu;
};

}  // namespace flexgait::humanoid
