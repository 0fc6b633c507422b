#pragma once
/// \file robot_params.hpp
/// The robot's geometry and masses (spec humanoid.md, "The robot (THORMANG3-class)") and the
/// plant's elastic actuators, sensors and timing ("The elastic actuator (plant)"). SI units.
#include <cmath>
#include <string>

#include "flexgait/core/config.hpp"
#include "flexgait/humanoid/joints.hpp"

namespace flexgait::humanoid {

/// Geometry and mass distribution. Defaults: the spec's figures (ROBOTIS's link masses, 43.7 kg,
/// plus batteries and computers split between pelvis and chest up to total_mass).
struct RobotParams {
  double total_mass = 57.0;        ///< [kg], >= sum of the listed links
  double hip_yaw_offset_y = 0.093; ///< hip yaw joint at (0, ±y, -z) from the pelvis origin [m]
  double hip_yaw_offset_z = 0.018; ///< [m]
  double hip_axes_depth = 0.093;   ///< hip roll/pitch axes below the pelvis origin [m]
  double thigh = 0.300;            ///< hip pitch to knee [m]
  double shank = 0.300;            ///< knee to ankle [m]
  double ankle_to_sole = 0.1145;   ///< ankle axes to the sole [m]
  double sole_length = 0.22;       ///< [m]
  double sole_width = 0.15;        ///< [m]
  double sole_friction = 1.0;
  // Link masses [kg]
  double m_hip_yaw = 0.243, m_hip_roll = 1.045, m_thigh = 3.095, m_shank = 2.401;
  double m_ankle_pitch = 1.045, m_ankle_roll = 0.223, m_foot = 1.689;
  double m_pelvis = 6.869, m_chest = 5.383, m_arm = 4.995, m_head = 2.0;
  // Where the link masses sit (the twin's link shapes are centred there; the controller's own
  // model reads the same numbers). Leg links not listed have their centre on their joint axes;
  // thigh and shank at their midpoints; the foot at the middle of its sole plate.
  double hip_yaw_com_z = -0.03;   ///< hip yaw link centre below the hip yaw joint [m]
  double sole_thickness = 0.02;   ///< sole plate [m]
  double chest_joint_z = 0.10;    ///< waist yaw joint above the pelvis origin [m]
  double chest_com_z = 0.16;      ///< chest centre above the waist joint [m]
  double arm_y = 0.22;            ///< arms (rigid, hanging) at ±y from the waist axis [m]
  double arm_com_z = 0.04;        ///< arm centre above the waist joint [m]
  double head_z = 0.42;           ///< head centre above the waist joint [m]

  /// Mass of the listed links (both legs, pelvis, chest, arms, head) [kg].
  double listed_mass() const {
    return 2 * (m_hip_yaw + m_hip_roll + m_thigh + m_shank + m_ankle_pitch + m_ankle_roll + m_foot) + m_pelvis +
           m_chest + 2 * m_arm + m_head;
  }
};

/// The elastic gear actuators, the sensors and the timing of the twin.
struct PlantParams {
  JointVector k_joint{};          ///< true gear stiffness per joint [Nm/rad] (plant.k_joint × plant.k_scale.*)
  double gear_damping = 80.0;     ///< d [Nm s/rad], integrated implicitly by MuJoCo
  double backlash = 0.0;          ///< dead band, total width [rad]
  double torque_limit = 100.0;    ///< servo torque limit [Nm]
  double rotor_inertia = 0.8;     ///< reflected rotor inertia [kg m^2]
  double servo_bandwidth = 30.0;  ///< motor-side position loop bandwidth [Hz] (critically damped PD)
  double servo_integral_time = 0.0;   ///< integral time of the position loop [s]; 0: PD only
  double encoder_steps = 501923.0;    ///< encoder steps per output turn
  double physics_dt = 0.001;      ///< MuJoCo step [s]
  double contact_time_constant = 0.005;  ///< sole-floor contact stiffness as MuJoCo's solref time constant [s] (≥ 2 physics_dt)
  double control_period = 0.004;  ///< controller period [s], a multiple of physics_dt
  double ft_force_noise = 0.0;    ///< std of F/T force noise [N]
  double ft_torque_noise = 0.0;   ///< std of F/T torque noise [Nm]
  double gyro_noise = 0.0;        ///< std [rad/s]
  double accel_noise = 0.0;       ///< std [m/s^2]
  int noise_seed = 1;             ///< seed of the sensor noise

  int substeps() const { return static_cast<int>(std::lround(control_period / physics_dt)); }
};

/// Keys robot.* and plant.* (plant.k_scale.<joint> multiplies plant.k_joint for one joint).
Schema robot_schema();
Schema plant_schema();
RobotParams robot_from_config(const Config& config);
PlantParams plant_from_config(const Config& config);

}  // namespace flexgait::humanoid
