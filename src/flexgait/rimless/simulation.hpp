#pragma once
/// \file simulation.hpp
/// What a rimless-wheel simulation returns (both the flexible and the rigid model): a sampled
/// log, the events, the steps with their gait labels, and the energy ledger.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/rimless/contact.hpp"
#include "flexgait/rimless/energy.hpp"
#include "flexgait/rimless/gait.hpp"

namespace flexgait::rimless {

/// Poincaré sections (spec rimless.md, "Analysis"): the touchdown of a new leg (before its
/// contact mode is chosen), or a leg passing upright, β = 0 upward (the paper's "vertical
/// equilibrium surface").
enum class Section { Touchdown, Upright };
constexpr std::array<EnumName<Section>, 2> enum_names(Section) {
  return {{{Section::Touchdown, "touchdown"}, {Section::Upright, "upright"}}};
}

struct ContactSample {
  int leg = -1;                       ///< -1: slot empty
  FootMode mode = FootMode::Stick;
  double N = 0, T = 0;                ///< ground reaction [N]
  double c = 0, cdot = 0;             ///< foot position [m] and velocity [m/s] along the slope
};

struct LogSample {
  double t = 0;                       ///< [s]
  std::array<double, 6> q{};          ///< (x, y, θ, ẋ, ẏ, θ̇)
  std::array<ContactSample, kMaxContacts> contact{};
  EnergyTerms energy;
  double w_damp = 0, w_fric = 0;      ///< dissipated work since t = 0 [J]
};

struct EventRecord {
  double t = 0;        ///< [s]
  std::string kind;    ///< start, touchdown, liftoff, stick_to_slip, slip_to_stick, slip_jam, failure, ...
  int leg = -1;
  std::string modes;   ///< feet on the ground after the event, e.g. "3:stick 4:slip+"
};

/// The hybrid state at the start of a smooth segment (after the reset at an event).
struct Restart {
  double t = 0;               ///< [s]
  std::vector<double> state;  ///< full state vector (flexible: dim state_size(w); rigid: (β, β̇))
  ContactSet contacts;
};

struct SimulationResult {
  std::vector<LogSample> samples;
  std::vector<EventRecord> events;
  std::vector<StepRecord> steps;
  std::vector<Restart> restarts;       ///< every segment start, t = 0 included
  std::optional<std::string> failure;  ///< why the run stopped early; empty if it completed
  int steps_completed = 0;             ///< touchdowns of new legs
  double t_final = 0;                  ///< [s]
  double energy_initial = 0, energy_final = 0;  ///< mechanical energy [J]
  double work_damping = 0, work_friction = 0;   ///< [J]
  /// |E_final + W_damp + W_fric - E_initial| / (KE_0 + m g L0 + W_damp + W_fric): relative to the
  /// energy that flowed, independent of where the potential's zero is.
  double energy_balance_error = 0;
  double mean_speed = 0;               ///< hub displacement along the slope / time, to the last touchdown [m/s]
  int jams = 0;                        ///< feet stopped by jam impulses
  int ambiguous_choices = 0;           ///< events where more than one mode combination was consistent
  long long solver_steps = 0, rhs_evals = 0;
  std::vector<double> final_state;     ///< full state vector at t_final
  ContactSet final_contacts;

  /// The gait label of every completed step.
  std::vector<std::string> gaits() const {
    std::vector<std::string> out;
    for (const auto& s : steps)
      if (s.complete) out.push_back(gait_label(s.single_support));
    return out;
  }

  /// The fields of `summary.json` (after the model's name), in order.
  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("steps", s.steps_completed, {.doc = "touchdowns of new legs"});
    std::vector<std::string> gaits = s.gaits();
    v("gaits", gaits, {.doc = "gait label of every completed step (stance-foot phases in single support)"});
    v("mean_speed", s.mean_speed, {.unit = "m/s", .doc = "hub displacement along the slope over time, to the last touchdown"});
    v("t_final", s.t_final, {.unit = "s", .doc = "simulated time"});
    v("energy_initial", s.energy_initial, {.unit = "J", .doc = "mechanical energy at the start"});
    v("energy_final", s.energy_final, {.unit = "J", .doc = "mechanical energy at the end"});
    v("work_damping", s.work_damping, {.unit = "J", .doc = "energy dissipated by the leg dampers"});
    v("work_friction", s.work_friction, {.unit = "J", .doc = "energy dissipated by friction and jam impulses"});
    v("energy_balance_error", s.energy_balance_error,
      {.doc = "|E_final + W_damp + W_fric − E_initial| over the energy that flowed"});
    v("jams", s.jams, {.doc = "feet stopped by jam impulses"});
    v("ambiguous_mode_choices", s.ambiguous_choices, {.doc = "events where more than one mode combination was consistent"});
    std::int64_t events = static_cast<std::int64_t>(s.events.size());
    v("events", events, {.doc = "hybrid events"});
    std::int64_t solver_steps = s.solver_steps, rhs_evals = s.rhs_evals;
    v("solver_steps", solver_steps, {.doc = "integrator steps"});
    v("rhs_evals", rhs_evals, {.doc = "right-hand-side evaluations"});
    v("failure", s.failure, {.doc = "why the run stopped early; null when it completed"});
  }
};

/// "3:stick 4:slip+" for a contact set; "flight" if empty.
std::string describe_contacts(const ContactSet& contacts);

}  // namespace flexgait::rimless
