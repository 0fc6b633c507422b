#pragma once
/// \file wheel_setup.hpp
/// Everything a run of the wheel needs, read from one resolved configuration (the command line's
/// and the Python module's common entry).
#include "flexgait/core/config.hpp"
#include "flexgait/rimless/parameters.hpp"
#include "flexgait/rimless/poincare.hpp"

namespace flexgait::rimless {

/// Keys of the analysis commands: rimless.*, initial.*, sim.*, analysis.* (the fixed-point search's and
/// the paper's analyses', analyses.hpp) and stagnation.*.
Schema rimless_analysis_schema();

struct WheelSetup {
  Config config;
  WheelParams wheel;
  InitialState initial;
  SimulationOptions sim;  ///< sim.* and solver.*, with the model (sim.model)
};

/// The wheel, its initial state (validated: throws ConfigError), the simulation options and the
/// model of a resolved configuration.
WheelSetup wheel_setup(Config config);

}  // namespace flexgait::rimless
