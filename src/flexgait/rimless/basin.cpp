#include "flexgait/rimless/basin.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "flexgait/core/record_json.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/sweep.hpp"

namespace flexgait::rimless {
namespace {

/// max_i |a_i - b_i| / scale_i, or infinity when the modes or dimensions differ.
double scaled_distance(const WheelParams& w, const SectionState& a, const SectionState& b) {
  if (a.flight != b.flight || a.mode != b.mode || a.z.size() != b.z.size()) return INFINITY;
  const Eigen::VectorXd s = b.scale(w);
  return ((a.z - b.z).array().abs() / s.array()).maxCoeff();
}

Config cell_config(const Config& base, const BasinSpec& spec, int ix, int iy) {
  const Config c = config_at(base, spec.x.key, format_number(spec.x.value(ix)), fmt::format("--x-range point {}", ix));
  return config_at(c, spec.y.key, format_number(spec.y.value(iy)), fmt::format("--y-range point {}", iy));
}

}  // namespace

BasinAxis parse_basin_axis(const std::string& option, const std::string& key, const std::string& text) {
  const auto bad = [&](const std::string& why) {
    return UsageError(
        fmt::format("{}: '{}' {}; allowed: FROM:TO:COUNT, finite numbers FROM != TO, an integer "
                    "COUNT >= 2 (e.g. 0.5:2.5:100)",
                    option, one_line(text), why));
  };
  const std::vector<std::string> f = split_text(text, ':');
  if (f.size() != 3) throw bad("does not have three fields");
  const auto from = parse_finite_number(f[0]), to = parse_finite_number(f[1]), n = parse_finite_number(f[2]);
  if (!from || !to) throw bad("has a bound that is not a finite number");
  if (*from == *to) throw bad("is an empty range (FROM = TO)");
  if (!n || *n != std::floor(*n) || *n < 2 || *n > 100000)
    throw bad("has a COUNT that is not an integer in [2, 100000]");
  return {key, *from, *to, static_cast<int>(*n)};
}

void check_basin(const Config& base, const BasinSpec& spec) {
  const Schema initial = schema_of<InitialState>();
  for (const auto* a : {&spec.x, &spec.y}) {
    const std::string option = a == &spec.x ? "--x" : "--y";
    const ParamSpec* p = initial.find(a->key);
    if (p == nullptr || p->type != ParamType::Real)
      throw ConfigError(a->key, fmt::format("{}: '{}' is not a key of the initial state; allowed: initial.omega, "
                                            "initial.beta",
                                            option, one_line(a->key)));
  }
  if (spec.x.key == spec.y.key)
    throw ConfigError(
        spec.y.key, fmt::format("--y: '{}' is --x's key too; allowed: the other key of the initial state", spec.y.key));
  if (spec.steps_limit < 1)
    throw ConfigError("--steps-limit", fmt::format("--steps-limit: {}; allowed: an integer >= 1", spec.steps_limit));
  if (!(spec.tolerance > 0) || !std::isfinite(spec.tolerance))
    throw ConfigError("--tolerance", fmt::format("--tolerance: {}; allowed: a finite number > 0", spec.tolerance));
  if (spec.cells() > kMaxBasinCells)
    throw ConfigError("--x-range", fmt::format("--x-range, --y-range: {} x {} = {} cells; allowed: at most {} cells "
                                               "(a coarser grid, or the region of interest in parts)",
                                               spec.x.count, spec.y.count, spec.cells(), kMaxBasinCells));
  for (const int iy : {0, spec.y.count - 1})
    for (const int ix : {0, spec.x.count - 1}) cell_config(base, spec, ix, iy);
}

BasinReference basin_reference(const Config& base, Section section) {
  const WheelParams w = wheel_from_config(base);
  const SimulationOptions sim = simulation_from_config(base);
  const FixedPointReport fp =
      find_fixed_point(w, sim, analysis_from_config(base), sim.model, section, initial_from_config(base));
  BasinReference ref;
  ref.found = fp.converged;
  ref.failure = fp.failure();
  if (!fp.converged) return ref;
  ref.point = fp.point;
  ref.gait = fp.gait;
  ref.stable = fp.stable;
  for (const auto& m : fp.multipliers) ref.max_multiplier = std::max(ref.max_multiplier, std::abs(m));
  return ref;
}

BasinOutcome failure_outcome(const Failure& failure) {
  switch (failure.reason) {
    case FailureReason::RolledBack:
    case FailureReason::FellBack:
      return BasinOutcome::RolledBack;
    case FailureReason::AtRest:
    case FailureReason::NoLanding:
      return BasinOutcome::Stopped;
    case FailureReason::BalancedAtVertical:
      return BasinOutcome::BalancedAtVertical;
    case FailureReason::SlidAway:
      return BasinOutcome::SlidAway;
    case FailureReason::TimeLimit:
      return BasinOutcome::TimeLimit;
    default:
      return BasinOutcome::Failed;
  }
}

std::string basin_header() {
  return "x,y,outcome,gait,steps,distance,failure";
}

std::string basin_row(const Config& base, const BasinSpec& spec, const BasinReference& ref, int cell) {
  const int ix = cell % spec.x.count, iy = cell / spec.x.count;
  const Config c = cell_config(base, spec, ix, iy);
  const WheelParams w = wheel_from_config(c);
  SimulationOptions sim = simulation_from_config(c);
  sim.log = false;
  // The run's length is its number of steps; sim.max_time (meant for one simulate run) does not cut
  // it short. sim.max_step_time still ends a wheel that stops.
  sim.max_time = std::numeric_limits<double>::infinity();
  sim.max_step_time = spec.no_landing_limit;
  const auto row = [&](BasinOutcome outcome, const std::string& gait, int steps, double distance,
                       const std::string& failure) {
    return fmt::format("{},{},{},{},{},{},{}", format_number(spec.x.value(ix)), format_number(spec.y.value(iy)),
                       name_of(outcome), gait, steps, format_number(distance), csv_field(failure));
  };
  SectionState p;
  // The first crossing of the section after the first step (settle simulates >= 1 step); the
  // orbit goes on from crossing to crossing in the full hybrid state (SectionWalk).
  SectionWalk walk(w, sim, sim.model, spec.section);
  if (const auto e = walk.settle(initial_from_config(c), 1, p)) {
    const bool infeasible = e->reason == FailureReason::InitialFootBelowGround;  // a foot below the ground
    return row(infeasible ? BasinOutcome::Infeasible : failure_outcome(*e), "", 0, NAN, e->text());
  }
  std::string gait;
  double distance = ref.found ? scaled_distance(w, p, ref.point) : INFINITY;
  for (int n = 1;; ++n) {
    if (distance <= spec.tolerance)
      return row(BasinOutcome::Converged, gait.empty() ? ref.gait : gait, n, distance, "");
    if (n == spec.steps_limit) return row(BasinOutcome::StepLimit, gait, n, distance, "");
    const MapStep s = walk.step();
    if (s.failure) return row(failure_outcome(*s.failure), gait, n, distance, s.failure->text());
    const double moved = scaled_distance(w, s.next, p);
    p = s.next;
    gait = s.gait;
    distance = ref.found ? scaled_distance(w, p, ref.point) : INFINITY;
    if (moved <= 0.01 * spec.tolerance && distance > 100 * spec.tolerance)
      return row(BasinOutcome::OtherGait, gait, n + 1, distance, "");
  }
}

bool basin_row_valid(const BasinSpec& spec, int cell, const std::vector<std::string>& cells) {
  // x,y,outcome,gait,steps,distance,failure
  const int ix = cell % spec.x.count, iy = cell / spec.x.count;
  const auto& outcomes = basin_outcomes();
  return cells.size() == 7 && cells[0] == format_number(spec.x.value(ix)) &&
         cells[1] == format_number(spec.y.value(iy)) &&
         std::find(outcomes.begin(), outcomes.end(), cells[2]) != outcomes.end() &&
         count_text(cells[4], static_cast<long long>(spec.steps_limit) + 1) && number_text(cells[5]);
}

const std::vector<std::string>& basin_outcomes() {
  static const std::vector<std::string> names = enum_name_list<BasinOutcome>();
  return names;
}

std::map<std::string, int> basin_counts(const std::string& basin_csv) {
  std::map<std::string, int> counts;
  for (const auto& name : basin_outcomes()) counts[name] = 0;
  const std::vector<CsvRecord> records = parse_csv(basin_csv);
  for (std::size_t r = 1; r < records.size(); ++r) ++counts[records[r].fields.at(3)];  // index, x, y, outcome
  return counts;
}

BasinSize basin_size(const BasinSpec& spec, const std::map<std::string, int>& counts) {
  BasinSize b;
  b.converged = counts.at("converged");
  b.fraction = static_cast<double>(b.converged) / static_cast<double>(spec.cells());
  b.cell_area = std::abs(spec.x.spacing() * spec.y.spacing());
  return b;
}

nlohmann::ordered_json basin_summary(const BasinSpec& spec, const BasinReference& ref,
                                     const std::map<std::string, int>& counts, const std::string& area_unit) {
  const BasinSize size = basin_size(spec, counts);
  nlohmann::ordered_json j;
  j["x"] = {{"key", spec.x.key}, {"from", spec.x.from}, {"to", spec.x.to}, {"count", spec.x.count}};
  j["y"] = {{"key", spec.y.key}, {"from", spec.y.from}, {"to", spec.y.to}, {"count", spec.y.count}};
  j["section"] = std::string(name_of(spec.section));
  j["steps_limit"] = spec.steps_limit;
  j["tolerance"] = spec.tolerance;
  j["no_landing_limit"] = spec.no_landing_limit;
  nlohmann::ordered_json r;
  r["found"] = ref.found;
  if (ref.found) {
    nlohmann::ordered_json st;
    const auto names = ref.point.names();
    for (Eigen::Index k = 0; k < ref.point.z.size(); ++k) st[names.at(static_cast<std::size_t>(k))] = ref.point.z(k);
    r["state"] = st;
    r["mode"] = ref.point.flight ? "flight" : mode_name(ref.point.mode);
    r["gait"] = ref.gait;
    r["stable"] = ref.stable;
    r["max_multiplier"] = ref.max_multiplier;
  } else {
    r["failure"] = ref.failure;
  }
  j["reference"] = r;
  nlohmann::ordered_json outcomes;
  for (const auto& name : basin_outcomes()) outcomes[name] = counts.at(name);
  j["outcomes"] = outcomes;
  j["cells"] = spec.cells();
  j["basin_fraction"] = size.fraction;
  j["cell_area"] = size.cell_area;
  j["basin_area"] = size.area();
  j["area_unit"] = area_unit;
  return j;
}

std::string basin_summary_json(const BasinSpec& spec, const BasinReference& ref,
                               const std::map<std::string, int>& counts, const std::string& area_unit) {
  return json_file_text(basin_summary(spec, ref, counts, area_unit));
}

}  // namespace flexgait::rimless
