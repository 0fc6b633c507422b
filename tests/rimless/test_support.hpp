#pragma once
// Shared set-up of the rimless tests: the spec's measured parameter set and run options.
#include "flexgait/rimless/flexible_wheel.hpp"

namespace flexgait::rimless::testing {

/// m = 1, I = 0.3, N = 10, φ = 0.1, L0 = 1, K = 1000, C = 30 (spec rimless.md), μ given.
inline WheelParams measured_wheel(double mu) {
  WheelParams w;
  w.mu_s = w.mu_k = mu;
  return w;
}

inline SimulationOptions run_options(int steps, double rtol = 1e-10) {
  SimulationOptions o;
  o.steps = steps;
  o.rtol = rtol;
  o.atol = 1e-12;
  o.sample_dt = 2e-3;
  o.max_step_time = 3.0;
  return o;
}

}  // namespace flexgait::rimless::testing
