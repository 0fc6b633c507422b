#include "flexgait/campaign/campaign.hpp"

#include <fmt/format.h>

#include <algorithm>
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
      for (std::size_t k = 0; k < v.size(); ++k)
        out += (k ? (depth == 0 ? ";" : ":") : "") + cell_text(v[k], depth + 1);
      return out;
    }
    default:
      return v.dump();
  }
}

bool is_sample_axis(const RandomDesign& random, const GridAxis& axis) {
  return !random.empty() && axis.key == RandomDesign::kSampleAxis;
}

/// The configuration keys one axis writes (an alias writes several: rimless.mu sets
/// rimless.mu_s and rimless.mu_k), under the axis's option text ("--grid rimless.mu").
struct AxisKeys {
  std::string axis;
  std::vector<std::string> keys;
};

/// The keys of `c` whose value came from `origin`, in schema order.
std::vector<std::string> keys_with_origin(const Config& c, const std::string& origin) {
  std::vector<std::string> keys;
  for (const ParamSpec& p : c.schema().params())
    if (c.origin(p.key) == origin) keys.push_back(p.key);
  return keys;
}

std::string listed(const std::vector<std::string>& keys) {
  std::string out;
  for (const auto& k : keys) out += (out.empty() ? "" : " and ") + k;
  return out;
}

/// Throws UsageError if two axes write the same key (an alias and one of its parts: the table
/// would label points with values that were never run), or if an axis writes a key that --set
/// gave (the axis would silently replace the --set value in every point). Values from a --config
/// file are the base a grid varies, and stay allowed.
void check_axes_apart(const std::vector<AxisKeys>& written, const Config& base) {
  for (std::size_t a = 0; a < written.size(); ++a) {
    for (std::size_t b = 0; b < a; ++b)
      for (const std::string& key : written[a].keys)
        if (std::find(written[b].keys.begin(), written[b].keys.end(), key) != written[b].keys.end())
          throw UsageError(fmt::format("{} and {} both set {} ({} sets {}; {} sets {}); give only one of them",
                                       one_line(written[b].axis), one_line(written[a].axis), key,
                                       one_line(written[b].axis), listed(written[b].keys), one_line(written[a].axis),
                                       listed(written[a].keys)));
    for (const std::string& key : written[a].keys)
      if (base.origin(key) == "--set")
        throw UsageError(
            fmt::format("--set {} and {} both set {}: the axis's values would replace the --set value at "
                        "every point; give only one of them",
                        key, one_line(written[a].axis), key));
  }
}

}  // namespace

std::string summary_cells(const nlohmann::ordered_json& j, const std::vector<std::string>& metrics) {
  std::string out;
  for (std::size_t k = 0; k < metrics.size(); ++k) {
    if (k) out += ',';
    const auto it = j.find(metrics[k]);
    if (it != j.end()) out += csv_field(cell_text(*it));
  }
  return out;
}

Campaign::Campaign(Experiment experiment, Config base, Grid grid, RandomDesign random)
    : experiment_(std::move(experiment)), base_(std::move(base)), grid_(std::move(grid)), random_(std::move(random)) {
  if (!random_.empty()) {
    const auto& axes = grid_.axes();
    if (axes.back().key != RandomDesign::kSampleAxis || axes.back().values != random_.sample_axis().values)
      throw UsageError("campaign: the random design's sample axis must be the grid's last axis");
    for (const RandomAxis& r : random_.axes())
      for (const GridAxis& g : axes)
        if (g.key == r.key) throw UsageError(fmt::format("--random: key '{}' is also a --grid axis", one_line(r.key)));
  }
  experiment_.check(base_);
  std::vector<AxisKeys> written;               // the keys each axis writes
  for (const GridAxis& axis : grid_.axes()) {  // each value alone: the domain of its key
    if (is_sample_axis(random_, axis)) continue;
    for (const std::string& value : axis.values) {
      Config c = base_;
      experiment_.set(c, axis.key, value, "--grid " + axis.key);
      if (&value == &axis.values.front())
        written.push_back({"--grid " + axis.key, keys_with_origin(c, "--grid " + axis.key)});
    }
  }
  for (const RandomAxis& axis : random_.axes())  // each end alone: the domain of its key
    for (const double end : {axis.low, axis.high}) {
      Config c = base_;
      experiment_.set(c, axis.key, format_number(end), "--random " + axis.key);
      if (end == axis.low) written.push_back({"--random " + axis.key, keys_with_origin(c, "--random " + axis.key)});
    }
  check_axes_apart(written, base_);
  for (int i = 0; i < size(); ++i) point_config(i);  // each combination: the cross-key checks
}

Config Campaign::point_config(int i) const {
  const std::vector<std::string> values = grid_.point(i);
  Config c = base_;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const GridAxis& axis = grid_.axes()[k];
    if (is_sample_axis(random_, axis)) {
      const int sample = std::stoi(values[k]);
      for (std::size_t r = 0; r < random_.axes().size(); ++r) {
        const std::string& key = random_.axes()[r].key;
        experiment_.set(c, key, random_.value(sample, r), "--random " + key);
      }
    } else {
      experiment_.set(c, axis.key, values[k], "--grid " + axis.key);
    }
  }
  try {
    experiment_.check(c);
  } catch (const ConfigError& e) {
    throw ConfigError(e.key(), fmt::format("--grid point {} ({}): {}", i, point_text(i), e.what()));
  }
  return c;
}

double Campaign::cost(int i) const {
  return experiment_.cost ? experiment_.cost(point_config(i)) : 1.0;
}

std::string Campaign::header() const {
  std::string out;
  for (const GridAxis& axis : grid_.axes()) out += csv_field(axis.key) + ",";
  for (const RandomAxis& axis : random_.axes()) out += csv_field(axis.key) + ",";
  for (const std::string& m : experiment_.metrics) out += csv_field(m) + ",";
  return out + "error";
}

std::vector<std::string> Campaign::point_values(int i) const {
  std::vector<std::string> values = grid_.point(i);
  if (!random_.empty()) {
    const int sample = i % random_.samples();  // the sample axis is last, the fastest
    for (std::size_t r = 0; r < random_.axes().size(); ++r) values.push_back(random_.value(sample, r));
  }
  return values;
}

std::string Campaign::point_text(int i) const {
  const std::vector<std::string> values = point_values(i);
  std::string out;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::size_t axes = grid_.axes().size();
    out +=
        fmt::format("{}{}={}", k ? ", " : "", k < axes ? grid_.axes()[k].key : random_.axes()[k - axes].key, values[k]);
  }
  return out;
}

std::string Campaign::row(int i, const std::filesystem::path& run_dir) const {
  std::string out;
  for (const std::string& v : point_values(i)) out += csv_field(v) + ",";
  try {
    return out + summary_cells(experiment_.run(point_config(i), run_dir), experiment_.metrics) + ",";
  } catch (const std::exception& e) {  // a point that cannot run is a row with its reason
    return out + std::string(experiment_.metrics.size() - 1, ',') + "," + csv_field(one_line(e.what(), 1000));
  }
}

bool Campaign::row_valid(int i, const std::vector<std::string>& cells) const {
  const std::vector<std::string> values = point_values(i);
  const std::size_t metrics = experiment_.metrics.size();
  if (cells.size() != values.size() + metrics + 1 || !std::equal(values.begin(), values.end(), cells.begin()))
    return false;
  const bool failed = !cells.back().empty();
  for (std::size_t m = 0; m < metrics; ++m) {
    const std::string& cell = cells[values.size() + m];
    const std::string type = m < experiment_.metric_types.size() ? experiment_.metric_types[m] : "";
    if ((failed && !cell.empty()) || !metric_cell_valid(type, cell)) return false;
  }
  return true;
}

std::string Campaign::signature() const {
  std::string out = fmt::format("flexgait {}\ncampaign {}\n", program_build(), experiment_.name);
  for (const GridAxis& axis : grid_.axes()) {
    out += "grid " + axis.key + "=";
    for (std::size_t k = 0; k < axis.values.size(); ++k) out += (k ? "," : "") + axis.values[k];
    out += "\n";
  }
  for (const RandomAxis& axis : random_.axes()) out += "random " + axis.given + "\n";
  if (!random_.empty()) out += fmt::format("samples {} seed {}\n", random_.samples(), random_.seed());
  return out + "base configuration:\n" + base_.to_yaml();
}

std::string Campaign::config_yaml() const {
  std::string out = fmt::format("# campaign of {} (flexgait {}): the base configuration below, and the grid\n",
                                experiment_.name, program_build());
  for (const GridAxis& axis : grid_.axes())
    out += fmt::format("#   --grid {}  ({} values{})\n", one_line(axis.given, 1000), axis.values.size(),
                       is_sample_axis(random_, axis)
                           ? fmt::format(": --samples {} --seed {}", random_.samples(), random_.seed())
                           : "");
  for (const RandomAxis& axis : random_.axes())
    out += fmt::format("#   --random {}  (drawn at each sample)\n", one_line(axis.given, 1000));
  return out + base_.to_yaml();
}

double kept_runs_bytes(const Campaign& campaign) {
  const Experiment& e = campaign.experiment();
  double bytes = 0;
  for (int i = 0; i < campaign.size(); ++i)
    bytes += e.run_bytes ? e.run_bytes(campaign.point_config(i)) : kSmallRunBytes;
  return bytes;
}

void check_kept_runs_size(const Campaign& campaign, double max_bytes) {
  const double bytes = kept_runs_bytes(campaign);
  if (bytes <= max_bytes) return;
  throw UsageError(
      fmt::format("--keep-runs: the {} points' run files could reach {:.3g} bytes (their logs as each run projects "
                  "them), above --max-run-bytes = {:.3g}; allowed: fewer points, sparser logs (sim.sample_dt, "
                  "output.log_period), no --keep-runs, or --max-run-bytes raised to at least {:.3g}",
                  campaign.size(), bytes, max_bytes, bytes));
}

SweepOutcome run_campaign(const Campaign& campaign, const CampaignRun& run) {
  SweepJob job;
  job.dir = run.dir;
  job.name = "campaign";
  job.noun = "campaign";
  job.valid_row = [&campaign](int i, const std::vector<std::string>& cells) { return campaign.row_valid(i, cells); };
  job.header = campaign.header();
  job.count = campaign.size();
  job.jobs = run.jobs;
  job.resume = run.resume;
  job.signature = campaign.signature();
  job.distributor = run.distributor;
  job.cost = [&campaign](int i) { return campaign.cost(i); };
  std::optional<RunDirectory> own;  // marks the directory complete as run_campaign returns
  std::optional<RunDirectory>& directory = run.directory != nullptr ? *run.directory : own;
  job.prepare = [&] {
    directory.emplace(run.dir);
    directory->write("config.yaml", campaign.config_yaml());
  };
  const std::filesystem::path runs = run.keep_runs ? run.dir / "runs" : std::filesystem::path();
  job.row = [&campaign, runs](int i) { return campaign.row(i, runs.empty() ? runs : runs / fmt::format("{:06d}", i)); };
  return run_sweep(job);
}

}  // namespace flexgait::campaign
