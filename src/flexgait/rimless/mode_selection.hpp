#pragma once
/// \file mode_selection.hpp
/// Choosing the contact modes at an event (docs/theory/rimless.md, "Events and contact
/// modes").
///
/// Each foot on the ground may stick, slip forward, slip backward, or leave. A combination is
/// consistent when, with the forces it implies:
///   stick: ċ = 0, N >= 0, |T| <= μ_s N;
///   slip s: N >= 0, D = cos β - μ(ċ) s sin β > 0 (μ_k, or Stribeck's μ(ċ), μ(0) = μ_s), and friction opposes the
///   motion
///           (s = sign ċ, or s·c̈ >= 0 when the foot starts from rest);
///   leave: the leg force with the foot held down is f <= 0 (the foot moves off the ground).
/// Every combination is enumerated; the foot whose guard fired may not keep its mode. Of the
/// consistent ones the rule takes the one that keeps most feet in their previous mode, then
/// prefers stick over slip over leave (and counts when more than one was consistent).
///
/// Painlevé jams (a moving foot whose slip denominator is D <= 0): the foot is stopped by a
/// tangential impulse perpendicular to its leg (no axial impulse through the massless spring),
/// admissible exactly when that direction lies in the friction cone; its kinetic-energy loss
/// is booked as friction work.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "flexgait/rimless/contact.hpp"
#include "flexgait/rimless/outcome.hpp"

namespace flexgait::rimless {

enum class EventKind : std::uint8_t {
  Touchdown,    ///< free foot height crosses 0 downward
  LiftOff,      ///< normal force N crosses 0 downward
  StickToSlip,  ///< μ_s - |T|/N crosses 0 downward
  SlipToStick,  ///< s ċ crosses 0 downward (stick, or slip the other way)
  SlipJam,      ///< slip denominator D crosses 0 downward
  FallOver,     ///< a stance leg reaches |β| = π/2
};
const char* event_name(EventKind kind);

struct GuardEvent {
  int leg = 0;
  EventKind kind = EventKind::Touchdown;
};

/// Tolerances of the consistency tests, scaled by the wheel (m g, sqrt(g L0), g).
struct ModeTolerances {
  double force;         ///< [N]
  double velocity;      ///< [m/s]
  double acceleration;  ///< [m/s²]
  static ModeTolerances of(const WheelParams& w);
};

struct ModeDecision {
  std::optional<FailureReason> failure;  ///< empty, or why no motion can continue
  std::string detail;                    ///< the report behind a failure
  ContactSet contacts;                   ///< the feet on the ground from now on, with their modes
  int consistent = 0;                    ///< how many combinations were consistent (> 1: the rule decided)
  int jammed_feet = 0;                   ///< feet stopped by a jam impulse at this event
  double impulse_energy = 0;             ///< kinetic energy removed by jam impulses [J]
  std::vector<int> impulse_legs;         ///< the feet that took jam impulses (decided at this event)
};

/// Decides the modes after `events` fired at state y. On return y's velocities include any jam
/// impulse, W_fric includes its energy, and legs that left hold their compression as free legs.
ModeDecision choose_modes(const WheelParams& w, const ContactSet& current, std::span<const GuardEvent> events,
                          std::span<double> y);

/// The state change of an event with its decision held fixed (jam impulses on the decided feet,
/// θ̇ for I = 0, free-leg compressions of the feet that left), applied to y. choose_modes()
/// applies the same change; this form is for differentiating the reset (variational.hpp).
void apply_reset(const WheelParams& w, const ContactSet& current, std::span<const GuardEvent> events,
                 const ModeDecision& decision, std::span<double> y);

}  // namespace flexgait::rimless
