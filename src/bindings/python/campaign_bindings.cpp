// flexgait.campaign: an experiment at every point of a grid of configuration keys — the rows of
// `flexgait campaign`'s campaign.csv, computed by the same Campaign (campaign/campaign.hpp).
#include <pybind11/stl.h>

#include <cmath>

#include <fmt/format.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "flexgait/campaign/campaign.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait::python {
namespace {

/// One grid value as configuration text: a bool as true/false, a number in shortest round-trip
/// form, a str as it is.
std::string value_text(const std::string& key, const py::handle& v) {
  const py::module_ numbers = py::module_::import("numbers");
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance(v, numbers.attr("Integral"))) return py::str(py::int_(py::reinterpret_borrow<py::object>(v)));
  if (py::isinstance(v, numbers.attr("Real"))) {
    const double x = py::float_(py::reinterpret_borrow<py::object>(v));
    if (!std::isfinite(x)) throw py::value_error(fmt::format("grid '{}': {} is not a finite number", one_line(key), x));
    return format_number(x);
  }
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  throw py::value_error(fmt::format("grid '{}': a value must be a float, int, bool or str, not {}", one_line(key),
                                    std::string(py::str(v.get_type().attr("__name__")))));
}

/// The grid's axes, in the dict's order: {key: [v1, v2, ...]} or {key: 'A:B:N'} (N values from A
/// to B, ends included), each read as `flexgait campaign --grid KEY=...` reads it.
std::vector<campaign::GridAxis> grid_axes(const py::dict& grid) {
  std::vector<campaign::GridAxis> axes;
  for (const auto& [k, v] : grid) {
    if (!py::isinstance<py::str>(k)) throw py::type_error("grid keys must be str, e.g. 'rimless.mu_s'");
    const std::string key = k.cast<std::string>();
    std::string values;
    if (py::isinstance<py::str>(v)) {
      values = v.cast<std::string>();
    } else if (py::isinstance<py::sequence>(v)) {
      for (const auto& item : v.cast<py::sequence>()) values += (values.empty() ? "" : ",") + value_text(key, item);
    } else {
      values = value_text(key, v);
    }
    axes.push_back(campaign::parse_grid_axis(key + "=" + values));
  }
  return axes;
}

py::dict run_campaign(const std::string& name, const py::dict& grid, const py::object& config,
                      const std::optional<std::string>& config_file) {
  campaign::Experiment experiment = campaign::find_experiment(name);
  const Config base = make_config(experiment.schema, config, config_file);
  const campaign::Campaign c(std::move(experiment), base, campaign::Grid(grid_axes(grid)));
  std::string csv = "index," + c.header() + "\n";
  {
    py::gil_scoped_release release;
    InterruptCheck interrupted;
    for (int i = 0; i < c.size(); ++i) {
      interrupted();
      csv += std::to_string(i) + "," + c.row(i) + "\n";
    }
  }
  py::dict points = csv_columns(csv);
  int errors = 0;
  for (const auto& e : points["error"].cast<std::vector<std::string>>()) errors += e.empty() ? 0 : 1;
  py::dict summary;
  summary["experiment"] = c.experiment().name;
  summary["points"] = c.size();
  summary["errors"] = errors;
  summary["metrics"] = c.experiment().metrics;
  py::dict out;
  out["points"] = points;
  out["summary"] = summary;
  out["config"] = config_dict(base);
  return out;
}

}  // namespace

void bind_campaign(py::module_& m) {
  m.def("campaign", &run_campaign, py::arg("experiment"), py::arg("grid"), py::arg("config") = py::none(),
        py::arg("config_file") = py::none(),
        "Run `experiment` (rimless-simulate, rimless-fixed-point, humanoid-walk, humanoid-bench, "
        "humanoid-push-recovery) at every point of the Cartesian product of `grid`'s axes, {key: [values]} or "
        "{key: 'A:B:N'}, over `config` (`flexgait campaign EXPERIMENT --grid ...`; every point is checked before "
        "any runs). Returns 'points' (campaign.csv's columns: index, the axes, each summary metric -- numbers as "
        "float arrays with NaN where a point failed or has none, true/false as bool arrays -- and 'error'), "
        "'summary' (experiment, points, errors, metrics) and 'config' (the base). Runs in this thread with the "
        "GIL released.");
}

}  // namespace flexgait::python
