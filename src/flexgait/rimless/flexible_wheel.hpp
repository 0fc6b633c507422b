#pragma once
/// \file flexible_wheel.hpp
/// Event-driven simulation of the flexible-leg rimless wheel with stick-slip contact
/// (docs/theory/rimless.md). Between events the flow is smooth (dynamics.hpp); at events the contact
/// modes are re-chosen (mode_selection.hpp) and the integrator restarts (CVodeReInit).
///
/// The guards and the flow are in flow.hpp.
#include <Eigen/Dense>

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "flexgait/numerics/ode_integrator.hpp"
#include "flexgait/rimless/mode_selection.hpp"
#include "flexgait/rimless/parameters.hpp"
#include "flexgait/rimless/simulation.hpp"

namespace flexgait::rimless {

/// The state vector (dim state_size(w)) of the initial condition: single support on leg 0 at
/// β = initial.beta, foot at c = 0, leg compressed statically by m g cos φ / K, and the wheel
/// rolling about the foot at θ̇ = initial.omega (ċ = 0, δ̇ = 0).
std::vector<double> initial_state(const WheelParams& w, const InitialState& initial);
/// Throws ConfigError naming the keys involved when initial_state() is not a valid start: the
/// stance leg's static compression m g cos φ / K is not below L0, or another foot starts below
/// the ground (a wheel of many legs sags more than the clearance of its neighbouring feet).
void check_initial_state(const WheelParams& w, const InitialState& initial);

/// The integrator's options of a run: SimulationOptions' tolerances and method, and the error
/// weights of the velocities (held to rtol times 1 % of sqrt(g L0), for the energy ledger).
numerics::OdeOptions integrator_options(const WheelParams& w, const SimulationOptions& options);

/// Where and how a run starts and stops.
struct RunSpec {
  std::vector<double> y0;           ///< full state (dim state_size(w))
  ContactSet contacts;              ///< feet on the ground at t = 0, before `pending`
  std::vector<GuardEvent> pending;  ///< events handled at t = 0 (e.g. a touchdown at the section)
  int steps = 0;                    ///< stop after this many touchdowns of new legs (0: options.steps)
  /// The stance leg of the step under way at t = 0, which decides which legs are new (-1: the
  /// leg landing at t = 0, else the oldest foot on the ground). A run that continues another
  /// passes that run's last stance leg, so that a bounce of it is not taken for a new step.
  int stance_leg = -1;
  std::optional<Section> stop_at;  ///< stop at the first crossing of this section instead
  /// With stop_at = Touchdown: a leg behind the stance leg landing (the wheel fell back onto it)
  /// is a crossing too (the first stage of the stagnation experiment ends on either neighbour).
  bool section_includes_legs_behind = false;
};

/// The parameter column of the sensitivities (docs/guide/rimless.md, "Orbit diagram and basin of attraction"): the
/// wheel at p + h and at p - h for one
/// real parameter p. With it (and SimulationOptions::sensitivities) the variational equations
/// carry ∂y/∂p as one more column, p treated as a state with ṗ = 0: along the flow
/// ṡ_p = (∂f/∂y) s_p + ∂f/∂p, across an event with guard g and reset R
///   s_p⁺ = Ξ s_p⁻ + ∂R/∂p + (f⁺ - R_y f⁻) (∂g/∂p) / (g_y f⁻)       (Ξ the saltation matrix),
/// and at the section s_p = (I - f⁻ g_y/(g_y f⁻)) s_p⁻ - f⁻ (∂g/∂p)/(g_y f⁻). ∂f/∂p, ∂g/∂p and
/// ∂R/∂p are central differences (· at plus - · at minus) / (2 h) of these algebraic functions at
/// one state (the flow's costs a second right-hand side per column evaluation, no integration).
struct ParameterDirection {
  WheelParams plus, minus;
  double step = 0;  ///< h, in the parameter's unit (the column is ∂y/∂p in that unit)
};

/// The state where a run crossed its stop section.
struct SectionHit {
  double t = 0;               ///< [s]
  std::vector<double> state;  ///< full state at the crossing, before any mode change
  ContactSet contacts;        ///< feet on the ground just before the crossing
  int leg = -1;               ///< the leg landing (touchdown) or upright (upright)
  /// With SimulationOptions::sensitivities: ∂y(t_section)/∂y(0), crossing-time correction
  /// included (n×n; n×(n + 1) with a ParameterDirection, the last column ∂y(t_section)/∂p at
  /// fixed y(0)); the pending events at t = 0 count as part of the map.
  Eigen::MatrixXd S;
};

/// The start of a default run: initial_state() with every foot's mode chosen at t = 0.
RunSpec default_run(const WheelParams& w, const InitialState& initial);

class FlexibleWheelSimulator {
 public:
  FlexibleWheelSimulator(const WheelParams& wheel, const SimulationOptions& options);
  /// With sensitivities in a parameter as well (SectionHit::S gets its column).
  FlexibleWheelSimulator(const WheelParams& wheel, const SimulationOptions& options,
                         const ParameterDirection& parameter);
  ~FlexibleWheelSimulator();
  FlexibleWheelSimulator(const FlexibleWheelSimulator&) = delete;
  FlexibleWheelSimulator& operator=(const FlexibleWheelSimulator&) = delete;

  /// Simulates as `spec` says. If it stops at a section, `section` holds the crossing. The
  /// samples (with SimulationOptions::log), events and steps are kept in the result.
  SimulationResult run(const RunSpec& spec, SectionHit* section = nullptr);
  /// The same, with the samples, events, steps and restarts handed to `sink` as they are made
  /// instead (the result's samples, events and steps stay empty; its counts, gait labels and
  /// energy ledger are filled): memory independent of the length of the run.
  SimulationResult run(const RunSpec& spec, RunSink& sink, SectionHit* section = nullptr);

 private:
  void run_into(const RunSpec& spec, SectionHit* section, RunSink& sink, SimulationResult& res);
  struct Impl;
  struct Run;  // one run: the model the hybrid loop (numerics/hybrid_simulation.hpp) drives
  std::unique_ptr<Impl> impl_;
};

/// Convenience: initial_state() then FlexibleWheelSimulator::run() (in memory, or into `sink`).
SimulationResult simulate_flexible(const WheelParams& w, const InitialState& initial, const SimulationOptions& options);
SimulationResult simulate_flexible(const WheelParams& w, const InitialState& initial, const SimulationOptions& options,
                                   RunSink& sink);

}  // namespace flexgait::rimless
