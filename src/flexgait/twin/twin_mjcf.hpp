#pragma once
/// \file twin_mjcf.hpp
/// The twin of a loaded robot as MJCF (docs/guide/robot.md): the file's bodies with their inertials and
/// geoms as MuJoCo compiled them (written at full precision, so the twin compiles to the same
/// numbers), a free joint at the root, the mapped joints carrying the elastic gears' stiffness
/// and damping under flexgait's joint names (the elastic drives move their spring references),
/// unmapped joints left out (held rigid at zero), the soles named l_sole / r_sole colliding with
/// the floor, the sites imu, l_ft, r_ft and the sensors of the builtin twin (model_xml.hpp).
#include <string>

#include "flexgait/robot/robot_description.hpp"
#include "flexgait/robot/robot_params.hpp"
#include "flexgait/twin/plant_params.hpp"

namespace flexgait::twin {

/// The sole centre in the frame of the F/T site twin_mjcf() puts on the foot (the sole's frame) [m].
std::array<double, 3> sole_center_in_site(const humanoid::Sole& sole);

/// \param robot sole friction (robot.sole_friction); \param plant gears, physics step, contacts.
std::string twin_mjcf(const humanoid::LoadedRobot& loaded, const humanoid::RobotParams& robot,
                      const PlantParams& plant);

/// The mapping that loads twin_mjcf(loaded, ...) back as a description: `--set` lines (KEY=VALUE),
/// one per line: each joint under its flexgait name (waist_yaw none if the robot has no waist),
/// each foot's body with its sole geom l_sole / r_sole.
std::string twin_mjcf_mapping(const humanoid::LoadedRobot& loaded);

}  // namespace flexgait::twin
