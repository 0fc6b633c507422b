// flexgait.rimless: the flexible-leg rimless wheel from Python.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "flexgait/core/sweep_runner.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/output.hpp"
#include "flexgait/rimless/poincare.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "flexgait/rimless/sweep.hpp"
#include "flexgait/rimless/wheel_setup.hpp"

namespace flexgait::python {
namespace {

using OptionalPath = std::optional<std::string>;

using rimless::WheelSetup;

WheelSetup wheel_setup(const Schema& schema, const py::object& overrides, const OptionalPath& file) {
  return rimless::wheel_setup(make_config(schema, overrides, file));
}

/// The in-memory record of a run (RunCollector) that also lets Ctrl-C stop it (InterruptCheck).
class InterruptibleCollector final : public rimless::RunSink {
 public:
  explicit InterruptibleCollector(rimless::SimulationResult& kept) : keep_(kept) {}
  void on_sample(const rimless::LogSample& sample) override {
    keep_.on_sample(sample);
    check_();
  }
  void on_event(const rimless::EventRecord& event) override {
    keep_.on_event(event);
    check_();
  }
  void on_step(const rimless::StepRecord& step) override {
    keep_.on_step(step);
    check_();
  }

 private:
  rimless::RunCollector keep_;
  InterruptCheck check_;
};

py::dict simulate(const py::object& config, const OptionalPath& config_file) {
  const WheelSetup s = wheel_setup(rimless::rimless_schema(), config, config_file);
  check_with_origin(s.config, [&] { rimless::check_log_size(s.sim); });  // the log is kept in memory
  const std::string model = s.config.choice("sim.model");
  Table log({}), events({}), steps({});
  nlohmann::ordered_json summary;
  {
    py::gil_scoped_release release;
    rimless::SimulationResult kept;  // samples, events and steps
    InterruptibleCollector sink(kept);
    rimless::SimulationResult r = s.sim.model == rimless::Model::Rigid
                                      ? rimless::simulate_rigid(s.wheel, s.initial, s.sim, sink)
                                      : rimless::simulate_flexible(s.wheel, s.initial, s.sim, sink);
    r.samples = std::move(kept.samples);
    r.events = std::move(kept.events);
    r.steps = std::move(kept.steps);
    log = rimless::log_table(r);
    events = rimless::events_table(r);
    steps = rimless::steps_table(r);
    summary = rimless::simulation_summary(r, model);
  }
  py::dict out;
  out["log"] = table_columns(std::move(log));
  out["events"] = table_columns(std::move(events));
  out["steps"] = table_columns(std::move(steps));
  out["summary"] = json_value(summary);
  out["config"] = config_dict(s.config);
  return out;
}

py::dict fixed_point(const py::object& config, const OptionalPath& config_file, const std::string& section) {
  const WheelSetup s = wheel_setup(rimless::rimless_analysis_schema(), config, config_file);
  const rimless::AnalysisOptions opt = rimless::analysis_from_config(s.config);
  const rimless::Section sec = section_of(section);
  rimless::FixedPointReport rep;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;  // Ctrl-C: checked from every run's poll
    rimless::SimulationOptions sim = s.sim;
    sim.poll = [&interrupted] { interrupted(); };
    rep = rimless::find_fixed_point(s.wheel, sim, opt, s.sim.model, sec, s.initial);
  }
  py::dict out = json_value(rimless::fixed_point_record(rep));
  // A failed search (converged False, failure saying why) has no fixed point and no Jacobian.
  out["z"] = rep.converged ? py::cast(Eigen::VectorXd(rep.point.z)) : py::none();
  out["state"] = out["z"];
  out["jacobian"] = rep.converged ? py::cast(Eigen::MatrixXd(rep.jacobian)) : py::none();
  out["multipliers"] = rep.converged ? py::object(complex_array(rep.multipliers)) : py::none();
  out["multipliers_fd"] = rep.converged ? py::object(complex_array(rep.multipliers_fd)) : py::none();
  return out;
}

py::dict poincare_map(const py::object& config, const OptionalPath& config_file, const std::string& section,
                      const std::optional<Eigen::VectorXd>& z) {
  const WheelSetup s = wheel_setup(rimless::rimless_analysis_schema(), config, config_file);
  const rimless::AnalysisOptions opt = rimless::analysis_from_config(s.config);
  if (z && !z->allFinite())  // None in a list arrives as NaN
    throw py::value_error("z: every component must be a finite number (None, NaN and inf are not)");
  rimless::SectionState point;
  rimless::MapStep step;
  std::optional<std::string> failure;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;  // Ctrl-C: checked from every run's poll
    const rimless::Section sec = section_of(section);
    rimless::SimulationOptions sim = rimless::map_options(s.sim, opt);
    sim.poll = [&interrupted] { interrupted(); };
    if (auto f = rimless::settle_on_section(s.wheel, sim, s.sim.model, sec, s.initial, opt.transient_steps, point))
      failure = f->text();
    if (!failure && z) {
      if (z->size() != point.z.size())
        failure =
            "z has " + std::to_string(z->size()) + " components, the section state " + std::to_string(point.z.size());
      else
        point.z = *z;
    }
    if (!failure) {
      rimless::PoincareMap map(s.wheel, sim, s.sim.model, sec);
      step = map.apply(point, false);
      if (step.failure) failure = step.failure->text();
    }
  }
  if (failure && z && z->size() != point.z.size()) throw py::value_error(*failure);
  py::dict out;
  out["names"] = point.names();
  out["z"] = Eigen::VectorXd(point.z);
  out["failure"] = failure ? py::object(py::str(*failure)) : py::object(py::none());
  if (!failure) {
    out["next"] = Eigen::VectorXd(step.next.z);
    out["gait"] = step.gait;
    out["period"] = step.period;
    out["distance"] = step.distance;
    out["dissipated"] = step.dissipated;
  }
  return out;
}

py::dict sweep(const std::string& param, double start, double stop, int count, const py::object& config,
               const OptionalPath& config_file, const std::string& section) {
  const WheelSetup s = wheel_setup(rimless::rimless_analysis_schema(), config, config_file);
  rimless::check_sweep_param(s.config.schema(), param);
  if (count < 1 || count > kMaxSweepPoints)
    throw py::value_error("count: " + std::to_string(count) + " is not in [1, " + std::to_string(kMaxSweepPoints) +
                          "] (the command line's cap)");
  const rimless::SweepSpec spec{param, start, stop, count, section_of(section)};
  for (int i = 0; i < count; ++i) rimless::sweep_point_config(s.config, spec, i);  // every point valid first
  std::string csv = "index," + rimless::sweep_header() + "\n";
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;
    const std::function<void()> poll = [&interrupted] { interrupted(); };  // within and between points
    for (int i = 0; i < count; ++i) {
      interrupted();
      csv += std::to_string(i) + "," + rimless::sweep_row(s.config, spec, i, poll) + "\n";
    }
  }
  return csv_columns(csv, {"state"}, {"multipliers"});
}

}  // namespace

rimless::Section section_of(const std::string& name) {
  if (name == "touchdown") return rimless::Section::Touchdown;
  if (name == "upright") return rimless::Section::Upright;
  throw py::value_error("section: '" + one_line(name) + "' is not one of touchdown, upright");
}

void bind_rimless(py::module_& m) {
  py::module_ r = m.def_submodule(
      "rimless",
      "The flexible-leg rimless wheel with stick-slip friction (Bao et al. 2024): event-driven hybrid simulation on "
      "SUNDIALS CVODE, Poincare maps, Newton-Raphson fixed points, sweeps.\n\n"
      "Every function takes `config`, a dict of configuration keys (e.g. {'rimless.mu_s': 0.4, 'sim.model': "
      "'rigid'}) applied over the defaults and over `config_file` (YAML), validated as on the command line: an "
      "unknown key or a bad value raises ValueError naming the key. The GIL is released while C++ runs.");
  r.def("simulate", &simulate, py::arg("config") = py::none(), py::arg("config_file") = py::none(),
        "Simulate the wheel (keys rimless.*, initial.*, sim.*; `sim.model` flexible or rigid).\n\n"
        "Returns a dict: 'log', 'events', 'steps' (each a dict of numpy arrays, the columns of log.csv, events.csv, "
        "steps.csv of `flexgait rimless simulate`), 'summary' (summary.json as a dict: energy ledger, gaits, "
        "speed, ...) and 'config' (the resolved configuration).");
  r.def("fixed_point", &fixed_point, py::arg("config") = py::none(), py::arg("config_file") = py::none(),
        py::arg("section") = "touchdown",
        "A periodic gait: settle on the Poincare section (`analysis.transient_steps`), then Newton-Raphson on "
        "P(z) - z. Returns fixed_point.json as a dict (converged, iterations, residual, state, multipliers, "
        "stable, gait, period, speed, ...) with 'z' (= 'state') and 'jacobian' (dP/dz) as numpy arrays and "
        "'multipliers' as a complex array. A failed search returns "
        "converged False, 'failure' saying why, and None for z, jacobian, state and multipliers. `section`: "
        "'touchdown' or 'upright'.");
  r.def("poincare_map", &poincare_map, py::arg("config") = py::none(), py::arg("config_file") = py::none(),
        py::arg("section") = "touchdown", py::arg("z") = py::none(),
        "One application of the Poincare map. Settles on the section from the configured initial state; `z` "
        "(numpy array, optional) replaces the section point's reduced state. Returns a dict: 'names' of z's "
        "components, 'z', 'next' = P(z), 'gait', 'period' [s], 'distance' [m], 'dissipated' [J], 'failure' "
        "(None or why the next crossing was not reached).");
  r.def("sweep", &sweep, py::arg("param"), py::arg("start"), py::arg("stop"), py::arg("count"),
        py::arg("config") = py::none(), py::arg("config_file") = py::none(), py::arg("section") = "touchdown",
        "Sweep one real parameter (a configuration key, or 'rimless.mu' for mu_s = mu_k) over `count` values "
        "from `start` to `stop`: gait, fixed point, multipliers, stability at each. Returns the columns of the "
        "command line's sweep.csv: numbers as float arrays (NaN where a point has none), true/false as bool "
        "arrays, text as lists. Runs in this thread with the GIL "
        "released: Python threads can run sweeps side by side.");
  bind_rimless_maps(r);
}

}  // namespace flexgait::python
