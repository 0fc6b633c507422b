#pragma once
/// \file rigid_wheel.hpp
/// The rigid rimless wheel (McGeer 1990; docs/theory/rimless.md, "The rigid wheel, the analytic limit"): rigid legs of
/// length L0,
/// mass m at the hub with inertia I, a foot that never slips, and an inelastic impact at
/// touchdown that keeps the angular momentum about the new foot. Between impacts it is an
/// inverted pendulum about the foot:
///   (m L0² + I) β̈ = m g L0 sin(β + φ),       β from -α to +α,
///   impact:  (m L0² cos 2α + I) ω⁻ = (m L0² + I) ω⁺.
/// Its step-to-step map of the post-impact speed is
///   ω⁺ₙ₊₁ = r sqrt((ω⁺ₙ)² + a),  r = (m L0² cos 2α + I)/(m L0² + I),  a = 4 m g L0 sin α sin φ/(m L0² + I),
/// with fixed point ω* = r sqrt(a / (1 - r²)) and multiplier r² (cos²2α for I = 0).
#include <optional>

#include "flexgait/rimless/parameters.hpp"
#include "flexgait/rimless/simulation.hpp"

namespace flexgait::rimless {

struct RigidStepMap {
  double r = 0;  ///< impact velocity ratio ω⁺/ω⁻
  double a = 0;  ///< gain in ω² from β = -α to +α [rad²/s²]
  /// Post-impact speed of the next step from that of this one [rad/s].
  double next(double omega_plus) const;
  /// Fixed point ω* [rad/s].
  double fixed_point() const;
  /// dω⁺ₙ₊₁/dω⁺ₙ at ω⁺ₙ (r² at the fixed point).
  double derivative(double omega_plus) const;
};

RigidStepMap rigid_step_map(const WheelParams& w);

/// Simulates the rigid wheel from stance angle initial.beta with angular velocity
/// initial.omega (integrated with the same event-locating integrator as the flexible wheel).
/// Impact losses are booked as work_damping (the infinitely stiff, dissipative leg).
/// With `stop_at` it stops at the first crossing of that section after t = 0: Touchdown right
/// after the impact (β = -α, ω⁺), Upright at the next β = 0 after an impact.
SimulationResult simulate_rigid(const WheelParams& w, const InitialState& initial, const SimulationOptions& options,
                                std::optional<Section> stop_at = std::nullopt);
/// The same, with the samples, events and steps handed to `sink` as they are made (the result's
/// vectors stay empty).
SimulationResult simulate_rigid(const WheelParams& w, const InitialState& initial, const SimulationOptions& options,
                                RunSink& sink, std::optional<Section> stop_at = std::nullopt);

}  // namespace flexgait::rimless
