// flexgait.humanoid: the THORMANG-class twin with elastic gears, its walking controller and the
// actuator deformation compensators from Python.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "flexgait/experiments/bench_output.hpp"
#include "flexgait/experiments/stiffness_bench.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/experiments/walk_output.hpp"

namespace flexgait::python {
namespace {

using OptionalPath = std::optional<std::string>;

py::dict bench(const py::object& config, const OptionalPath& config_file) {
  const Config c = make_config(experiments::bench_schema(), config, config_file);
  const experiments::BenchParams params = experiments::bench_from_config(c);
  std::string csv, summary;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;  // Ctrl-C: checked before every physics step
    const experiments::BenchResult r = experiments::run_stiffness_bench(params, [&interrupted] { interrupted(); });
    csv = experiments::bench_csv(r);
    summary = experiments::bench_summary_json(r);
  }
  py::dict out;
  out["samples"] = csv_columns(csv);
  out["summary"] = json_value(summary);
  out["config"] = config_dict(c);
  return out;
}

py::dict walk(const py::object& config, const OptionalPath& config_file,
              const std::optional<std::string>& compensation) {
  py::dict overrides;
  if (!config.is_none()) overrides = py::dict(config);
  if (compensation) overrides["control.compensation"] = *compensation;
  const Config c = make_config(experiments::walk_run_schema(), overrides, config_file);
  const experiments::WalkRunParams params = experiments::walk_run_from_config(c);
  Table log({}), joints({});
  std::string footsteps, summary, timing;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;  // Ctrl-C: checked from the walk's progress hook
    const experiments::WalkResult r = experiments::run_walk(params, [&](double) { interrupted(); });
    log = experiments::walk_log_table(r);
    joints = experiments::walk_joints_table(r);
    footsteps = experiments::walk_footsteps_csv(r);
    summary = experiments::walk_summary_json(r);
    timing = experiments::walk_timing_json(r);
  }
  py::dict out;
  out["log"] = table_columns(std::move(log));
  out["joints"] = table_columns(std::move(joints));
  out["footsteps"] = csv_columns(footsteps);
  out["metrics"] = json_value(summary);
  out["timing"] = json_value(timing);
  out["config"] = config_dict(c);
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
        "estimates, gravity torques), 'footsteps', 'metrics' (summary.json: fell, pelvis_roll_error_max, "
        "zmp_rms_y, estimate_error_rms, ...), 'timing' and 'config'.");
}

}  // namespace flexgait::python
