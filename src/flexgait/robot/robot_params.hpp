#pragma once
/// \file robot_params.hpp
/// The builtin robot's geometry and masses (docs/theory/humanoid.md, "The robot"). SI units. The
/// twin's truth (its gears, sensors, faults, floor and timing) is twin/plant_params.hpp.
#include <cmath>
#include <string>

#include "flexgait/core/config.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/robot/joints.hpp"

namespace flexgait::humanoid {

/// The magnitude of gravity, along −z, of the builtin robot's world and of a description that states
/// none (MuJoCo's default `<option gravity="0 0 -9.81">`; URDF has no gravity) [m/s^2]. A loaded
/// MJCF's own value is LoadedRobot::gravity.
inline constexpr double kDefaultGravity = 9.81;

/// Geometry and mass distribution. Defaults: the spec's figures; the links' masses, centres of mass
/// and inertias are THORMANG3's (builtin_inertials.hpp, 42.533 kg) plus batteries and computers
/// split between pelvis and chest up to total_mass.
struct RobotParams {
  double total_mass = 57.0;         ///< [kg], >= kLinksMass
  double hip_yaw_offset_y = 0.093;  ///< hip yaw joint at (0, ±y, -z) from the pelvis origin [m]
  double hip_yaw_offset_z = 0.018;  ///< [m]
  double hip_axes_depth = 0.093;    ///< hip roll/pitch axes below the pelvis origin [m]
  double thigh = 0.300;             ///< hip pitch to knee [m]
  double shank = 0.300;             ///< knee to ankle [m]
  double ankle_to_sole = 0.1145;    ///< ankle axes to the sole [m]
  double sole_length = 0.22;        ///< [m]
  double sole_width = 0.15;         ///< [m]
  double sole_offset_y = 0.014;     ///< sole box centre outward of the ankle axis [m] (as on the real robot)
  double sole_friction = 1.0;
  double chest_joint_z = 0.1705;  ///< waist yaw joint above the pelvis origin [m] (ROBOTIS's torso_y)
  // The shapes the twin draws (for looks only: the masses are builtin_inertials.hpp's).
  double sole_thickness = 0.02;  ///< sole plate [m] (it collides)
  double chest_com_z = 0.11;     ///< chest box centre above the waist joint [m]
  double arm_y = 0.22;           ///< arms (rigid, hanging) at ±y from the waist axis [m]
  double arm_com_z = 0.0;        ///< arm capsule centre above the waist joint [m]
  double head_z = 0.27;          ///< head centre above the waist joint [m]

  /// The sum of THORMANG3's links (thormang3_inertials.hpp), the least total mass [kg].
  static constexpr double kLinksMass = 42.53350283;

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("robot.total_mass", s.total_mass,
      {.unit = "kg",
       .doc = "total mass; the mass beyond THORMANG3's links (42.533 kg) goes to pelvis and chest",
       .bounds = closed(kLinksMass, 500)});
    v("robot.thigh", s.thigh, {.unit = "m", .doc = "hip pitch axis to knee", .bounds = left_open(0.05, 2)});
    v("robot.shank", s.shank, {.unit = "m", .doc = "knee to ankle axes", .bounds = left_open(0.05, 2)});
    v("robot.ankle_to_sole", s.ankle_to_sole,
      {.unit = "m", .doc = "ankle axes to the sole", .bounds = closed(0.01, 1)});
    v("robot.sole_offset_y", s.sole_offset_y,
      {.unit = "m", .doc = "sole box centre outward of the ankle axis", .bounds = closed(0, 0.1)});
    v("robot.sole_friction", s.sole_friction, {.doc = "sole-floor friction coefficient", .bounds = closed(0.05, 5)});
  }
};

/// Keys robot.*.
inline Schema robot_schema() {
  return schema_of<RobotParams>();
}
inline RobotParams robot_from_config(const Config& config) {
  return record_from_config<RobotParams>(config);
}

}  // namespace flexgait::humanoid
