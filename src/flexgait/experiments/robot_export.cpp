#include "flexgait/experiments/robot_export.hpp"

#include "flexgait/core/text.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/robot/urdf_export.hpp"
#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/robot_loader.hpp"
#include "flexgait/twin/twin_mjcf.hpp"

namespace flexgait::experiments {

RobotExport export_robot(const Config& config, const std::string& format, const std::string& file_name) {
  if (format != "mjcf" && format != "urdf")
    throw UsageError("--format: '" + one_line(format) + "' is not one of mjcf, urdf");
  const WalkRunParams params = walk_run_from_config(config);
  // The robot through the loader (the builtin: its twin's MJCF with the builtin mapping).
  humanoid::LoadedRobot loaded;
  if (params.loaded)
    loaded = *params.loaded;
  else
    loaded = twin::load_robot_text(twin::humanoid_mjcf(params.robot, params.plant), "xml", "builtin",
                                   humanoid::RobotDescriptionParams{});
  RobotExport out{{}, config};
  std::string mapping;
  if (format == "mjcf") {
    out.text = walk_twin(params).mjcf;
    mapping = twin::twin_mjcf_mapping(loaded);
  } else {
    out.text = humanoid::robot_urdf(loaded);
    mapping = humanoid::urdf_mapping(loaded);
  }
  // The compensation keys resolved for the default case, so that it loads back to the same compensation.
  for (const auto& [key, value] : params.case_defaults) out.reload.set(key, value, "default (the compensation case)");
  out.reload.set("robot.description", file_name, "humanoid export");
  for (const std::string& line : split_text(mapping, '\n'))
    if (const std::optional<KeyValue> kv = split_key_value(line)) out.reload.set(kv->key, kv->value, "humanoid export");
  return out;
}

}  // namespace flexgait::experiments
