#pragma once
/// \file parameters.hpp
/// Parameters of the flexible-leg rimless wheel (docs/theory/rimless.md, "Equations of motion") and of its
/// simulation. All SI. Defaults: the spec's measured set, under which the four gait
/// behaviours appear as μ varies in (0, 1.5). Each struct lists its configuration keys once
/// (core/record.hpp).
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "flexgait/core/config.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/numerics/ode_integrator.hpp"

namespace flexgait::rimless {

/// The friction law of a slipping foot (docs/theory/rimless.md, "Equations of motion"; docs/guide/rimless.md, "Stribeck
/// friction"). Coulomb:
/// T = -s μ_k N. Stribeck: T = -s (μ(v) N + σ |v|) with v = ċ, s = sign v and
/// μ(v) = μ_k + (μ_s - μ_k) exp(-(|v|/v_s)^δ), so μ(0) = μ_s. A sticking foot obeys |T| <= μ_s N
/// under both laws.
enum class Friction { Coulomb, Stribeck };
constexpr std::array<EnumName<Friction>, 2> enum_names(Friction) {
  return {{{Friction::Coulomb, "coulomb"}, {Friction::Stribeck, "stribeck"}}};
}

/// The wheel. Immutable for a run.
struct WheelParams {
  double m = 1.0;                         ///< total mass [kg]
  double I = 0.3;                         ///< moment of inertia about the hub [kg m^2]; 0 = point mass
  int legs = 10;                          ///< number of spokes N; α = π/N
  double slope = 0.1;                     ///< slope angle φ [rad]
  double L0 = 1.0;                        ///< leg rest length [m]
  double K = 1000.0;                      ///< leg spring stiffness [N/m]
  double C = 30.0;                        ///< leg damper [N s/m]
  double mu_s = 0.6;                      ///< static friction coefficient
  double mu_k = 0.6;                      ///< kinetic friction coefficient, <= mu_s
  Friction friction = Friction::Coulomb;  ///< the slip law
  double stribeck_velocity = 0.1;         ///< Stribeck velocity v_s [m/s], > 0 (Stribeck only)
  double stribeck_exponent = 2.0;         ///< Stribeck exponent δ, > 0 (Stribeck only)
  double viscous = 0.0;  ///< viscous rise σ of the slip friction coefficient [s/m], >= 0 (Stribeck only)
  double g = 9.81;       ///< gravity [m/s^2]

  /// Half the angle between spokes, α = π/N [rad].
  double alpha() const { return std::numbers::pi / legs; }

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("rimless.m", s.m, {.unit = "kg", .doc = "total mass", .bounds = positive()});
    v("rimless.I", s.I,
      {.unit = "kg m^2", .doc = "moment of inertia about the hub (0: point mass)", .bounds = non_negative()});
    v("rimless.legs", s.legs, {.doc = "number of legs N (alpha = pi/N)", .bounds = closed(3, 100)});
    v("rimless.slope", s.slope, {.unit = "rad", .doc = "slope angle phi", .bounds = closed(0, std::numbers::pi / 4)});
    v("rimless.L0", s.L0, {.unit = "m", .doc = "leg rest length", .bounds = positive()});
    v("rimless.K", s.K, {.unit = "N/m", .doc = "leg spring stiffness", .bounds = positive()});
    v("rimless.C", s.C, {.unit = "N s/m", .doc = "leg damping", .bounds = non_negative()});
    v("rimless.mu_s", s.mu_s, {.doc = "static friction coefficient", .bounds = non_negative()});
    v("rimless.mu_k", s.mu_k, {.doc = "kinetic friction coefficient (<= mu_s)", .bounds = non_negative()});
    v("rimless.friction", s.friction,
      {.doc = "slip friction law: coulomb (mu_k) or stribeck (mu_k + (mu_s - mu_k) exp(-(|v|/v_s)^delta), plus sigma "
              "|v|)"});
    v("rimless.stribeck_velocity", s.stribeck_velocity,
      {.unit = "m/s", .doc = "Stribeck velocity v_s (friction = stribeck only)", .bounds = positive()});
    v("rimless.stribeck_exponent", s.stribeck_exponent,
      {.doc = "Stribeck exponent delta (friction = stribeck only)", .bounds = positive()});
    v("rimless.viscous", s.viscous,
      {.unit = "s/m",
       .doc =
           "viscous rise sigma of a slipping foot's friction coefficient, mu(v) + sigma |v| (friction = stribeck only)",
       .bounds = non_negative()});
    v("rimless.g", s.g, {.unit = "m/s^2", .doc = "gravitational acceleration", .bounds = positive()});
  }
};

/// Where a simulation starts: single support on leg 0, foot at x-coordinate 0 (docs/theory/rimless.md).
struct InitialState {
  double omega = 1.4;  ///< wheel angular velocity θ̇ [rad/s]
  double beta = 0.0;   ///< stance-leg angle from the slope normal [rad], |β| < α

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("initial.omega", s.omega,
      {.unit = "rad/s", .doc = "initial wheel angular velocity", .bounds = closed(-100, 100)});
    v("initial.beta", s.beta,
      {.unit = "rad",
       .doc = "initial stance-leg angle from the slope normal, |beta| < pi/N",
       .bounds = open(-std::numbers::pi / 2, std::numbers::pi / 2)});
  }
};

/// The wheel's model: flexible legs with stick-slip friction, or McGeer's rigid rimless wheel.
enum class Model { Flexible, Rigid };
constexpr std::array<EnumName<Model>, 2> enum_names(Model) {
  return {{{Model::Flexible, "flexible"}, {Model::Rigid, "rigid"}}};
}

/// How the hybrid simulation runs.
struct SimulationOptions {
  Model model = Model::Flexible;  ///< which model the run simulates
  int steps = 20;                 ///< steps to simulate (touchdowns of new legs)
  double max_time = 120.0;        ///< simulated-time limit [s]
  double max_step_time = 10.0;    ///< a step longer than this counts as stopped [s]
  /// Wall-clock limit of one run [s]: a run that makes no progress (a stiff flow on an explicit
  /// or Adams method) ends with a named failure instead of running for hours. Machine-dependent
  /// by nature: a run it ends is not reproducible bytes; one it does not end is unaffected.
  double max_wall_time = 300.0;
  /// Work limit [solver steps per second of simulated time], averaged over every 4096 solver
  /// steps: above it the solver is held at tiny steps by a mode far faster than the gait (a stiff
  /// leg on adams or dop853, K = 1e9 N/m: ~5e6) or by chattering contacts, and the run ends with a
  /// named failure; a leg mode |λ| with |λ|/6.1 above it (stability alone) ends it before the
  /// first step. A walking wheel at the spec's parameters takes ~10²–10³ steps per simulated
  /// second. Deterministic, unlike max_wall_time.
  double max_step_rate = 1e6;
  double sample_dt = 1e-3;  ///< log sampling interval [s]; events are logged as well
  /// Cap on the sampled log's projected size [bytes] (output.hpp, check_log_size): a run whose
  /// log could exceed it is refused before it starts.
  double max_log_bytes = 1e9;
  double rtol = 1e-10;  ///< the integrator's relative tolerance
  double atol = 1e-12;  ///< the integrator's absolute tolerance
  /// DOP853 (6–7× faster than Adams here, the same events to 1e-8 s); Adams and BDF stay for
  /// comparison and for stiff flows (BDF).
  numerics::OdeMethod method = numerics::OdeMethod::Dop853;
  bool log = true;             ///< keep the sampled log (off for maps and sweeps; not a key)
  bool sensitivities = false;  ///< carry ∂y/∂y0 through flows and events (variational.hpp; not a key)
  /// Called now and then during every run of these options (numerics::HybridLimits::poll: Ctrl-C
  /// from Python); may throw to abandon the run. Not a key.
  std::function<void()> poll;

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("sim.model", s.model, {.doc = "flexible legs with stick-slip, or the rigid rimless wheel"});
    v("sim.steps", s.steps, {.doc = "steps to simulate (touchdowns of new legs)", .bounds = closed(1, 1e6)});
    v("sim.max_time", s.max_time, {.unit = "s", .doc = "simulated-time limit", .bounds = positive()});
    v("sim.max_wall_time", s.max_wall_time,
      {.unit = "s",
       .doc = "wall-clock limit of one run (ends a run that makes no progress, e.g. a stiff flow)",
       .bounds = positive()});
    v("sim.max_step_rate", s.max_step_rate,
      {.unit = "1/s",
       .doc = "solver steps per simulated second (over every 4096 steps) above which a run ends as stuck (stiff flow)",
       .bounds = positive()});
    v("sim.max_step_time", s.max_step_time,
      {.unit = "s", .doc = "a step longer than this is reported as stopped", .bounds = positive()});
    v("sim.sample_dt", s.sample_dt,
      {.unit = "s", .doc = "log sampling interval (events are logged too)", .bounds = closed(1e-6, 10)});
    v("sim.max_log_bytes", s.max_log_bytes,
      {.unit = "B",
       .doc = "cap on log.csv's projected size (about 400 bytes a row: a row every sim.sample_dt over sim.max_time, "
              "or sim.steps times sim.max_step_time if shorter, and 6 a step); a run that could exceed it is refused "
              "before it starts",
       .bounds = positive()});
    v("solver.rtol", s.rtol, {.doc = "the integrator's relative tolerance", .bounds = closed(1e-14, 1e-2)});
    v("solver.atol", s.atol, {.doc = "the integrator's absolute tolerance", .bounds = closed(1e-16, 1e-2)});
    v("solver.method", s.method,
      {.doc = "integrator: CVODE's Adams or BDF multistep method, or the explicit Runge-Kutta DOP853"});
  }
};

/// The configuration keys of the wheel, the initial state, and the simulation.
Schema rimless_schema();
inline WheelParams wheel_from_config(const Config& config) {
  return record_from_config<WheelParams>(config);
}
inline InitialState initial_from_config(const Config& config) {
  return record_from_config<InitialState>(config);
}
inline SimulationOptions simulation_from_config(const Config& config) {
  return record_from_config<SimulationOptions>(config);
}

/// Throws ConfigError (key named) if the parameters are inconsistent with each other,
/// e.g. mu_k > mu_s, |initial.beta| >= α, or a Stribeck key away from its default with
/// friction = coulomb (a value equal to the default is what a resolved configuration writes
/// back, so it is accepted).
void validate(const WheelParams& wheel, const InitialState& initial);

}  // namespace flexgait::rimless
