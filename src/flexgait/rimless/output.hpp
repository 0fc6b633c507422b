#pragma once
/// \file output.hpp
/// A rimless-wheel run as files: log.csv, events.csv, steps.csv and summary.json — from a
/// finished in-memory result, or written while the run goes (RunFiles) with the same bytes.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/table.hpp"
#include "flexgait/rimless/simulation.hpp"

namespace flexgait::rimless {

/// log.csv: t, state, per contact slot (leg, phase, N, T, c, cdot), energies, dissipated work,
/// and the energy balance E + W_damp + W_fric - E(0).
std::string log_csv(const SimulationResult& result);
/// log.csv's columns, and one sample's row as numbers by log.csv's own row writer (`e0`: the
/// run's initial mechanical energy [J]; a text cell, phaseK, is NaN).
std::vector<std::string> log_column_names();
std::vector<double> log_values(const LogSample& sample, double e0);
/// events.csv: t, kind, leg, modes after the event (a failure's message instead).
std::string events_csv(const SimulationResult& result);
/// steps.csv: one row per step with its gait label and energy.
std::string steps_csv(const SimulationResult& result);
/// The run's summary record: `model`, then the SimulationResult's fields in declaration order.
nlohmann::ordered_json simulation_summary(const SimulationResult& result, const std::string& model);
/// summary.json: simulation_summary's text (json_file_text).
std::string summary_json(const SimulationResult& result, const std::string& model);
/// The same three tables as typed columns (their csv() is the text above, byte for byte): for
/// the Python bindings, whose arrays then need no text round trip.
Table log_table(const SimulationResult& result);
Table events_table(const SimulationResult& result);
Table steps_table(const SimulationResult& result);

/// The projected size of log.csv [bytes]: ~400 bytes a row; a row every sim.sample_dt over the
/// longest run the options allow, min(sim.max_time, sim.steps × sim.max_step_time), and ~6 a
/// step (the samples on both sides of each event). An upper bound of the time, typical rows.
double projected_log_bytes(const SimulationOptions& options);

/// Throws ConfigError naming sim.sample_dt and sim.max_log_bytes if projected_log_bytes exceeds
/// sim.max_log_bytes: a log of gigabytes (sample_dt = 1e-6 s) is refused before the run starts,
/// not found on a full disk after it. Commands that keep the log call it (simulate).
void check_log_size(const SimulationOptions& options);

/// Writes the four files into `dir` (each atomically).
void write_run(const RunDirectory& dir, const SimulationResult& result, const std::string& model);

/// log.csv, events.csv and steps.csv of a run written while it goes (a RunSink): rows are made
/// as the samples, events and steps come and go to disk in pieces of about 1 MB, so memory does
/// not grow with the run. Each file is written under a temporary name and renamed into place by
/// finish(); until then (an exception, an interruption) no file exists under its final name.
/// The bytes are those of log_csv(), events_csv() and steps_csv() of the same run in memory.
class RunFiles final : public RunSink {
 public:
  explicit RunFiles(const RunDirectory& dir);
  ~RunFiles() override;
  void on_start(double energy_initial) override;
  void on_sample(const LogSample& sample) override;
  void on_event(const EventRecord& event) override;
  void on_step(const StepRecord& step) override;
  /// Writes the rest and renames the three files into place (after the run).
  void finish();

 private:
  struct File;
  double energy_initial_ = 0;  // [J]
  std::unique_ptr<File> log_, events_, steps_;
};

}  // namespace flexgait::rimless
