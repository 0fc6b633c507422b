#pragma once
/// \file experiment_table.hpp
/// The experiments a campaign can run: each yields one summary per configuration. An entry maps
/// a name to its configuration schema, the checks a complete configuration must pass, the
/// summary's keys (the columns of campaign.csv, the same names as the experiment's own
/// summary.json) and the run of one point. Adding an experiment to campaigns is one entry here.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"

namespace flexgait::campaign {

struct Experiment {
  std::string name;     ///< as on the command line: rimless-simulate, humanoid-walk, ...
  std::string summary;  ///< the file its command writes the summary to, e.g. "summary.json"
  Schema schema;        ///< the keys it accepts (--config, --set, --grid)
  /// Sets key = value in `config` under `origin`, validated (ConfigError otherwise). Aliases such
  /// as rimless.mu (sets rimless.mu_s and rimless.mu_k) are resolved here.
  std::function<void(Config& config, const std::string& key, const std::string& value, const std::string& origin)> set;
  /// The cross-key checks of a complete configuration (throws ConfigError with the key's origin).
  std::function<void(const Config& config)> check;
  /// The summary's keys, in the summary's order (the metric columns).
  std::vector<std::string> metrics;
  /// Runs one point: returns its summary record (an object: the metrics by key, with their JSON
  /// types; the same record the experiment's own summary file holds). If `run_dir` is not empty,
  /// the run's files go there too (config.yaml and the summary at least). Thread-safe.
  std::function<nlohmann::ordered_json(const Config& config, const std::filesystem::path& run_dir)> run;
  /// The estimated cost of a point, in any unit (humanoid-walk: the simulated time it plans);
  /// empty: all points alike. Only the order the points are handed out depends on it.
  std::function<double(const Config& config)> cost = {};
  /// The type of each metric's cells, as FieldDescription::type names it ("real", "integer",
  /// "boolean", "list of real", ...); "" when not known. A resumed row's cells are checked by it.
  std::vector<std::string> metric_types = {};
  /// The projected size of one point's run files when they are kept (campaign --keep-runs)
  /// [bytes]; empty: a few files of a few kB (kSmallRunBytes).
  std::function<double(const Config& config)> run_bytes = {};
};

/// What a kept run writes at least (config.yaml, the summary, small tables) [bytes]: the builtin
/// robot's config.yaml alone is ~19 kB.
inline constexpr double kSmallRunBytes = 64e3;

/// Whether `cell` (campaign.csv's text of one summary value) can be a value of type `type`
/// (Experiment::metric_types): empty (null) always; "real" a finite number; "integer" an integer;
/// "boolean" true or false; "list of real" finite numbers joined by ';'; any text otherwise.
bool metric_cell_valid(const std::string& type, const std::string& cell);

/// The names of the experiments, in table order.
std::vector<std::string> experiment_names();

/// The experiment called `name`; throws UsageError listing the names if there is none.
Experiment find_experiment(const std::string& name);

}  // namespace flexgait::campaign
