#pragma once
/// \file urdf_export.hpp
/// A loaded robot as URDF (docs/guide/robot.md, `flexgait humanoid export --format urdf`): the rigid robot —
/// one link per body with its inertial (mass, centre, principal inertia and axes), one joint per
/// body (revolute for the mapped joints under the file's names, fixed otherwise), the shapes as
/// visuals (URDF readers such as MuJoCo's give every collision shape contacts). The soles: a sole
/// made of the foot's contact geoms (Sole::hull) is exported as those geoms, the foot's only
/// <collision> elements (a capsule, which URDF lacks, as the spheres at its ends), so the reload
/// makes the same hull; any other sole comes from the mapping (robot.feet.*.sole_size /
/// sole_center, see urdf_mapping).
/// Link frames sit on the joint anchors (URDF puts a joint at its child link's origin).
#include <Eigen/Dense>
#include <array>
#include <string>

#include "flexgait/robot/robot_description.hpp"

namespace flexgait::humanoid {

std::string robot_urdf(const LoadedRobot& robot);

/// URDF's roll, pitch, yaw of R = Rz(yaw) Ry(pitch) Rx(roll) [rad]. At |pitch| = π/2 (a frame
/// turned a quarter about its y, common in files whose frames follow the joint axes) roll and yaw
/// are not separately defined; the three returned reproduce R to rounding there too.
std::array<double, 3> urdf_rpy(const Eigen::Matrix3d& R);

/// The mapping that loads robot_urdf(robot) back: `--set` lines (KEY=VALUE), one per line.
std::string urdf_mapping(const LoadedRobot& robot);

}  // namespace flexgait::humanoid
