#include "flexgait/rimless/sweep.hpp"

#include <fmt/format.h>

#include "flexgait/core/text.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"

namespace flexgait::rimless {

void check_sweep_param(const Schema& schema, const std::string& param) {
  if (const ParamAlias* alias = schema.find_alias(param)) {
    check_sweep_param(schema, alias->parts.front());  // an alias's parts are of one type
    return;
  }
  const ParamSpec* p = schema.find(param);
  if (p == nullptr)
    throw ConfigError(param, fmt::format("--param: unknown key '{}'; allowed: a real-valued key of config.yaml, or "
                                         "rimless.mu (sets mu_s and mu_k)",
                                         param));
  if (p->type != ParamType::Real)
    throw ConfigError(param, fmt::format("--param: key '{}' is not a real number; allowed: a real-valued key", param));
}

std::vector<std::string> param_keys(const Schema& schema, const std::string& param) {
  if (const ParamAlias* alias = schema.find_alias(param)) return alias->parts;
  return {param};
}

Config config_at(const Config& base, const std::string& param, const std::string& value, const std::string& origin) {
  Config c = base;
  c.set(param, value, origin);  // an alias (rimless.mu) sets each of its parts
  check_with_origin(c, [&] { validate(wheel_from_config(c), initial_from_config(c)); });
  return c;
}

Config sweep_point_config(const Config& base, const SweepSpec& spec, int i) {
  return config_at(base, spec.param, format_number(spec.value(i)), fmt::format("sweep point {}", i));
}

void check_sweep(const Config& base, const SweepSpec& spec) {
  config_at(base, spec.param, format_number(spec.from), "--from");
  config_at(base, spec.param, format_number(spec.to), "--to");
  for (int i = 0; i < spec.count; ++i) sweep_point_config(base, spec, i);
}

std::string sweep_header() {
  return "value,transient_gait,transient_speed,transient_failure,converged,mode,state,multipliers,max_multiplier,"
         "stable,gait,period,speed,dissipated_per_cycle,residual,iterations,failure";
}

std::string sweep_row(const Config& base, const SweepSpec& spec, int i, const std::function<void()>& poll) {
  const Config c = sweep_point_config(base, spec, i);
  const WheelParams w = wheel_from_config(c);
  const InitialState initial = initial_from_config(c);
  SimulationOptions sim = simulation_from_config(c);
  const AnalysisOptions opt = analysis_from_config(c);
  sim.log = false;
  sim.poll = poll;
  sim.steps = std::max(1, opt.transient_steps);
  const SimulationResult r =
      sim.model == Model::Rigid ? simulate_rigid(w, initial, sim) : simulate_flexible(w, initial, sim);
  std::string transient_gait;
  for (const auto& s : r.steps)
    if (s.complete) transient_gait = step_gait(s);

  std::string row = fmt::format("{},{},{},{}", format_number(spec.value(i)), transient_gait,
                                format_number(r.mean_speed), csv_field(text_of(r.failure)));
  const FixedPointReport fp = find_fixed_point(w, sim, opt, sim.model, spec.section, initial);
  std::string state, mult;
  double max_mult = 0;
  for (Eigen::Index k = 0; k < fp.point.z.size(); ++k) state += (k ? ";" : "") + format_number(fp.point.z(k));
  for (std::size_t k = 0; k < fp.multipliers.size(); ++k) {
    mult += fmt::format("{}{}:{}", k ? ";" : "", format_number(fp.multipliers[k].real()),
                        format_number(fp.multipliers[k].imag()));
    max_mult = std::max(max_mult, std::abs(fp.multipliers[k]));
  }
  // A point without a fixed point has no multiplier, period, speed or energy: empty cells, not 0.
  const auto found = [&](double v) { return fp.converged ? format_number(v) : std::string(); };
  row += fmt::format(",{},{},{},{},{},{},{},{},{},{},{},{},{}", fp.converged ? "true" : "false",
                     fp.point.flight ? "flight" : mode_name(fp.point.mode), state, mult, found(max_mult),
                     fp.stable ? "true" : "false", fp.gait, found(fp.period), found(fp.speed), found(fp.dissipated),
                     format_number(fp.residual), fp.iterations, csv_field(fp.failure()));
  return row;
}

namespace {

bool boolean_text(const std::string& cell) {
  return cell == "true" || cell == "false";
}

/// Items joined by ';' (none: the empty cell), each of which `item` accepts.
template <class Item>
bool list_text(const std::string& cell, const Item& item) {
  if (cell.empty()) return true;
  for (const std::string& part : split_text(cell, ';'))
    if (!item(part)) return false;
  return true;
}

bool number_cell(const std::string& cell) {
  return number_text(cell);
}

}  // namespace

bool sweep_row_valid(const SweepSpec& spec, int i, const std::vector<std::string>& cells) {
  // value,transient_gait,transient_speed,transient_failure,converged,mode,state,multipliers,
  // max_multiplier,stable,gait,period,speed,dissipated_per_cycle,residual,iterations,failure
  if (cells.size() != 17 || cells[0] != format_number(spec.value(i))) return false;
  for (const std::size_t k : {2u, 14u})
    if (!number_cell(cells[k])) return false;
  // (a point without a fixed point leaves max_multiplier, period, speed and the energy empty)
  for (const std::size_t k : {8u, 11u, 12u, 13u})
    if (cells[4] == "false" ? !cells[k].empty() : !number_cell(cells[k])) return false;
  if (!boolean_text(cells[4]) || !boolean_text(cells[9])) return false;
  if (!count_text(cells[15], 1'000'000)) return false;  // Newton's iterations (analysis.max_iterations <= 1000)
  const auto complex_text = [](const std::string& item) {
    const auto colon = item.find(':');
    return colon != std::string::npos && number_text(item.substr(0, colon)) && number_text(item.substr(colon + 1));
  };
  if (!list_text(cells[6], number_cell) || !list_text(cells[7], complex_text)) return false;
  return (cells[4] == "true") == cells[16].empty();
}

}  // namespace flexgait::rimless
