#include "schema_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/core/sweep_runner.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/experiments/bench_output.hpp"
#include "flexgait/experiments/compensation_study.hpp"
#include "flexgait/experiments/push_recovery.hpp"
#include "flexgait/experiments/stiffness_bench.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/experiments/walk_output.hpp"
#include "flexgait/rimless/analyses.hpp"
#include "flexgait/rimless/basin.hpp"
#include "flexgait/rimless/gait_branch.hpp"
#include "flexgait/rimless/orbit_diagram.hpp"
#include "flexgait/rimless/output.hpp"
#include "flexgait/rimless/poincare.hpp"
#include "flexgait/rimless/simulation.hpp"
#include "flexgait/rimless/stagnation.hpp"
#include "flexgait/rimless/sweep.hpp"
#include "flexgait/rimless/wheel_setup.hpp"
#include "reproduce_command.hpp"

namespace flexgait::cli {
namespace {

const char* type_name(ParamType type) {
  switch (type) {
    case ParamType::Real:
      return "real";
    case ParamType::Integer:
      return "integer";
    case ParamType::Boolean:
      return "boolean";
    case ParamType::Choice:
      return "choice";
    case ParamType::Text:
      return "text";
    case ParamType::List:
      return "list";
    case ParamType::Reals:
      return "list of real";
  }
  return "?";
}

nlohmann::ordered_json configuration_json(const Schema& schema) {
  nlohmann::ordered_json keys = nlohmann::ordered_json::array();
  for (const ParamSpec& p : schema.params()) {
    nlohmann::ordered_json k;
    k["key"] = p.key;
    k["type"] = type_name(p.type);
    k["default"] = p.derived.empty() ? p.fallback : "auto";
    k["unit"] = p.unit;
    k["doc"] = p.doc;
    k["allowed"] = p.allowed();
    if (!p.derived.empty()) k["derived"] = p.derived;
    if (p.type == ParamType::List) {
      nlohmann::ordered_json fields = nlohmann::ordered_json::array();
      for (const ParamSpec& f : p.item_fields)
        fields.push_back({{"name", f.key},
                          {"type", type_name(f.type)},
                          {"length", f.length},
                          {"unit", f.unit},
                          {"doc", f.doc},
                          {"allowed", f.allowed()},
                          {"optional", f.optional}});
      k["item_fields"] = std::move(fields);
    }
    keys.push_back(std::move(k));
  }
  return keys;
}

/// The schema's aliases: [{key, parts, doc}, ...] (a key that sets each of its parts).
nlohmann::ordered_json aliases_json(const Schema& schema) {
  nlohmann::ordered_json aliases = nlohmann::ordered_json::array();
  for (const ParamAlias& a : schema.aliases()) aliases.push_back({{"key", a.key}, {"parts", a.parts}, {"doc", a.doc}});
  return aliases;
}

/// The columns of a CSV text: its header, as the file's own writer made it (the writers are run on
/// an empty result, so the names are never typed twice).
std::vector<std::string> header_of(const std::string& csv) {
  const std::vector<CsvRecord> records = parse_csv(csv);
  if (records.empty()) throw std::logic_error("a CSV writer wrote no header");
  return records.front().fields;
}

nlohmann::ordered_json table_json(const std::vector<std::string>& columns, std::string_view doc) {
  return {{"doc", doc}, {"columns", columns}};
}

/// joints.csv: one column per leg joint and quantity ("<joint>_<quantity>"), and with
/// control.k_estimation on one more per joint ("k_est_<joint>"): the columns of the walk with the
/// estimation on, those present only then named under "present_when".
nlohmann::ordered_json walk_joints_json() {
  experiments::WalkResult without, with;
  with.k_estimation = true;
  const auto always = header_of(experiments::walk_joints_csv(without));
  const auto all = header_of(experiments::walk_joints_csv(with));
  nlohmann::ordered_json j = table_json(all, "per control period and leg joint: <joint>_<quantity> [rad, Nm]");
  nlohmann::ordered_json only = nlohmann::ordered_json::array();
  for (const auto& c : all)
    if (std::find(always.begin(), always.end(), c) == always.end()) only.push_back(c);
  j["present_when"] = {{"control.k_estimation=true", std::move(only)}};
  return j;
}

/// A sweep's CSV (core/sweep_runner.hpp): the index, then the job's columns.
std::vector<std::string> sweep_columns(const std::string& job_header) {
  return header_of(sweep_file_header(job_header) + "\n");
}

/// branch.csv: the parameter, the section state's components, the step's quantities, a modulus and
/// an argument per multiplier, ...: its state columns are the largest mode's of the model and
/// section, so the columns of every model, section and mode, those not always there under
/// "present_when".
nlohmann::ordered_json gait_branch_json() {
  std::vector<std::vector<std::string>> variants;
  for (const auto& model : enum_names(rimless::Model{}))
    for (const auto& section : enum_names(rimless::Section{}))
      for (const rimless::FootMode mode : {rimless::FootMode::Stick, rimless::FootMode::SlipForward})
        for (const bool flight : {false, true}) {
          const rimless::SectionState state{model.value, section.value, flight, mode, {}};
          rimless::GaitBranch branch;
          branch.state_names = state.names();
          variants.push_back(header_of(rimless::gait_branch_csv(branch)));
        }
  std::vector<std::string> all;
  for (const auto& v : variants)
    for (const auto& c : v)
      if (std::find(all.begin(), all.end(), c) == all.end()) all.push_back(c);
  nlohmann::ordered_json some = nlohmann::ordered_json::array();
  for (const auto& c : all)
    if (!std::all_of(variants.begin(), variants.end(),
                     [&](const auto& v) { return std::find(v.begin(), v.end(), c) != v.end(); }))
      some.push_back(c);
  nlohmann::ordered_json j = table_json(all, "one row per point of the continued branch");
  j["present_when"] = {{"the section state (model, section, foot mode) has the component", std::move(some)}};
  return j;
}

/// The tables of the rimless analyses, from their writers run on no points.
void add_rimless_analysis_tables(nlohmann::ordered_json& t) {
  const Config base = resolve_config(rimless::rimless_analysis_schema(), std::nullopt, {});
  const auto sweep = sweep_columns(rimless::sweep_header());
  t["rimless sweep: sweep.csv"] = table_json(sweep, "one row per parameter value");
  t["rimless analysis gait-vs-friction: sweep.csv"] = table_json(sweep, "one row per value of mu");
  t["rimless analysis gait-vs-friction: gaits.csv"] =
      table_json(header_of(rimless::friction_gaits_csv({})), "one row per value of mu");
  t["rimless analysis gait-vs-friction: thresholds.csv"] =
      table_json(header_of(rimless::friction_thresholds_csv(base, {}, rimless::Section::Touchdown, {})),
                 "one row per threshold between behaviours");
  t["rimless analysis energy: energy.csv"] =
      table_json(header_of(rimless::single_support_energy_csv(base, {})), "one row per logged sample of each mu");
  t["rimless analysis fixed-points: fixed_points.csv"] = table_json(
      header_of(rimless::behaviour_fixed_points_csv(base, {}, rimless::Section::Touchdown)), "one row per mu");
  t["rimless analysis robustness: robustness.csv"] =
      table_json(rimless::robustness_csv_columns(), "one row per perturbed component, sign and epsilon of each mu");
  t["rimless analysis stagnation: stagnation.csv"] =
      table_json(header_of(rimless::stagnation_csv(rimless::StagnationScan{})), "one row per stage");
  t["rimless analysis stagnation-map: stagnation_map.csv"] =
      table_json(sweep_columns(rimless::stagnation_map_header()), "one row per variation");
  t["rimless continuation: branch.csv"] = gait_branch_json();
  t["rimless analysis orbit-diagram: branch_K.csv"] = gait_branch_json();
  t["rimless analysis orbit-diagram: orbit_points.csv"] =
      table_json(sweep_columns(rimless::orbit_points_header()), "one row per parameter value");
  t["rimless analysis orbit-diagram: orbit.csv"] =
      table_json(header_of(rimless::orbit_csv("")), "one row per recorded step of each parameter value");
  t["rimless analysis basin: basin.csv"] =
      table_json(sweep_columns(rimless::basin_header()), "one row per cell of the grid");
}

const char* json_type(const nlohmann::ordered_json& v) {
  if (v.is_boolean()) return "boolean";
  if (v.is_number()) return "number";
  if (v.is_string()) return "text";
  if (v.is_array()) return "list";
  return "object";
}

/// The fields of a JSON document a writer builds by hand (no record behind it), read from the
/// writer's own output: each top-level key with its JSON type, and for a list of objects the keys
/// of its first item ("item_fields").
nlohmann::ordered_json written_fields_json(const std::string& document) {
  const auto doc = nlohmann::ordered_json::parse(document);
  nlohmann::ordered_json fields = nlohmann::ordered_json::array();
  for (const auto& [key, value] : doc.items()) {
    nlohmann::ordered_json f{{"key", key}, {"type", json_type(value)}};
    if (value.is_array() && !value.empty() && value.front().is_object()) {
      nlohmann::ordered_json items = nlohmann::ordered_json::array();
      for (const auto& [k, v] : value.front().items()) items.push_back({{"key", k}, {"type", json_type(v)}});
      f["item_fields"] = std::move(items);
    }
    fields.push_back(std::move(f));
  }
  return {{"fields", std::move(fields)}};
}

/// comparison.json of the compensation and the mismatch studies, from their writers on walks not
/// run (every case of the default configuration, default metrics).
void add_study_results(nlohmann::ordered_json& results) {
  const experiments::WalkRunParams base;
  const auto compensation = experiments::compensation_cases(base);
  results["humanoid compensation: comparison.json"] = written_fields_json(json_file_text(
      experiments::compensation_comparison(compensation, std::vector<experiments::WalkResult>(compensation.size()))));
  const auto mismatch = experiments::mismatch_cases(base, {1.0});
  results["humanoid mismatch: comparison.json"] = written_fields_json(json_file_text(
      experiments::mismatch_comparison(mismatch, std::vector<experiments::WalkResult>(mismatch.size()))));
}

/// summary.json of the basin and of the orbit diagram, from their writers on an empty map.
void add_map_results(nlohmann::ordered_json& results) {
  rimless::BasinSpec basin;
  basin.x = {"initial.omega", 0, 1, 2};
  basin.y = {"initial.beta", 0, 1, 2};
  std::map<std::string, int> none;
  for (const std::string& outcome : rimless::basin_outcomes()) none[outcome] = 0;
  results["rimless analysis basin: summary.json"] =
      written_fields_json(rimless::basin_summary_json(basin, rimless::BasinReference{}, none, ""));
  results["rimless analysis orbit-diagram: summary.json"] =
      written_fields_json(rimless::orbit_summary_json(sweep_file_header(rimless::orbit_points_header()) + "\n"));
}

nlohmann::ordered_json tables_json() {
  nlohmann::ordered_json t;
  const rimless::SimulationResult rimless_run;
  t["rimless simulate: log.csv"] = table_json(header_of(rimless::log_csv(rimless_run)), "one row per logged sample");
  t["rimless simulate: events.csv"] = table_json(header_of(rimless::events_csv(rimless_run)), "one row per event");
  t["rimless simulate: steps.csv"] = table_json(header_of(rimless::steps_csv(rimless_run)), "one row per step");
  const experiments::WalkResult walk;
  t["humanoid walk: log.csv"] = table_json(header_of(experiments::walk_log_csv(walk)), "one row per control period");
  t["humanoid walk: footsteps.csv"] =
      table_json(header_of(experiments::walk_footsteps_csv(walk)), "one row per foot placement, planned and landed");
  t["humanoid walk: joints.csv"] = walk_joints_json();
  t["humanoid bench: bench.csv"] =
      table_json(header_of(experiments::bench_csv(experiments::BenchResult{})), "one row per pose of both sweeps");
  add_rimless_analysis_tables(t);
  return t;
}

}  // namespace

std::string schema_document() {
  nlohmann::ordered_json doc;
  doc["configurations"]["rimless"] = configuration_json(rimless::rimless_analysis_schema());
  doc["configurations"]["humanoid-walk"] = configuration_json(experiments::walk_run_schema());
  doc["configurations"]["humanoid-bench"] = configuration_json(experiments::bench_schema());
  doc["configurations"]["humanoid-push-recovery"] = configuration_json(experiments::push_recovery_schema());
  doc["aliases"]["rimless"] = aliases_json(rimless::rimless_analysis_schema());
  doc["aliases"]["humanoid-walk"] = aliases_json(experiments::walk_run_schema());
  doc["aliases"]["humanoid-bench"] = aliases_json(experiments::bench_schema());
  nlohmann::ordered_json rimless_summary = record_schema_json<rimless::SimulationResult>();
  rimless_summary["fields"].insert(rimless_summary["fields"].begin(),
                                   nlohmann::ordered_json{{"key", "model"},
                                                          {"type", "choice"},
                                                          {"unit", ""},
                                                          {"doc", "sim.model of the run"},
                                                          {"choices", enum_name_list<rimless::Model>()}});
  doc["results"]["rimless simulate: summary.json"] = std::move(rimless_summary);
  doc["results"]["rimless analysis stagnation: stagnation.json"] = record_schema_json<rimless::StagnationSummary>();
  doc["results"]["humanoid walk: summary.json"] = record_schema_json<experiments::WalkMetrics>();
  doc["results"]["humanoid bench: summary.json"] = record_schema_json<experiments::BenchResult>();
  add_study_results(doc["results"]);
  add_map_results(doc["results"]);
  doc["tables"] = tables_json();
  nlohmann::ordered_json runs = nlohmann::ordered_json::object();
  for (const ReproduceRun& r : reproduce_runs()) runs[r.dir] = r.command;
  doc["reproduce"] = std::move(runs);
  return json_file_text(doc);
}

void add_schema_command(CLI::App& app, std::function<int()>& action) {
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "schema", "Every configuration key (type, default, unit, domain) and every summary field (type, unit), as JSON");
  cmd->add_option("--out", *out, "write to this file (atomically) instead of standard output");
  cmd->callback([&action, out] {
    action = [out] {
      if (!out->empty()) check_output_file(*out, "--out");
      const std::string text = schema_document();
      if (out->empty())
        fmt::print("{}", text);
      else
        write_file_atomic(*out, text);
      return 0;
    };
  });
}

}  // namespace flexgait::cli
