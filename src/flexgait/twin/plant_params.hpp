#pragma once
/// \file plant_params.hpp
/// The twin's truth: its elastic actuators, sensors and their faults, the floor and the timing
/// (docs/theory/humanoid.md, "The elastic actuator (plant)"). SI units. A controller is told none
/// of it.
#include <cmath>
#include <string>

#include "flexgait/core/config.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/robot/joints.hpp"
#include "flexgait/twin/sensor_faults.hpp"
#include "flexgait/twin/terrain.hpp"

namespace flexgait::twin {

/// The elastic gear actuators, the sensors and the timing of the twin.
struct PlantParams {
  double k_joint = 1000.0;              ///< true gear stiffness [Nm/rad], times k_scale per joint
  humanoid::JointVector k_scale = [] {  ///< factor on k_joint for each joint
    humanoid::JointVector ones;
    ones.fill(1.0);
    return ones;
  }();
  double gear_damping = 80.0;   ///< d [Nm s/rad], integrated implicitly by MuJoCo
  double backlash = 0.0;        ///< dead band, total width [rad]
  double torque_limit = 100.0;  ///< servo torque limit [Nm]
  /// Each joint's own servo torque limit [Nm], 0: torque_limit. Not a key: a loaded robot's file limits
  /// (walk_experiment.cpp, docs/guide/robot.md "Torque limits"); all 0 for the builtin.
  humanoid::JointVector joint_torque_limit{};
  double rotor_inertia = 0.8;        ///< reflected rotor inertia [kg m^2]
  double servo_bandwidth = 30.0;     ///< motor-side position loop bandwidth [Hz] (critically damped PD)
  double servo_integral_time = 0.0;  ///< integral time of the position loop [s]; 0: PD only
  double encoder_steps = 501923.0;   ///< encoder steps per output turn
  double physics_dt = 0.001;         ///< MuJoCo step [s]
  double contact_time_constant =
      0.005;  ///< sole-floor contact stiffness as MuJoCo's solref time constant [s] (≥ 2 physics_dt)
  double control_period = 0.004;    ///< controller period [s], a multiple of physics_dt
  double ft_force_noise = 0.0;      ///< std of F/T force noise [N]
  double ft_torque_noise = 0.0;     ///< std of F/T torque noise [Nm]
  double gyro_noise = 0.0;          ///< std [rad/s]
  double accel_noise = 0.0;         ///< std [m/s^2]
  double encoder_noise = 0.0;       ///< std of the encoder reading's noise, beyond quantisation [rad]
  double motor_torque_noise = 0.0;  ///< std of the noise of each servo's torque from its current [Nm]
  int noise_seed = 1;               ///< seed of the sensor noise
  ImuModel imu;                     ///< IMU bias, bias drift, AHRS error (plant.imu.*)
  SensorFaults faults;              ///< the sensors' fault schedule (plant.faults.*)
  TerrainParams terrain;            ///< the floor (terrain.*; flat by default)

  int substeps() const { return static_cast<int>(std::lround(control_period / physics_dt)); }
  /// The true gear stiffness of each joint, k_joint × k_scale [Nm/rad].
  humanoid::JointVector gear_stiffness() const { return humanoid::scaled(k_joint, k_scale); }
  /// The servo torque limit of each joint: joint_torque_limit where set, else torque_limit [Nm].
  humanoid::JointVector servo_torque_limits() const {
    humanoid::JointVector out;
    for (int j = 0; j < humanoid::kJoints; ++j)
      out[j] = joint_torque_limit[j] > 0 ? joint_torque_limit[j] : torque_limit;
    return out;
  }

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("plant.k_joint", s.k_joint,
      {.unit = "Nm/rad", .doc = "true gear stiffness of every joint", .bounds = positive()});
    for (int j = 0; j < humanoid::kJoints; ++j) {
      const std::string key = "plant.k_scale." + std::string(humanoid::kJointNames[j]);
      v(key, s.k_scale[j], {.doc = "factor on plant.k_joint for this joint", .bounds = left_open(0, 100)});
    }
    v("plant.gear_damping", s.gear_damping,
      {.unit = "Nm s/rad", .doc = "gear damping (implicit in MuJoCo)", .bounds = closed(0, 10000)});
    v("plant.backlash", s.backlash,
      {.unit = "rad", .doc = "backlash dead band, total width", .bounds = closed(0, 0.1)});
    v("plant.torque_limit", s.torque_limit, {.unit = "Nm", .doc = "servo torque limit", .bounds = positive()});
    v("plant.rotor_inertia", s.rotor_inertia,
      {.unit = "kg m^2", .doc = "reflected rotor inertia", .bounds = closed(1e-4, 100)});
    v("plant.servo_bandwidth", s.servo_bandwidth,
      {.unit = "Hz", .doc = "motor-side position loop bandwidth", .bounds = closed(0.1, 1000)});
    v("plant.servo_integral_time", s.servo_integral_time,
      {.unit = "s", .doc = "integral time of the position loop (0: none, PD only)", .bounds = closed(0, 100)});
    v("plant.encoder_steps", s.encoder_steps, {.doc = "encoder steps per output turn", .bounds = closed(1, 1e12)});
    v("plant.physics_dt", s.physics_dt, {.unit = "s", .doc = "MuJoCo step", .bounds = closed(1e-5, 0.002)});
    v("plant.contact_time_constant", s.contact_time_constant,
      {.unit = "s",
       .doc = "sole-floor contact time constant (MuJoCo solref; softer contacts let the feet rock)",
       .bounds = closed(1e-4, 0.1)});
    v("plant.control_period", s.control_period,
      {.unit = "s", .doc = "controller period (a multiple of the physics step)", .bounds = closed(1e-4, 0.008)});
    v("plant.noise.ft_force", s.ft_force_noise, {.unit = "N", .doc = "F/T force noise std", .bounds = closed(0, 1000)});
    v("plant.noise.ft_torque", s.ft_torque_noise,
      {.unit = "Nm", .doc = "F/T torque noise std", .bounds = closed(0, 1000)});
    v("plant.noise.gyro", s.gyro_noise, {.unit = "rad/s", .doc = "gyro noise std", .bounds = closed(0, 100)});
    v("plant.noise.accel", s.accel_noise,
      {.unit = "m/s^2", .doc = "accelerometer noise std", .bounds = closed(0, 1000)});
    v("plant.noise.encoder", s.encoder_noise,
      {.unit = "rad", .doc = "encoder noise std (beyond quantisation)", .bounds = closed(0, 1)});
    v("plant.noise.motor_torque", s.motor_torque_noise,
      {.unit = "Nm", .doc = "noise std of each servo's torque from its motor current", .bounds = closed(0, 1000)});
    v("plant.noise.seed", s.noise_seed, {.doc = "seed of the sensor noise", .bounds = closed(0, 2147483647)});
    ImuModel::visit_fields(s.imu, v);
    SensorFaults::visit_fields(s.faults, v);
    TerrainParams::visit_fields(s.terrain, v);
  }
};

/// Keys plant.* (plant.k_scale.<joint> multiplies plant.k_joint for one joint).
inline Schema plant_schema() {
  return schema_of<PlantParams>();
}
/// The plant's keys; throws ConfigError when plant.control_period is not a multiple of plant.physics_dt,
/// or a latency fault has no delay (plant.faults.<sensor>.delay).
PlantParams plant_from_config(const Config& config);

}  // namespace flexgait::twin
