#pragma once
/// \file robot_loader.hpp
/// Reads a robot description (MJCF or URDF) through MuJoCo's compiler and resolves the mapping
/// (robot_description.hpp) into a LoadedRobot. MuJoCo stays inside the .cpp: callers get plain data.
///
/// Rules: the robot's root is the body under the world that holds the mapped joints (its free
/// joint, if any, is dropped: the twin adds one); the mapped joints are hinges; the path from the
/// root to each foot body holds exactly six joints, the leg's six mapped ones in kinematic order;
/// each foot has a sole (a box geom whose axes are the foot's, or a size and a centre). URDF is
/// compiled with fusestatic="false" so that bodies on fixed joints (feet, sensor frames) stay.
#include <cstddef>
#include <string>

#include "flexgait/robot/robot_description.hpp"

namespace flexgait::twin {

/// The size limit of a description file [bytes]: the largest published humanoid files (MJCF or
/// URDF, meshes apart) are below 1 MB; the limit keeps a huge file from being read into memory.
inline constexpr std::size_t kMaxDescriptionBytes = std::size_t{16} << 20;

/// Loads the description named by `params.description` (not builtin). Throws ConfigError naming
/// the key and the name: a missing, unreadable, non-regular, empty or too large file, a number that
/// is not finite (naming its line), a negative mass or inertia, a parse error (MuJoCo's message), a mapped
/// name not in the file, a leg with the wrong number of joints, a foot without a sole.
/// What the loader translated (MuJoCo 3 attributes, robot_loader_xml.hpp) is printed on stderr,
/// one "warning:" line each, and kept in LoadedRobot::warnings.
humanoid::LoadedRobot load_robot(const humanoid::RobotDescriptionParams& params);

/// Loads description text (MJCF or URDF by `format`: "xml" or "urdf") as load_robot does; `source`
/// names it in messages.
humanoid::LoadedRobot load_robot_text(const std::string& text, const std::string& format, const std::string& source,
                                      const humanoid::RobotDescriptionParams& params);

}  // namespace flexgait::twin
