#pragma once
/// \file flow.hpp
/// The flexible wheel's smooth flow and guard functions in a fixed contact mode, as free
/// functions over (parameters, contact set, state) — what the event-driven simulator integrates.
///
/// Guards, four per leg k at indices 4k..4k+3 (all fire on downward crossings):
///   free leg:  h_k = y - (L0 - δ_k) cos β_k                       touchdown (free_foot_height)
///   stick:     N_k; μ_s - |T_k|/N_k; cos β_k                      lift-off; stick→slip; fall
///   slip s:    N_k; s ċ_k; cos β_k; cos β_k - μ(ċ_k) s sin β_k    lift-off; slip→stick; fall; jam
/// Unused slots hold +1.
#include <span>
#include <vector>

#include "flexgait/rimless/contact.hpp"
#include "flexgait/rimless/dynamics.hpp"
#include "flexgait/rimless/mode_selection.hpp"

namespace flexgait::rimless {

inline constexpr int kGuardsPerLeg = 4;
inline int guard_count(const WheelParams& w) {
  return kGuardsPerLeg * w.legs;
}

/// ẏ for state y (dim state_size(w)), including the dissipated-work rates
/// Ẇ_damp = Σ C δ̇², Ẇ_fric = -Σ T ċ and the free legs' relaxation K δ + C δ̇ = 0.
/// \return false if the mode has no consistent motion at y (e.g. a slip jam).
bool flow_derivative(const WheelParams& w, const ContactSet& contacts, std::span<const double> y,
                     std::span<double> ydot);
/// The same with the mode's dynamics at y written into `d` (contact_dynamics' in-place form): the
/// integrator's hot path keeps one Dynamics for all its evaluations. Where the mode has a
/// consistent motion the normal forces N are not computed (normal_forces(contacts, d) does).
bool flow_derivative(const WheelParams& w, const ContactSet& contacts, std::span<const double> y,
                     std::span<double> ydot, Dynamics& d);

/// cos 2αk and sin 2αk of every leg k's offset from leg 0: the free feet's heights by angle
/// addition, cos β_k = cos θ cos 2αk - sin θ sin 2αk (one sine and cosine of θ for all legs
/// instead of one cosine per leg; within 2 ulp of cos(θ + 2αk), and closer to cos β_k once θ is
/// large, where θ + 2αk rounds).
struct LegOffsets {
  std::vector<double> cos, sin;  ///< per leg
};
LegOffsets leg_offsets(const WheelParams& w);
/// Free foot k's height y - (L0 - δ_k) cos β_k (the touchdown guard), cos β_k by angle addition
/// from cos θ and sin θ of the state y.
inline double free_foot_height(const WheelParams& w, const LegOffsets& offsets, int k, double cos_theta,
                               double sin_theta, std::span<const double> y) {
  const std::size_t i = static_cast<std::size_t>(k);
  const double cb = cos_theta * offsets.cos[i] - sin_theta * offsets.sin[i];
  return y[StateIndex::y] - (w.L0 - y[StateIndex::free_delta + k]) * cb;
}

/// Guard values (dim guard_count(w)) of the mode at y.
void guard_values(const WheelParams& w, const ContactSet& contacts, std::span<const double> y, std::span<double> g);
/// The same with the mode's dynamics at y given (d = contact_dynamics(w, contacts, y)).
void guard_values(const WheelParams& w, const ContactSet& contacts, const Dynamics& d, std::span<const double> y,
                  std::span<double> g);
/// The same with the legs' offsets given (offsets = leg_offsets(w); the integrator's hot path).
void guard_values(const WheelParams& w, const LegOffsets& offsets, const ContactSet& contacts, const Dynamics& d,
                  std::span<const double> y, std::span<double> g);

/// The guards' crossing directions in the mode (dim guard_count(w)): -1 (downward) for the slots
/// guard_values writes, numerics::kNoGuard for those it leaves at +1 (slots 1–3 of a free leg,
/// slot 3 of a sticking foot): the integrator watches the mode's guards alone.
void guard_directions(const WheelParams& w, const ContactSet& contacts, std::span<int> directions);

/// The event a guard slot stands for, given whether its leg is on the ground and its mode.
EventKind guard_event(int slot, bool on_ground, FootMode mode);

}  // namespace flexgait::rimless
