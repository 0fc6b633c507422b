// flexgait.humanoid: the THORMANG-class twin with elastic gears, its walking controller and the
// actuator deformation compensators from Python.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/experiments/bench_output.hpp"
#include "flexgait/experiments/compensation_study.hpp"
#include "flexgait/experiments/robot_export.hpp"
#include "flexgait/experiments/stiffness_bench.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/experiments/walk_output.hpp"

namespace flexgait::python {
namespace {

using OptionalPath = std::optional<std::string>;

py::dict bench(const py::object& config, const OptionalPath& config_file) {
  const Config c = make_config(experiments::bench_schema(), config, config_file);
  const experiments::BenchParams params = experiments::bench_from_config(c);
  std::string csv;
  nlohmann::ordered_json summary;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;  // Ctrl-C: checked before every physics step
    const experiments::BenchResult r = experiments::run_stiffness_bench(params, [&interrupted] { interrupted(); });
    csv = experiments::bench_csv(r);
    summary = record_json(r);
  }
  py::dict out;
  out["samples"] = csv_columns(csv);
  out["summary"] = json_value(summary);
  out["config"] = config_dict(c);
  return out;
}

py::dict walk(const py::object& config, const OptionalPath& config_file,
              const std::optional<std::string>& compensation) {
  py::dict extra;
  if (compensation) extra["control.compensation"] = *compensation;
  const py::dict overrides = config_with(config, extra);  // the caller's dict unchanged
  const Config c = make_config(experiments::walk_run_schema(), overrides, config_file);
  const experiments::WalkRunParams params = experiments::walk_run_from_config(c);
  Table log({}), joints({});
  std::string footsteps;
  nlohmann::ordered_json summary, timing;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;  // Ctrl-C: checked from the walk's progress hook
    const experiments::WalkResult r = experiments::run_walk(params, [&](double) { interrupted(); });
    log = experiments::walk_log_table(r);
    joints = experiments::walk_joints_table(r);
    footsteps = experiments::walk_footsteps_csv(r);
    summary = experiments::walk_summary(r);
    timing = experiments::walk_timing(r);
  }
  py::dict out;
  out["log"] = table_columns(std::move(log));
  out["joints"] = table_columns(std::move(joints));
  out["footsteps"] = csv_columns(footsteps);
  out["summary"] = json_value(summary);
  out["timing"] = json_value(timing);
  out["config"] = config_dict(c);
  return out;
}

py::dict compensation(const py::object& config, const OptionalPath& config_file) {
  const Config c = make_config(experiments::walk_run_schema(), config, config_file);
  const experiments::WalkRunParams params = experiments::walk_run_from_config(c);
  const std::vector<experiments::StudyCase> cases = experiments::compensation_cases(params);
  std::vector<experiments::WalkResult> results;
  std::vector<nlohmann::ordered_json> summaries;
  nlohmann::ordered_json comparison;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;
    for (const auto& one : cases) {
      results.push_back(experiments::run_walk(one.params, [&](double) { interrupted(); }));
      summaries.push_back(experiments::walk_summary(results.back()));
    }
    comparison = experiments::compensation_comparison(cases, results);
  }
  py::dict runs;
  for (std::size_t i = 0; i < cases.size(); ++i) runs[py::str(cases[i].name)] = json_value(summaries[i]);
  py::dict out;
  out["summary"] = json_value(comparison);
  out["runs"] = runs;
  out["config"] = config_dict(c);
  return out;
}

py::dict export_robot(const std::string& format, const py::object& config, const OptionalPath& config_file,
                      const std::string& file_name) {
  const Config c = make_config(experiments::walk_run_schema(), config, config_file);
  std::optional<experiments::RobotExport> exported;
  {
    py::gil_scoped_release release;
    exported.emplace(experiments::export_robot(c, format, file_name));
  }
  py::dict out;
  out["text"] = exported->text;
  out["format"] = format;
  out["config"] = config_dict(exported->reload);
  out["config_yaml"] = exported->reload.to_yaml();
  return out;
}

}  // namespace

void bind_humanoid(py::module_& m) {
  py::module_ h = m.def_submodule(
      "humanoid",
      "The THORMANG-class humanoid twin (MuJoCo) with elastic gears, the ZMP preview-control walking controller "
      "and the actuator deformation compensators (Kim 2017).\n\n"
      "`config` is a dict of configuration keys (robot.*, plant.*, walk.*, balance.*, control.*, bench.*) over "
      "the defaults and `config_file` (YAML); an unknown key or a bad value raises ValueError naming the key. "
      "The GIL is released while C++ runs.");
  h.def("bench", &bench, py::arg("config") = py::none(), py::arg("config_file") = py::none(),
        "The stiffness bench (thesis Fig. 12): one elastic actuator with a load arm swept through poses; fits "
        "k_joint, repeats with the input compensator, and runs the output compensator on the encoder.\n\n"
        "Returns a dict: 'samples' (the columns of bench.csv as numpy arrays), 'summary' (summary.json: k_fit, "
        "r_squared, errors) and 'config'.");
  h.def("walk", &walk, py::arg("config") = py::none(), py::arg("config_file") = py::none(),
        py::arg("compensation") = py::none(),
        "Walk the twin with the walking controller (`flexgait humanoid walk`). `compensation`: 'off', 'input', "
        "'output' or 'both' (the same as config key control.compensation; default both).\n\n"
        "Returns a dict: 'log' (log.csv's columns: ZMP reference, F/T and true ZMP, COM, IMU attitude, ... as "
        "numpy arrays), 'joints' (joints.csv: per leg joint desired, command, encoder, true link angle, the "
        "estimates, gravity torques), 'footsteps', 'summary' (summary.json: fell, pelvis_roll_error_max, "
        "zmp_rms_y, estimate_error_rms, ...), 'timing' and 'config'.");
  h.def("compensation", &compensation, py::arg("config") = py::none(), py::arg("config_file") = py::none(),
        "The compensation study (`flexgait humanoid compensation`, thesis experiments 2-4): the same gait with "
        "compensation off, both compensators (full and thesis form), the field's baselines and the measured and "
        "dynamic loads. Returns 'summary' (comparison.json: the headline cuts and one row per case), 'runs' (each "
        "case's walk summary by case name) and 'config'.");
  h.def("export", &export_robot, py::arg("format") = "mjcf", py::arg("config") = py::none(),
        py::arg("config_file") = py::none(), py::arg("file_name") = "robot.xml",
        "The robot (robot.description, builtin by default) as `flexgait humanoid export` writes it: format "
        "'mjcf' (the twin: elastic gears, sensors, floor) or 'urdf' (the rigid robot). Returns 'text' (the "
        "document), 'format', 'config' (the configuration that loads it back when the text is saved as "
        "`file_name`, as a dict) and 'config_yaml' (the same as YAML).");
}

}  // namespace flexgait::python
