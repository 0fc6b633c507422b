#pragma once
/// \file robot_export.hpp
/// The robot of a walk run's configuration as a file another simulator or the loader reads
/// (docs/guide/robots.md): the twin as MJCF (elastic gears as joint springs, sensors, floor) or the
/// rigid robot as URDF, and the configuration that loads that file back.
#include <string>

#include "flexgait/core/config.hpp"

namespace flexgait::experiments {

struct RobotExport {
  std::string text;  ///< the MJCF or URDF document
  /// The run's configuration with robot.description = the file's name and the keys of the
  /// exported names' mapping: `humanoid walk --config` of it walks the exported robot.
  Config reload;
};

/// `config`: a resolved walk_run_schema() configuration; `format`: "mjcf" or "urdf" (anything
/// else: UsageError naming --format); `file_name`: the name the text will be written under (the
/// reload configuration names it, relative to itself).
RobotExport export_robot(const Config& config, const std::string& format, const std::string& file_name);

}  // namespace flexgait::experiments
