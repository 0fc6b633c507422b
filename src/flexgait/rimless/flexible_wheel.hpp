#pragma once
/// \file flexible_wheel.hpp
/// Event-driven simulation of the flexible-leg rimless wheel with stick-slip contact
/// (spec rimless.md). Between events the flow is smooth (dynamics.hpp); at events the contact
/// modes are re-chosen (mode_selection.hpp) and the integrator restarts (CVodeReInit).
///
/// The guards and the flow are in flow.hpp.
#include <memory>
#include <span>
#include <vector>

#include "flexgait/rimless/parameters.hpp"
#include "flexgait/rimless/simulation.hpp"

namespace flexgait::rimless {

/// The state vector (dim state_size(w)) of the initial condition: single support on leg 0 at
/// β = initial.beta, foot at c = 0, leg compressed statically by m g cos φ / K, and the wheel
/// rolling about the foot at θ̇ = initial.omega (ċ = 0, δ̇ = 0).
std::vector<double> initial_state(const WheelParams& w, const InitialState& initial);

/// Why a simulation stops besides completing its steps.
struct StopRequest {
  int steps = 0;  ///< stop at this many touchdowns of new legs
};

class FlexibleWheelSimulator {
 public:
  FlexibleWheelSimulator(const WheelParams& wheel, const SimulationOptions& options);
  ~FlexibleWheelSimulator();
  FlexibleWheelSimulator(const FlexibleWheelSimulator&) = delete;
  FlexibleWheelSimulator& operator=(const FlexibleWheelSimulator&) = delete;

  /// Simulates from state `y0` at t = 0 (the modes are chosen there) for `options.steps` steps.
  SimulationResult run(std::span<const double> y0);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Convenience: initial_state() then FlexibleWheelSimulator::run().
SimulationResult simulate_flexible(const WheelParams& w, const InitialState& initial, const SimulationOptions& options);

}  // namespace flexgait::rimless
