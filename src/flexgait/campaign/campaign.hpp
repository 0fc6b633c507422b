#pragma once
/// \file campaign.hpp
/// A campaign: one experiment (experiment_table.hpp) run at every point of a grid (grid.hpp),
/// each point the base configuration plus the point's keys. Every point is checked before
/// anything runs; the points run on the sweep runner (core/sweep_runner.hpp: threads or MPI
/// ranks, a durable partial file, resume by signature), and DIR gets
///   campaign.csv  index, the axis values, the drawn values of the --random keys (random_design.hpp),
///                 the summary's metrics flattened (same names as the experiment's summary),
///                 `error` (why a point could not run; empty otherwise);
///                 one row per point, sorted by index, the same bytes whatever the threads,
///                 ranks and resumes;
///   config.yaml   the base configuration (loadable with --config), the axes in its header;
///   runs/NNNNNN/  each point's run files (keep_runs only);
///   complete      the RunDirectory marker: the campaign finished (core/run_directory.hpp).
/// Cells: numbers as format_number, booleans true/false, null empty, lists joined by ';' (pairs
/// such as a multiplier's re, im by ':'), text quoted as CSV needs.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "flexgait/campaign/experiment_table.hpp"
#include "flexgait/campaign/grid.hpp"
#include "flexgait/campaign/random_design.hpp"
#include "flexgait/core/config.hpp"
#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/sweep_runner.hpp"

namespace flexgait::campaign {

class Campaign {
 public:
  /// Checks the base configuration and every point: each axis value alone (a ConfigError whose
  /// message starts "--grid KEY: ..."), then each point's whole configuration ("--grid point I
  /// (KEY=V, ...): ..."). Nothing runs and nothing is written here. With random keys, `grid` has
  /// the design's sample axis last (a UsageError otherwise, or if a random key is a --grid key);
  /// each random axis's ends are checked like a grid value ("--random KEY: ...").
  Campaign(Experiment experiment, Config base, Grid grid, RandomDesign random = {});

  const Experiment& experiment() const { return experiment_; }
  const Grid& grid() const { return grid_; }
  const RandomDesign& random() const { return random_; }
  int size() const { return grid_.size(); }
  /// The checked configuration of point i.
  Config point_config(int i) const;
  /// The estimated cost of point i (Experiment::cost; 1 without one): points run most expensive first.
  double cost(int i) const;
  /// campaign.csv's header without "index": the axis keys, the random keys, the metrics, error.
  std::string header() const;
  /// Point i's cells (no index): never throws for a failing run; its message goes to `error`.
  /// `run_dir` not empty: the point's run files go there.
  std::string row(int i, const std::filesystem::path& run_dir = {}) const;
  /// Whether `cells` (a resumed row's fields after the index) can be row(i)'s: the point's own
  /// axis and drawn values exactly, each metric's cell of its type (metric_cell_valid), and either
  /// an empty `error` or no metric at all (a point that could not run).
  bool row_valid(int i, const std::vector<std::string>& cells) const;
  /// What a resumed campaign must match: the program's build (program_build.hpp: version and git
  /// describe), experiment, axes, base configuration.
  std::string signature() const;
  /// config.yaml: the axes as comments, then the base configuration.
  std::string config_yaml() const;

 private:
  /// Point i's cells before the metrics: the axis values, then the drawn random values.
  std::vector<std::string> point_values(int i) const;
  /// "KEY=V, ..." of point i, for messages.
  std::string point_text(int i) const;

  Experiment experiment_;
  Config base_;
  Grid grid_;
  RandomDesign random_;
};

/// The projected size of every point's run files when kept (Experiment::run_bytes) [bytes].
double kept_runs_bytes(const Campaign& campaign);
/// Throws UsageError naming --keep-runs and --max-run-bytes if kept_runs_bytes exceeds `max_bytes`.
void check_kept_runs_size(const Campaign& campaign, double max_bytes);

/// The summary record's values under `metrics` as CSV cells (see the file comment).
std::string summary_cells(const nlohmann::ordered_json& summary, const std::vector<std::string>& metrics);

struct CampaignRun {
  std::filesystem::path dir;
  int jobs = 0;  ///< threads per process; 0: all cores
  bool resume = false;
  bool keep_runs = false;
  PointDistributor* distributor = nullptr;  ///< nullptr: the threads of this process
  /// Where the coordinator keeps the campaign's RunDirectory (made once the campaign is known to
  /// run), so that the caller's later files (reduced.csv, the figure) come before its `complete`
  /// marker, written when the caller's optional goes out of scope. nullptr: run_campaign marks
  /// the directory complete itself when the points are done.
  std::optional<RunDirectory>* directory = nullptr;
};

/// Runs the campaign into run.dir (on the coordinator; an MPI worker computes the points it is
/// handed and writes nothing). --resume of a different campaign, or a run.dir that cannot be a
/// directory of results (check_output_directory): UsageError before anything is written.
SweepOutcome run_campaign(const Campaign& campaign, const CampaignRun& run);

}  // namespace flexgait::campaign
