#include "flexgait/campaign/experiment_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "flexgait/core/record.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/experiments/bench_output.hpp"
#include "flexgait/experiments/push_recovery.hpp"
#include "flexgait/experiments/stiffness_bench.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/experiments/walk_output.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/output.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "flexgait/rimless/wheel_setup.hpp"
#include "flexgait/walking/footstep_plan.hpp"

namespace flexgait::campaign {
namespace {

void set_key(Config& config, const std::string& key, const std::string& value, const std::string& origin) {
  config.set(key, value, origin);
}

template <class R>
std::vector<std::string> record_keys() {
  std::vector<std::string> keys;
  for (const auto& f : describe_record<R>()) keys.push_back(f.key);
  return keys;
}

template <class R>
std::vector<std::string> record_types() {
  std::vector<std::string> types;
  for (const auto& f : describe_record<R>()) types.push_back(f.type);
  return types;
}

/// The types of a record's values (as FieldDescription::type), `keys` in order: "" for a null, a
/// text, a list or an object (kinds a value may change between runs).
std::vector<std::string> json_types(const nlohmann::ordered_json& json, const std::vector<std::string>& keys) {
  std::vector<std::string> types;
  for (const auto& k : keys) {
    const auto it = json.find(k);
    std::string type;
    if (it != json.end() && it->is_boolean())
      type = "boolean";
    else if (it != json.end() && it->is_number_integer())
      type = "integer";
    else if (it != json.end() && it->is_number_float())
      type = "real";
    types.push_back(type);
  }
  return types;
}

/// The keys of a record, in order, less `skip`.
std::vector<std::string> json_keys(const nlohmann::ordered_json& json, const std::vector<std::string>& skip) {
  std::vector<std::string> keys;
  for (const auto& item : json.items())
    if (std::find(skip.begin(), skip.end(), item.key()) == skip.end()) keys.push_back(item.key());
  return keys;
}

/// The run directory of a kept point, with its configuration (empty path: none).
std::optional<RunDirectory> kept_run(const Config& config, const std::filesystem::path& run_dir) {
  if (run_dir.empty()) return std::nullopt;
  RunDirectory dir(run_dir);
  dir.write_config(config);
  return dir;
}

Experiment rimless_simulate() {
  Experiment e{"rimless-simulate", "summary.json", rimless::rimless_schema(), set_key, {}, {}, {}};
  e.check = [](const Config& c) { rimless::wheel_setup(c); };
  e.metrics = record_keys<rimless::SimulationResult>();
  e.metrics.insert(e.metrics.begin(), "model");
  e.metric_types = record_types<rimless::SimulationResult>();
  e.metric_types.insert(e.metric_types.begin(), "choice");
  e.run = [](const Config& c, const std::filesystem::path& run_dir) {
    rimless::WheelSetup s = rimless::wheel_setup(c);
    const auto dir = kept_run(c, run_dir);
    s.sim.log = dir.has_value();  // the time series only for a kept run
    const rimless::SimulationResult r = s.sim.model == rimless::Model::Rigid
                                            ? rimless::simulate_rigid(s.wheel, s.initial, s.sim)
                                            : rimless::simulate_flexible(s.wheel, s.initial, s.sim);
    const std::string model = c.choice("sim.model");
    if (dir) rimless::write_run(*dir, r, model);
    return rimless::simulation_summary(r, model);
  };
  // log.csv as rimless::check_log_size projects it, plus events, steps, summary and config.
  e.run_bytes = [](const Config& c) {
    return rimless::projected_log_bytes(rimless::wheel_setup(c).sim) + kSmallRunBytes;
  };
  return e;
}

/// fixed_point.json of `rimless fixed-point` (touchdown section) less its Newton history, with
/// max_multiplier, the largest |multiplier| (null without a fixed point), for the maps. The
/// section is not an axis: on the upright section one orbit has the same multipliers, gait,
/// period and speed (conjugate return maps), only `state` differs, and gaits with flight never
/// reach it (docs/guide/campaigns.md).
nlohmann::ordered_json fixed_point_summary(const rimless::FixedPointReport& r) {
  nlohmann::ordered_json j = rimless::fixed_point_record(r);
  j.erase("history");
  double largest = 0;
  for (const auto& m : r.multipliers) largest = std::max(largest, std::abs(m));
  j["max_multiplier"] = r.converged ? nlohmann::ordered_json(largest) : nlohmann::ordered_json();
  return j;
}

Experiment rimless_fixed_point() {
  Experiment e{"rimless-fixed-point", "fixed_point.json", rimless::rimless_analysis_schema(), set_key, {}, {}, {}};
  e.check = [](const Config& c) { rimless::wheel_setup(c); };
  // Keys that appear only in some reports (last_iterate, jacobian_note) are not columns.
  e.metrics = json_keys(fixed_point_summary(rimless::FixedPointReport{}), {});
  e.metric_types = json_types(fixed_point_summary(rimless::FixedPointReport{}), e.metrics);
  e.run = [](const Config& c, const std::filesystem::path& run_dir) {
    const rimless::WheelSetup s = rimless::wheel_setup(c);
    const rimless::FixedPointReport r = rimless::find_fixed_point(s.wheel, s.sim, rimless::analysis_from_config(c),
                                                                  s.sim.model, rimless::Section::Touchdown, s.initial);
    nlohmann::ordered_json summary = fixed_point_summary(r);
    if (const auto dir = kept_run(c, run_dir)) dir->write("fixed_point.json", rimless::fixed_point_json(r));
    return summary;
  };
  return e;
}

Experiment humanoid_walk() {
  Experiment e{"humanoid-walk", "summary.json", experiments::walk_run_schema(), set_key, {}, {}, {}};
  e.check = [](const Config& c) { experiments::walk_run_from_config(c); };
  e.metrics = record_keys<experiments::WalkMetrics>();
  e.metric_types = record_types<experiments::WalkMetrics>();
  // The walk's planned duration: a point costs about its simulated time (a fall ends it sooner).
  e.cost = [](const Config& c) { return static_cast<double>(c.integer("walk.steps")) * c.real("walk.step_time"); };
  e.run = [](const Config& c, const std::filesystem::path& run_dir) {
    const experiments::WalkRunParams params = experiments::walk_run_from_config(c);
    const experiments::WalkResult r = experiments::run_walk(params);
    if (const auto dir = kept_run(experiments::with_derived_values(c, params), run_dir))
      return experiments::write_walk(*dir, "", r);
    return experiments::walk_summary(r);
  };
  // log.csv and joints.csv get a row every output.log_period over the plan's duration: measured
  // on the builtin robot (13 joints) 457 + 2233 bytes a row; 3 kB a row with room for more joints.
  e.run_bytes = [](const Config& c) {
    constexpr double kRowBytes = 3e3;
    const experiments::WalkRunParams p = experiments::walk_run_from_config(c);
    const double rows = std::floor(walking::plan_footsteps(p.walk).duration / p.log_period) + 1;
    return kRowBytes * rows + kSmallRunBytes;
  };
  return e;
}

Experiment humanoid_bench() {
  Experiment e{"humanoid-bench", "summary.json", experiments::bench_schema(), set_key, {}, {}, {}};
  e.check = [](const Config& c) { experiments::bench_from_config(c); };
  e.metrics = record_keys<experiments::BenchResult>();
  e.metric_types = record_types<experiments::BenchResult>();
  e.run = [](const Config& c, const std::filesystem::path& run_dir) {
    const experiments::BenchResult r = experiments::run_stiffness_bench(experiments::bench_from_config(c));
    nlohmann::ordered_json summary = record_json(r);
    if (const auto dir = kept_run(c, run_dir)) {
      dir->write("bench.csv", experiments::bench_csv(r));
      dir->write("summary.json", json_file_text(summary));
    }
    return summary;
  };
  return e;
}

/// The largest recoverable push of one situation and direction (experiments/push_recovery.hpp):
/// summary.json is the PushRecoveryResult record.
Experiment humanoid_push_recovery() {
  Experiment e{"humanoid-push-recovery", "summary.json", experiments::push_recovery_schema(), set_key, {}, {}, {}};
  e.check = [](const Config& c) { experiments::push_recovery_from_config(c); };
  e.metrics = record_keys<experiments::PushRecoveryResult>();
  e.metric_types = record_types<experiments::PushRecoveryResult>();
  // About 8 runs of the simulated time each run plans; a scan adds about one per scan step up to
  // half the first upper end.
  e.cost = [](const Config& c) {
    const bool standing = c.choice("push_recovery.situation") == "standing";
    const double scan = c.real("push_recovery.scan_step");
    const double runs = 8 + (scan > 0 ? 0.5 * c.real("push_recovery.upper") / scan : 0.0);
    return runs * (standing ? c.real("push_recovery.stand_time") + c.real("push_recovery.settle_time")
                            : static_cast<double>(c.integer("walk.steps")) * c.real("walk.step_time"));
  };
  e.run = [](const Config& c, const std::filesystem::path& run_dir) {
    const experiments::PushRecoveryResult r = experiments::run_push_recovery(experiments::push_recovery_from_config(c));
    nlohmann::ordered_json summary = record_json(r);
    if (const auto dir = kept_run(c, run_dir)) dir->write("summary.json", json_file_text(summary));
    return summary;
  };
  return e;
}

std::vector<Experiment> table() {
  return {rimless_simulate(), rimless_fixed_point(), humanoid_walk(), humanoid_bench(), humanoid_push_recovery()};
}

}  // namespace

bool metric_cell_valid(const std::string& type, const std::string& cell) {
  if (cell.empty()) return true;
  if (type == "real") return parse_finite_number(cell).has_value();
  if (type == "integer") {
    const std::size_t digits = cell.front() == '-' ? 1 : 0;
    return cell.size() > digits && cell.size() <= 20 &&
           cell.find_first_not_of("0123456789", digits) == std::string::npos;
  }
  if (type == "boolean") return cell == "true" || cell == "false";
  if (type == "list of real") {
    for (const std::string& item : split_text(cell, ';'))
      if (!parse_finite_number(item)) return false;
    return true;
  }
  return true;
}

std::vector<std::string> experiment_names() {
  std::vector<std::string> names;
  for (const Experiment& e : table()) names.push_back(e.name);
  return names;
}

Experiment find_experiment(const std::string& name) {
  for (Experiment& e : table())
    if (e.name == name) return std::move(e);
  std::string names;
  for (const auto& n : experiment_names()) names += (names.empty() ? "" : ", ") + n;
  throw UsageError(fmt::format("campaign: unknown experiment '{}'; allowed: {}", one_line(name), names));
}

}  // namespace flexgait::campaign
