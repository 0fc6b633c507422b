#include "schema_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <vector>
#include <nlohmann/json.hpp>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/experiments/bench_output.hpp"
#include "flexgait/experiments/stiffness_bench.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/experiments/walk_output.hpp"
#include "flexgait/rimless/output.hpp"
#include "flexgait/rimless/simulation.hpp"
#include "flexgait/rimless/stagnation.hpp"
#include "flexgait/rimless/wheel_setup.hpp"

namespace flexgait::cli {
namespace {

const char* type_name(ParamType type) {
  switch (type) {
    case ParamType::Real: return "real";
    case ParamType::Integer: return "integer";
    case ParamType::Boolean: return "boolean";
    case ParamType::Choice: return "choice";
    case ParamType::Text: return "text";
    case ParamType::List: return "list";
    case ParamType::Reals: return "list of real";
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
        fields.push_back({{"name", f.key}, {"type", type_name(f.type)}, {"length", f.length}, {"unit", f.unit},
                          {"doc", f.doc}, {"allowed", f.allowed()}, {"optional", f.optional}});
      k["item_fields"] = std::move(fields);
    }
    keys.push_back(std::move(k));
  }
  return keys;
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
  return t;
}

}  // namespace

std::string schema_document() {
  nlohmann::ordered_json doc;
  doc["configurations"]["rimless"] = configuration_json(rimless::rimless_analysis_schema());
  doc["configurations"]["humanoid-walk"] = configuration_json(experiments::walk_run_schema());
  doc["configurations"]["humanoid-bench"] = configuration_json(experiments::bench_schema());
  nlohmann::ordered_json rimless_summary = record_schema_json<rimless::SimulationResult>();
  rimless_summary["fields"].insert(rimless_summary["fields"].begin(),
                                   nlohmann::ordered_json{{"key", "model"}, {"type", "choice"}, {"unit", ""},
                                                          {"doc", "sim.model of the run"},
                                                          {"choices", enum_name_list<rimless::Model>()}});
  doc["results"]["rimless simulate: summary.json"] = std::move(rimless_summary);
  doc["results"]["rimless analysis stagnation: stagnation.json"] = record_schema_json<rimless::StagnationSummary>();
  doc["results"]["humanoid walk: summary.json"] = record_schema_json<experiments::WalkMetrics>();
  doc["results"]["humanoid bench: summary.json"] = record_schema_json<experiments::BenchResult>();
  doc["tables"] = tables_json();
  return doc.dump(2) + "\n";
}

void add_schema_command(CLI::App& app, std::function<int()>& action) {
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "schema", "Every configuration key (type, default, unit, domain) and every summary field (type, unit), as JSON");
  cmd->add_option("--out", *out, "write to this file (atomically) instead of standard output");
  cmd->callback([&action, out] {
    action = [out] {
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
