#pragma once
/// \file parameters.hpp
/// Parameters of the flexible-leg rimless wheel (spec rimless.md, "The model") and of its
/// simulation. All SI. Defaults: the spec's measured set, under which the four gait
/// behaviours appear as μ varies in (0, 1.5).
#include <cmath>
#include <numbers>
#include <string>

#include "flexgait/core/config.hpp"

namespace flexgait::rimless {

/// The wheel. Immutable for a run.
struct WheelParams {
  double m = 1.0;      ///< total mass [kg], (0, inf)
  double I = 0.3;      ///< moment of inertia about the hub [kg m^2], [0, inf); 0 = point mass
  int legs = 10;       ///< number of spokes N, [3, 100]; α = π/N
  double slope = 0.1;  ///< slope angle φ [rad], [0, π/4]
  double L0 = 1.0;     ///< leg rest length [m], (0, inf)
  double K = 1000.0;   ///< leg spring stiffness [N/m], (0, inf)
  double C = 30.0;     ///< leg damper [N s/m], [0, inf)
  double mu_s = 0.6;   ///< static friction coefficient, [0, inf)
  double mu_k = 0.6;   ///< kinetic friction coefficient, [0, mu_s]
  double g = 9.81;     ///< gravity [m/s^2], (0, inf)

  /// Half the angle between spokes, α = π/N [rad].
  double alpha() const { return std::numbers::pi / legs; }
};

/// Where a simulation starts: single support on leg 0, foot at x-coordinate 0 (spec rimless.md).
struct InitialState {
  double omega = 1.4;  ///< wheel angular velocity θ̇ [rad/s]
  double beta = 0.0;   ///< stance-leg angle from the slope normal [rad], |β| < α
};

enum class OdeMethodChoice { Adams, Bdf };

/// How the hybrid simulation runs.
struct SimulationOptions {
  int steps = 20;               ///< steps to simulate (touchdowns of new legs), [1, 1e6]
  double max_time = 120.0;      ///< simulated-time limit [s]
  double max_step_time = 10.0;  ///< a step longer than this counts as stopped [s]
  double sample_dt = 1e-3;      ///< log sampling interval [s]; events are logged as well
  double rtol = 1e-10;          ///< CVODE relative tolerance
  double atol = 1e-12;          ///< CVODE absolute tolerance
  OdeMethodChoice method = OdeMethodChoice::Adams;
  bool log = true;              ///< keep the sampled log (off for maps and sweeps)
  bool sensitivities = false;   ///< carry ∂y/∂y0 through flows and events (variational.hpp)
};

/// The configuration keys of the wheel, the initial state, and the simulation.
Schema rimless_schema();
WheelParams wheel_from_config(const Config& config);
InitialState initial_from_config(const Config& config);
SimulationOptions simulation_from_config(const Config& config);

/// Throws ConfigError (key named) if the parameters are inconsistent with each other,
/// e.g. mu_k > mu_s or |initial.beta| >= α.
void validate(const WheelParams& wheel, const InitialState& initial);

}  // namespace flexgait::rimless
