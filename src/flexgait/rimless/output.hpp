#pragma once
/// \file output.hpp
/// A rimless-wheel run as files: log.csv, events.csv, steps.csv and summary.json.
#include <string>

#include "flexgait/core/run_directory.hpp"
#include "flexgait/rimless/simulation.hpp"

namespace flexgait::rimless {

/// log.csv: t, state, per contact slot (leg, phase, N, T, c, cdot), energies, dissipated work,
/// and the energy balance E + W_damp + W_fric - E(0).
std::string log_csv(const SimulationResult& result);
/// events.csv: t, kind, leg, modes after the event.
std::string events_csv(const SimulationResult& result);
/// steps.csv: one row per step with its gait label and energy.
std::string steps_csv(const SimulationResult& result);
/// summary.json (pretty-printed, keys in a fixed order; numbers round-trip exactly).
std::string summary_json(const SimulationResult& result, const std::string& model);

/// Writes the four files into `dir` (each atomically).
void write_run(const RunDirectory& dir, const SimulationResult& result, const std::string& model);

}  // namespace flexgait::rimless
