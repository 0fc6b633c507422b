// The `flexgait` Python module: the C++ core, not a re-write.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings.hpp"
#include "convert.hpp"
#include "flexgait/core/config.hpp"
#include "flexgait/experiments/stiffness_bench.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/rimless/wheel_setup.hpp"
#include "flexgait/twin/mujoco_messages.hpp"
#include "flexgait/version.hpp"

namespace py = pybind11;

namespace {

flexgait::Schema schema_named(const std::string& name) {
  if (name == "rimless") return flexgait::rimless::rimless_analysis_schema();
  if (name == "walk") return flexgait::experiments::walk_run_schema();
  if (name == "bench") return flexgait::experiments::bench_schema();
  throw py::value_error("schema: '" + name + "' is not one of rimless, walk, bench");
}

}  // namespace

PYBIND11_MODULE(_flexgait, m) {
  m.doc() =
      "flexgait: legged locomotion with compliance, from Python.\n\n"
      "Two studies on one C++20 core (the same code as the `flexgait` command line):\n"
      "  flexgait.rimless  - the flexible-leg rimless wheel with stick-slip friction: simulate, poincare_map,\n"
      "                      fixed_point, sweep, continuation, basin, orbit_diagram, gait_vs_friction,\n"
      "                      stagnation.\n"
      "  flexgait.humanoid - a THORMANG-class humanoid twin (MuJoCo) with elastic gears: bench (stiffness\n"
      "                      identification), walk (ZMP preview control with the actuator deformation\n"
      "                      compensators on or off), compensation (the study), export (MJCF, URDF).\n"
      "  flexgait.HumanoidLoop, flexgait.Controller - the humanoid's closed loop stepped from Python;\n"
      "                      flexgait.env.HumanoidEnv - the same with Gymnasium's reset/step.\n"
      "  flexgait.campaign - any experiment over a grid of keys (`flexgait campaign`).\n\n"
      "Configuration: every function takes `config`, a dict {key: value} over the defaults (and over\n"
      "`config_file`, a YAML file as written by the command line), nested dicts as YAML nests, validated\n"
      "as on the command line; a bad key or value raises ValueError naming the key. flexgait.defaults('walk')\n"
      "lists the keys.\n\n"
      "Results: dicts. Tables are dicts of columns (the command line's CSV files to the last digit): numbers\n"
      "as float arrays with NaN where a point failed, true/false as bool arrays, states as 2-D float arrays,\n"
      "Floquet multipliers as complex arrays. The record a command writes as its summary is 'summary'. SI\n"
      "units throughout.\n\n"
      "Threads: the GIL is released while C++ computes, so Python threads can run sweeps side by side.\n\n"
      "Example:\n"
      "    import flexgait\n"
      "    run = flexgait.rimless.simulate({'rimless.mu_s': 0.4, 'rimless.mu_k': 0.4})\n"
      "    run['summary']['energy_balance_error'], run['log']['t']\n"
      "    walk = flexgait.humanoid.walk({'walk.steps': 4}, compensation='off')\n"
      "    walk['summary']['pelvis_roll_error_max']\n";
  m.attr("__version__") = flexgait::kVersion;
  // MuJoCo's messages to stderr, not to stdout and MUJOCO_LOG.TXT; hooks another module (MuJoCo's
  // own Python bindings) has set are left alone.
  if (!flexgait::twin::mujoco_messages_hooked()) flexgait::twin::route_mujoco_messages_to_stderr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const flexgait::ConfigError& e) {
      // The command line's message names where a value came from ("--set: key ..."); here it
      // came from the config dict.
      std::string message = e.what();
      if (message.rfind("--set: ", 0) == 0) message = "config: " + message.substr(7);
      PyErr_SetString(PyExc_ValueError, message.c_str());
    } catch (const flexgait::UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  m.def(
      "defaults",
      [](const std::string& name) {
        return flexgait::python::config_dict(
            flexgait::python::make_config(schema_named(name), py::none(), std::nullopt));
      },
      py::arg("schema"),
      "The default configuration of 'rimless' (rimless.*, initial.*, sim.*, analysis.*), 'walk' (robot.*, "
      "plant.*, walk.*, balance.*, control.*, output.*) or 'bench' (bench.*, actuator) as a dict key -> value.");
  m.def(
      "describe",
      [](const std::string& name) {
        py::dict out;
        const flexgait::Schema schema = schema_named(name);
        for (const auto& p : schema.params()) {
          py::dict d;
          d["default"] = p.fallback;
          d["unit"] = p.unit;
          d["doc"] = p.doc;
          d["allowed"] = p.allowed();
          out[py::str(p.key)] = d;
        }
        return out;
      },
      py::arg("schema"),
      "Every key of a schema ('rimless', 'walk', 'bench') with its default, unit, meaning and allowed values.");
  flexgait::python::bind_rimless(m);
  flexgait::python::bind_humanoid(m);
  flexgait::python::bind_loop(m);
  flexgait::python::bind_campaign(m);
}
