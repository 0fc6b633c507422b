// flexgait.rimless: continuation, basin, orbit diagram, gait against friction and stagnation — the
// library calls of `flexgait rimless continuation` and `flexgait rimless analysis ...`, with typed
// results (docs/guide/python.md).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/core/sweep_runner.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/rimless/analyses.hpp"
#include "flexgait/rimless/basin.hpp"
#include "flexgait/rimless/gait_branch.hpp"
#include "flexgait/rimless/orbit_diagram.hpp"
#include "flexgait/rimless/stagnation.hpp"
#include "flexgait/rimless/sweep.hpp"
#include "flexgait/rimless/wheel_setup.hpp"

namespace flexgait::python {
namespace {

using OptionalPath = std::optional<std::string>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The analysis schema's configuration: defaults, `config_file`, `config`, then `extra` (keys the
/// function's own arguments set, as the command line's options set them).
Config analysis_config(const py::object& config, const OptionalPath& config_file, const py::dict& extra = {}) {
  return make_config(rimless::rimless_analysis_schema(), config_with(config, extra), config_file);
}

/// A CSV column's cells by name (header row first), for the columns typed here rather than by typed_column.
std::vector<std::string> column_cells(const std::vector<CsvRecord>& records, const std::string& name) {
  std::vector<std::string> cells;
  if (records.empty()) return cells;
  const auto& h = records.front().fields;
  const auto at = static_cast<std::size_t>(std::find(h.begin(), h.end(), name) - h.begin());
  for (std::size_t r = 1; r < records.size(); ++r)
    cells.push_back(at < records[r].fields.size() ? records[r].fields[at] : "");
  return cells;
}

// --- continuation ---

/// A branch (and the period-2k branch switched to) as arrays, one row per point of branch.csv.
py::dict branch_dict(const rimless::GaitBranch& b) {
  const std::size_t n = b.rows.size(), m = b.state_names.size();
  py::array_t<double> parameter(static_cast<py::ssize_t>(n)), period(static_cast<py::ssize_t>(n)),
      speed(static_cast<py::ssize_t>(n)), dissipated(static_cast<py::ssize_t>(n)),
      residual(static_cast<py::ssize_t>(n));
  py::array_t<bool> stable(static_cast<py::ssize_t>(n));
  py::array_t<std::complex<double>> multipliers({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(m)});
  std::vector<std::vector<double>> state;
  std::vector<std::string> gait, event, mode;
  for (std::size_t i = 0; i < n; ++i) {
    const rimless::GaitBranchRow& r = b.rows[i];
    const auto k = static_cast<py::ssize_t>(i);
    parameter.mutable_at(k) = r.p;
    period.mutable_at(k) = r.period;
    speed.mutable_at(k) = r.speed;
    dissipated.mutable_at(k) = r.dissipated;
    residual.mutable_at(k) = r.point.residual;
    stable.mutable_at(k) = r.point.stable;
    for (std::size_t j = 0; j < m; ++j)
      multipliers.mutable_at(k, static_cast<py::ssize_t>(j)) =
          j < r.point.multipliers.size() ? r.point.multipliers[j] : std::complex<double>(kNaN, kNaN);
    state.emplace_back(r.state.data(), r.state.data() + r.state.size());
    gait.push_back(r.gait);
    event.push_back(r.event);
    mode.push_back(rimless::mode_text(r.section));
  }
  py::dict out;
  out["summary"] = json_value(rimless::gait_branch_summary(b));
  out["parameter"] = parameter;
  out["state_names"] = b.state_names;
  out["state"] = padded_matrix(state);
  out["multipliers"] = multipliers;
  out["stable"] = stable;
  out["period"] = period;
  out["speed"] = speed;
  out["dissipated_per_step"] = dissipated;
  out["residual"] = residual;
  out["gait"] = gait;
  out["mode"] = mode;
  out["event"] = event;
  return out;
}

py::dict continuation(const std::string& param, double start, double stop, double step, const py::object& config,
                      const OptionalPath& config_file, const std::string& section, int period,
                      bool switch_at_period_doubling) {
  const Config c = analysis_config(config, config_file);
  rimless::GaitContinuationSpec spec{.param = param, .from = start, .to = stop, .step = step};
  spec.section = section_of(section);
  spec.period = period;
  spec.switch_at_period_doubling = switch_at_period_doubling;
  spec.tuning = rimless::gait_continuation_from_config(c);
  rimless::GaitBranch b;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;
    spec.on_point = [&interrupted](double) { interrupted(); };
    b = rimless::continue_gait(c, spec);  // ConfigError (ValueError) on bad input
  }
  if (!b.failure.empty()) throw std::runtime_error("continuation: " + b.failure);
  py::dict out = branch_dict(b);
  py::list switched;
  for (const auto& s : b.switched) switched.append(branch_dict(s));
  out["switched"] = switched;
  out["config"] = config_dict(c);
  return out;
}

// --- basin ---

/// "A:B:N" of a str, or of a sequence (from, to, count).
std::string range_text(const py::object& range) {
  if (py::isinstance<py::str>(range)) return range.cast<std::string>();
  if (py::isinstance<py::sequence>(range) && py::len(range) == 3) {
    const auto s = range.cast<py::sequence>();
    return fmt::format("{}:{}:{}", format_number(s[0].cast<double>()), format_number(s[1].cast<double>()),
                       py::str(s[2]).cast<std::string>());
  }
  throw py::value_error("a range is 'FROM:TO:COUNT' or (from, to, count), not " + std::string(py::repr(range)));
}

py::dict basin(const std::string& x, const py::object& x_range, const std::string& y, const py::object& y_range,
               const py::object& config, const OptionalPath& config_file, const std::string& section) {
  const Config c = analysis_config(config, config_file);
  const auto limits = record_from_config<rimless::BasinOptions>(c);
  rimless::BasinSpec spec;
  spec.x = rimless::parse_basin_axis("x_range", x, range_text(x_range));
  spec.y = rimless::parse_basin_axis("y_range", y, range_text(y_range));
  spec.steps_limit = limits.steps_limit;
  spec.tolerance = limits.tolerance;
  spec.no_landing_limit = limits.no_landing_limit;
  spec.section = section_of(section);
  rimless::check_basin(c, spec);
  std::string csv = "index," + rimless::basin_header() + "\n";
  rimless::BasinReference ref;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;
    ref = rimless::basin_reference(c, spec.section);
    for (int i = 0; i < static_cast<int>(spec.cells()); ++i) {
      interrupted();
      csv += std::to_string(i) + "," + rimless::basin_row(c, spec, ref, i) + "\n";
    }
  }
  const auto counts = rimless::basin_counts(csv);
  const std::string area_unit =
      fmt::format("({}) x ({})", c.schema().find(spec.x.key)->unit, c.schema().find(spec.y.key)->unit);
  py::dict out = csv_columns(csv);
  const auto outcome = out["outcome"].cast<std::vector<std::string>>();
  py::array_t<bool> converged({static_cast<py::ssize_t>(spec.y.count), static_cast<py::ssize_t>(spec.x.count)});
  for (std::size_t i = 0; i < outcome.size(); ++i)  // cell i is (x index i % x.count, y index i / x.count)
    converged.mutable_at(static_cast<py::ssize_t>(i) / spec.x.count, static_cast<py::ssize_t>(i) % spec.x.count) =
        outcome[i] == "converged";
  out["converged"] = converged;
  out["summary"] = json_value(rimless::basin_summary(spec, ref, counts, area_unit));
  out["config"] = config_dict(c);
  return out;
}

// --- orbit diagram ---

py::dict orbit_diagram(const std::string& param, double start, double stop, int count, const py::object& config,
                       const OptionalPath& config_file, const std::string& section) {
  const Config c = analysis_config(config, config_file);
  const auto lengths = record_from_config<rimless::OrbitDiagramOptions>(c);
  rimless::check_sweep_param(c.schema(), param);
  if (start == stop)
    throw py::value_error(fmt::format("stop: {} equals start; allowed: a value other than start", stop));
  if (count < 2 || count > kMaxSweepPoints)
    throw py::value_error(fmt::format("count: {}; allowed: an integer in [2, {}]", count, kMaxSweepPoints));
  const rimless::OrbitDiagramSpec spec{
      {param, start, stop, count, section_of(section)}, lengths.transient, lengths.record};
  rimless::check_orbit_diagram(c, spec);
  std::string points = "index," + rimless::orbit_points_header() + "\n";
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;
    for (int i = 0; i < count; ++i) {
      interrupted();
      points += std::to_string(i) + "," + rimless::orbit_points_row(c, spec, i) + "\n";
    }
  }
  // One row per recorded crossing (orbit.csv); its state column as a 2-D array.
  const std::string crossings_csv = rimless::orbit_csv(points);
  const auto records = parse_csv(crossings_csv);
  py::dict crossings = csv_columns(crossings_csv);
  crossings["state"] = vector_rows(column_cells(records, "state"));
  // θ̇ at each value's crossings: (count, record), NaN after a record that stopped early.
  const auto point_records = parse_csv(points);
  std::vector<std::string> thetad = column_cells(point_records, "thetad");
  py::dict out;
  out["parameter"] = typed_column(column_cells(point_records, "value"));
  out["thetad"] = vector_rows(thetad);
  out["crossings"] = crossings;
  out["summary"] = json_value(rimless::orbit_summary(points));
  out["config"] = config_dict(c);
  return out;
}

// --- gait against friction ---

py::dict gait_vs_friction(const std::optional<double>& start, const std::optional<double>& stop,
                          const std::optional<int>& count, const py::object& config, const OptionalPath& config_file,
                          const std::string& section) {
  py::dict extra;
  if (start) extra["analysis.friction.mu_from"] = *start;
  if (stop) extra["analysis.friction.mu_to"] = *stop;
  if (count) extra["analysis.friction.count"] = *count;
  const Config c = analysis_config(config, config_file, extra);
  const rimless::PaperAnalysisOptions paper = rimless::paper_analysis_from_config(c);
  const rimless::SweepSpec spec{"rimless.mu", paper.friction_mu_from, paper.friction_mu_to, paper.friction_count,
                                section_of(section)};
  rimless::check_sweep(c, spec);
  std::string sweep = "index," + rimless::sweep_header() + "\n";
  std::vector<rimless::FrictionGait> gaits;
  std::string thresholds;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;
    const std::function<void()> poll = [&interrupted] { interrupted(); };
    for (int i = 0; i < spec.count; ++i) sweep += std::to_string(i) + "," + rimless::sweep_row(c, spec, i, poll) + "\n";
    std::vector<double> values;
    for (int i = 0; i < spec.count; ++i) values.push_back(spec.value(i));
    gaits = rimless::friction_gaits(c, values, spec.section, paper);
    thresholds = rimless::friction_thresholds_csv(c, gaits, spec.section, paper);
  }
  py::dict out;
  out["sweep"] = csv_columns(sweep, {"state"}, {"multipliers"});
  out["gaits"] = csv_columns(rimless::friction_gaits_csv(gaits));
  out["thresholds"] = csv_columns(thresholds);
  out["config"] = config_dict(c);
  return out;
}

// --- stagnation ---

py::dict stagnation(const py::object& config, const OptionalPath& config_file) {
  const rimless::WheelSetup s = rimless::wheel_setup(analysis_config(config, config_file));
  const rimless::StagnationOptions opt = rimless::stagnation_from_config(s.config);
  rimless::StagnationScan scan;
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;
    rimless::SimulationOptions sim = s.sim;
    sim.poll = [&interrupted] { interrupted(); };
    scan = rimless::scan_stagnation(s.wheel, s.initial, sim, opt);
  }
  py::dict out;
  out["stages"] = csv_columns(rimless::stagnation_csv(scan));
  out["summary"] = json_value(record_json(scan.summary));
  out["config"] = config_dict(s.config);
  return out;
}

}  // namespace

void bind_rimless_maps(py::module_& r) {
  r.def("continuation", &continuation, py::arg("param"), py::arg("start"), py::arg("stop"), py::arg("step") = 0.0,
        py::arg("config") = py::none(), py::arg("config_file") = py::none(), py::arg("section") = "touchdown",
        py::arg("period") = 1, py::arg("switch_at_period_doubling") = false,
        "The periodic gait followed in one real key from `start` to `stop` by pseudo-arclength continuation "
        "(`flexgait rimless continuation`; `step` 0: |stop - start| / 50). Returns a dict, one entry per point of "
        "branch.csv: 'parameter', 'state' (points x state_names, NaN where a point's mode has fewer components), "
        "'multipliers' (complex, points x state_names, NaN where fewer), 'stable' (bool), 'period', 'speed', "
        "'dissipated_per_step', 'residual', 'gait', 'mode', 'event'; 'summary' (param, points, reached_end, "
        "stop_reason, exact_jacobian, period, segments, mode, section); 'switched' (the period-2k branch at the "
        "first period doubling, the same dict, when asked) and 'config'. RuntimeError when the start has no fixed "
        "point.");
  r.def("basin", &basin, py::arg("x"), py::arg("x_range"), py::arg("y"), py::arg("y_range"),
        py::arg("config") = py::none(), py::arg("config_file") = py::none(), py::arg("section") = "touchdown",
        "Basin of attraction of the gait Newton finds from the configured initial state (`rimless analysis "
        "basin`): a grid over two keys of the initial state, `x_range` and `y_range` each (from, to, count) or "
        "'FROM:TO:COUNT'. Returns basin.csv's columns ('x', 'y', 'outcome', 'gait', 'steps', 'distance', "
        "'failure'; cell i at x index i % x_count, y index i // x_count), 'converged' (bool, y_count x x_count), "
        "'summary' (summary.json: reference gait, outcome counts, basin_fraction, basin_area) and 'config'.");
  r.def("orbit_diagram", &orbit_diagram, py::arg("param"), py::arg("start"), py::arg("stop"), py::arg("count"),
        py::arg("config") = py::none(), py::arg("config_file") = py::none(), py::arg("section") = "touchdown",
        "Orbit diagram (`rimless analysis orbit-diagram`): at `count` values of `param`, the section states of "
        "analysis.orbit.record crossings after analysis.orbit.transient steps. Returns 'parameter' (count), "
        "'thetad' (count x record, rad/s; NaN after a record that stopped), 'crossings' (orbit.csv's columns, "
        "'state' as a 2-D array), 'summary' (summary.json: distinct values per parameter, period_one_until, "
        "first_multiple) and 'config'.");
  r.def("gait_vs_friction", &gait_vs_friction, py::arg("start") = py::none(), py::arg("stop") = py::none(),
        py::arg("count") = py::none(), py::arg("config") = py::none(), py::arg("config_file") = py::none(),
        py::arg("section") = "touchdown",
        "The gait against mu = mu_s = mu_k (`rimless analysis gait-vs-friction`; start, stop, count set "
        "analysis.friction.mu_from, mu_to, count). Returns 'sweep' (sweep.csv's columns), 'gaits' (gaits.csv: "
        "the periodic gait at each mu, continued from neighbours where the start finds none), 'thresholds' "
        "(thresholds.csv) and 'config'.");
  r.def("stagnation", &stagnation, py::arg("config") = py::none(), py::arg("config_file") = py::none(),
        "Stagnation near the vertical (`rimless analysis stagnation`, stagnation.* keys): the critical omega0, "
        "the near-vertical time against |omega0 - omega_c|, the stagnation interval. Returns 'summary' "
        "(stagnation.json), 'stages' (stagnation.csv's columns) and 'config'.");
}

}  // namespace flexgait::python
