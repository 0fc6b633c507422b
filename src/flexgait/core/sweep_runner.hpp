#pragma once
/// \file sweep_runner.hpp
/// Runs independent sweep points on all cores (oneTBB) or over the ranks of an MPI job (a
/// PointDistributor), appends each finished point to a durable partial file at once (an
/// interrupted sweep loses nothing), resumes from it, shows a progress bar on a terminal, and
/// writes the final CSV sorted by point index: the same bytes whatever the threads, ranks and
/// resumes. `rimless sweep`, the rimless analysis sweeps and `flexgait campaign` run on it.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/point_distributor.hpp"

namespace flexgait {

/// The most points of one sweep: `rimless sweep --count`, the Python `sweep`'s count, a
/// campaign's grid (campaign/grid.hpp).
inline constexpr int kMaxSweepPoints = 1'000'000;

struct SweepJob {
  std::filesystem::path dir;   ///< output directory
  std::string name = "sweep";  ///< files: NAME.csv (final), NAME.partial.csv, NAME.signature
  std::string noun = "sweep";  ///< what the messages call it ("no sweep to resume", "campaign")
  std::string header;          ///< CSV header, without "index" (added first)
  int count = 0;               ///< points 0 .. count-1
  int jobs = 0;                ///< worker threads (per process); 0: all cores
  bool resume = false;         ///< keep the finished points of an earlier run with the same signature
  std::string signature;       ///< what defines the sweep (parameters, configuration); checked on resume
  /// Computes point i; returns its CSV cells (no index, no newline). Must be thread-safe.
  PointFunction row;
  /// Whether `cells` (a resumed row's fields after the index, as many as the header has) are what
  /// row(i) could have returned: the point's own axis values, numbers that parse and are finite
  /// where the column holds numbers. A row it refuses is computed again. Empty: any row with the
  /// right number of fields is kept.
  std::function<bool(int i, const std::vector<std::string>& cells)> valid_row;
  /// The estimated cost of point i (any unit, e.g. the simulated time it plans): the points are
  /// handed out most expensive first (ties by index), so the last to start are the cheap ones and
  /// no worker idles long at the end. Empty: index order. The CSV is sorted by index either way.
  std::function<double(int)> cost;
  /// Called once the sweep is known to run (after check_resumable, the directory made), before
  /// the points: writes what goes beside the CSV (a campaign's config.yaml). May be empty.
  std::function<void()> prepare;
  /// Who computes the points; nullptr: the threads of this process (ThreadDistributor). In an MPI
  /// worker process (not the coordinator) run_sweep computes what it is handed and touches no file.
  PointDistributor* distributor = nullptr;
};

struct SweepOutcome {
  int computed = 0;  ///< points computed in this run
  int resumed = 0;   ///< points taken from the partial file
  double seconds = 0;
};

/// The header of a sweep's final CSV file: an index column, then the job's header.
inline std::string sweep_file_header(const std::string& job_header) {
  return "index," + job_header;
}

/// Throws UsageError if `job.resume` is set but its directory holds no sweep with the
/// same signature. Call it before writing anything.
void check_resumable(const SweepJob& job);

/// Runs the job (after check_resumable). Without resume an earlier sweep in the directory is replaced.
/// If the coordinator fails before the points start (e.g. check_resumable throws), the workers of
/// `job.distributor` are released before the exception propagates.
SweepOutcome run_sweep(const SweepJob& job);

}  // namespace flexgait
