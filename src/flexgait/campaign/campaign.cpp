#include "flexgait/campaign/campaign.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "flexgait/campaign/program_build.hpp"
#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait::campaign {
namespace {

// One JSON value as cell text (before CSV quoting): lists joined by ';', a list inside a list by ':'.
std::string cell_text(const nlohmann::ordered_json& v, int depth = 0) {
  switch (v.type()) {
    case nlohmann::json::value_t::null:
    case nlohmann::json::value_t::discarded:
      return "";
    case nlohmann::json::value_t::boolean:
      return v.get<bool>() ? "true" : "false";
    case nlohmann::json::value_t::number_integer:
      return std::to_string(v.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return std::to_string(v.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float:
      return format_number(v.get<double>());
    case nlohmann::json::value_t::string:
      return v.get<std::string>();
    case nlohmann::json::value_t::array: {
      std::string out;
      for (std::size_t k = 0; k < v.size(); ++k) out += (k ? (depth == 0 ? ";" : ":") : "") + cell_text(v[k], depth + 1);
      return out;
    }
    default:
      return v.dump();
  }
}

std::string axes_text(const Grid& grid, const std::vector<std::string>& values) {
  std::string out;
  for (std::size_t k = 0; k < values.size(); ++k)
    out += fmt::format("{}{}={}", k ? ", " : "", grid.axes()[k].key, values[k]);
  return out;
}

}  // namespace

std::string summary_cells(const std::string& summary_json, const std::vector<std::string>& metrics) {
  const auto j = nlohmann::ordered_json::parse(summary_json);
  std::string out;
  for (std::size_t k = 0; k < metrics.size(); ++k) {
    if (k) out += ',';
    const auto it = j.find(metrics[k]);
    if (it != j.end()) out += csv_field(cell_text(*it));
  }
  return out;
}

Campaign::Campaign(Experiment experiment, Config base, Grid grid)
    : experiment_(std::move(experiment)), base_(std::move(base)), grid_(std::move(grid)) {
  experiment_.check(base_);
  for (const GridAxis& axis : grid_.axes())  // each value alone: the domain of its key
    for (const std::string& value : axis.values) {
      Config c = base_;
      experiment_.set(c, axis.key, value, "--grid " + axis.key);
    }
  for (int i = 0; i < size(); ++i) point_config(i);  // each combination: the cross-key checks
}

Config Campaign::point_config(int i) const {
  const std::vector<std::string> values = grid_.point(i);
  Config c = base_;
  for (std::size_t k = 0; k < values.size(); ++k)
    experiment_.set(c, grid_.axes()[k].key, values[k], "--grid " + grid_.axes()[k].key);
  try {
    experiment_.check(c);
  } catch (const ConfigError& e) {
    throw ConfigError(e.key(), fmt::format("--grid point {} ({}): {}", i, axes_text(grid_, values), e.what()));
  }
  return c;
}

double Campaign::cost(int i) const { return experiment_.cost ? experiment_.cost(point_config(i)) : 1.0; }

std::string Campaign::header() const {
  std::string out;
  for (const GridAxis& axis : grid_.axes()) out += csv_field(axis.key) + ",";
  for (const std::string& m : experiment_.metrics) out += csv_field(m) + ",";
  return out + "error";
}

std::string Campaign::row(int i, const std::filesystem::path& run_dir) const {
  std::string out;
  for (const std::string& v : grid_.point(i)) out += csv_field(v) + ",";
  try {
    return out + summary_cells(experiment_.run(point_config(i), run_dir), experiment_.metrics) + ",";
  } catch (const std::exception& e) {  // a point that cannot run is a row with its reason
    return out + std::string(experiment_.metrics.size() - 1, ',') + "," + csv_field(one_line(e.what(), 1000));
  }
}

std::string Campaign::signature() const {
  std::string out = fmt::format("flexgait {}\ncampaign {}\n", program_build(), experiment_.name);
  for (const GridAxis& axis : grid_.axes()) {
    out += "grid " + axis.key + "=";
    for (std::size_t k = 0; k < axis.values.size(); ++k) out += (k ? "," : "") + axis.values[k];
    out += "\n";
  }
  return out + "base configuration:\n" + base_.to_yaml();
}

std::string Campaign::config_yaml() const {
  std::string out = fmt::format("# campaign of {} (flexgait {}): the base configuration below, and the grid\n",
                                experiment_.name, program_build());
  for (const GridAxis& axis : grid_.axes())
    out += fmt::format("#   --grid {}  ({} values)\n", one_line(axis.given, 1000), axis.values.size());
  return out + base_.to_yaml();
}

SweepOutcome run_campaign(const Campaign& campaign, const CampaignRun& run) {
  SweepJob job;
  job.dir = run.dir;
  job.name = "campaign";
  job.header = campaign.header();
  job.count = campaign.size();
  job.jobs = run.jobs;
  job.resume = run.resume;
  job.signature = campaign.signature();
  job.distributor = run.distributor;
  job.cost = [&campaign](int i) { return campaign.cost(i); };
  job.prepare = [&] { write_file_atomic(run.dir / "config.yaml", campaign.config_yaml()); };
  const std::filesystem::path runs = run.keep_runs ? run.dir / "runs" : std::filesystem::path();
  job.row = [&campaign, runs](int i) {
    return campaign.row(i, runs.empty() ? runs : runs / fmt::format("{:06d}", i));
  };
  return run_sweep(job);
}

}  // namespace flexgait::campaign
