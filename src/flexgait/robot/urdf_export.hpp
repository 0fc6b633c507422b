#pragma once
/// \file urdf_export.hpp
/// A loaded robot as URDF (docs/guide/robot.md, `flexgait humanoid export --format urdf`): the rigid robot —
/// one link per body with its inertial (mass, centre, principal inertia and axes), one joint per
/// body (revolute for the mapped joints under the file's names, fixed otherwise), the shapes as
/// visuals only (URDF readers such as MuJoCo's give every collision shape contacts; the twin's
/// soles come from the mapping: robot.feet.*.sole_size / sole_center, see urdf_sole_mapping).
/// Link frames sit on the joint anchors (URDF puts a joint at its child link's origin).
#include <string>

#include "flexgait/robot/robot_description.hpp"

namespace flexgait::humanoid {

std::string robot_urdf(const LoadedRobot& robot);

/// The mapping that loads robot_urdf(robot) back: `--set` lines (KEY=VALUE), one per line.
std::string urdf_mapping(const LoadedRobot& robot);

}  // namespace flexgait::humanoid
