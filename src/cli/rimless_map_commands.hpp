#pragma once
/// \file rimless_map_commands.hpp
/// `flexgait rimless analysis orbit-diagram` and `... basin` (docs/guide/rimless.md, "Orbit diagram and basin of
/// attraction"): brute-force maps of the
/// wheel's long-run behaviour over a parameter or over initial states, on the sweep runner.
#include <CLI/CLI.hpp>
#include <string>

#include "flexgait/rimless/simulation.hpp"
#include "options.hpp"

namespace flexgait::cli {

/// The options only these two analyses take (besides --from/--to/--count, --jobs, --resume, --section).
struct MapOptions {
  std::string param;                   ///< orbit-diagram: the key varied
  std::string transient, record;       ///< orbit-diagram: as given, set as analysis.orbit.transient and .record
  std::vector<std::string> branches;   ///< orbit-diagram: branch.csv files of `rimless continuation` to overlay
  std::string x, y;                    ///< basin: keys of the initial state
  std::string x_range, y_range;        ///< basin: FROM:TO:COUNT
  std::string steps_limit, tolerance;  ///< basin: as given, set as analysis.basin.steps_limit and .tolerance
};

/// Adds the options above to the analysis subcommand.
void add_map_options(CLI::App& analysis, MapOptions& options);

/// The options of add_map_options (the analysis table says which analysis takes which).
const std::vector<std::string>& map_option_names();

/// What the analysis subcommand hands over.
struct MapRun {
  std::string name;  ///< "orbit-diagram" or "basin"
  RunOptions run;
  MapOptions map;
  double from = 0, to = 0;
  int count = 0;
  int jobs = 0;
  bool resume = false;
  rimless::Section section = rimless::Section::Touchdown;
};

/// Runs orbit-diagram or basin; every option checked before anything is written (options the
/// analysis does not take are refused by the caller, the analysis table of rimless_commands.cpp). The basin's cells
/// are spread over the ranks when started by mpirun (like `flexgait campaign`).
int run_map_analysis(const MapRun& a, const CLI::App& cmd);

}  // namespace flexgait::cli
