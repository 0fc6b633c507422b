#pragma once
/// \file walk_output.hpp
/// A walk's files: log.csv (one row per logged sample), footsteps.csv (planned and landed
/// footprints) and summary.json (the metrics), as text.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/table.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/experiments/walk_experiment.hpp"

namespace flexgait::experiments {

std::string walk_log_csv(const WalkResult& result);
/// Leg joints over the walk: desired, command, encoder, true link, estimates, τ_g of the input and
/// the output compensator, and the twin's gear torque.
std::string walk_joints_csv(const WalkResult& result);
std::string walk_footsteps_csv(const WalkResult& result);
/// log.csv's and joints.csv's rows as typed columns (csv() is the text above, byte for byte): for
/// the Python bindings, whose arrays then need no text round trip.
Table walk_log_table(const WalkResult& result);
Table walk_joints_table(const WalkResult& result);
/// Columns of log.csv and joints.csv by name, and a sample's values in them: the numbers those
/// files hold for it, made by the files' own row writers (e.g. the replay's plotted signals).
class WalkColumns {
 public:
  /// `names`: columns of log.csv, else of joints.csv (with the stiffness estimates' columns when
  /// `k_estimation`); std::invalid_argument naming a column neither file has.
  explicit WalkColumns(const std::vector<std::string>& names, bool k_estimation = false);
  /// One value per name, in their order.
  std::vector<double> values(const WalkSample& sample) const;

 private:
  std::vector<std::pair<bool, std::size_t>> where_;  ///< (in joints.csv, column index)
  bool k_estimation_;
};
/// The walk's summary record: the WalkMetrics fields (fell, steps_completed, zmp_rms_x, ...), and
/// with online stiffness identification `k_estimate` (per identified joint), `k_estimate_mean` and
/// `k_estimate_relative_std` (per identified joint).
nlohmann::ordered_json walk_summary(const WalkResult& result);
/// summary.json: walk_summary's text. Deterministic: the same configuration gives the same bytes.
std::string walk_summary_json(const WalkResult& result);
/// Wall-clock time and real-time factor (differs run to run), and timing.json's text.
nlohmann::ordered_json walk_timing(const WalkResult& result);
std::string walk_timing_json(const WalkResult& result);
/// log.csv and joints.csv written while the walk runs, so that memory stays flat in the walk's
/// length (run_walk's `record`): rows go to temporary files beside the targets, in pieces of
/// kRowsPerWrite rows; commit() renames them into place (nothing half-written if the run stops).
class WalkLogWriter {
 public:
  static constexpr int kRowsPerWrite = 256;
  /// Opens the temporary files under `dir`/`sub`; `k_estimation`: joints.csv has the stiffness
  /// estimates' columns (control.k_estimation on or calibrate).
  WalkLogWriter(const RunDirectory& dir, const std::string& sub, bool k_estimation);
  void add(const WalkSample& sample);
  void commit();

 private:
  static std::filesystem::path make_parent(const std::filesystem::path& dir);
  void flush();
  AtomicFileWriter log_, joints_;
  CsvWriter log_csv_, joints_csv_;
  bool k_estimation_;
  int pending_ = 0;
};

/// Writes the walk's files (log.csv, footsteps.csv, joints.csv, summary.json, timing.json) under
/// `dir`/`sub` (sub "" or "name/"; log.csv and joints.csv only when the walk kept its log in
/// memory, not when a WalkLogWriter streamed them); returns the summary record (walk_summary).
nlohmann::ordered_json write_walk(const RunDirectory& dir, const std::string& sub, const WalkResult& result);

}  // namespace flexgait::experiments
