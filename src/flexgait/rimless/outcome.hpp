#pragma once
/// \file outcome.hpp
/// Why a rimless-wheel run or Poincaré-map evaluation stopped early: a physics outcome, as a
/// reason (`FailureReason`, one `{value, "name", "sentence"}` table) plus its detail, never an
/// exception (docs/guide/library.md: a run that stops early says why). Exceptions remain for broken contracts
/// (a state vector of the wrong size, a mode kept after its guard fired).
///
/// The text that files and the console show is made from the reason and the detail
/// (`Failure::text()`): the reason's sentence, then " (detail)" when there is a detail; a sentence
/// with "{}" takes the detail in that place instead. A stage ("transient", "reaching the
/// section", ...) goes before it as "stage: ".
#include <array>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/numerics/reason_table.hpp"

namespace flexgait::numerics {
enum class LoopFailure;  // hybrid_simulation.hpp
}

namespace flexgait::rimless {

enum class FailureReason : std::uint8_t {
  // The start (docs/theory/rimless.md, "Events and contact modes"): the initial state is not on or above the ground.
  InitialFootBelowGround,
  // Mode choice at an event (mode_selection.hpp, docs/theory/rimless.md, "Events and contact modes").
  Fell,                    ///< a stance leg reached |β| = π/2
  TooManyFeet,             ///< more feet on the ground than kMaxContacts
  JamWithoutImpulse,       ///< a Painlevé jam that no impulse inside the cone stops
  PainleveParadox,         ///< every mode slips with D <= 0 or breaks a condition, no impulse helps
  NoConsistentMode,        ///< no combination of foot modes is consistent (I > 0)
  PointMassLanding,        ///< I = 0: a landing after a flight has no consistent motion
  PointMassSingleSlip,     ///< I = 0: single-support slip snaps to the friction-cone edge
  PointMassDoubleSupport,  ///< I = 0: no consistent mode in double support
  // Contact dynamics of one mode (dynamics.hpp).
  SlipJam,                 ///< a slipping foot with D <= 0 (Painlevé jam)
  PointMassTorqueBalance,  ///< I = 0: the torque balance does not fix θ̇
  PointMassSingular,       ///< I = 0: the constrained equations are singular
  // Checks after a smooth step and at events (the flexible wheel).
  MissedModeChange,             ///< the contact mode became inconsistent within one solver step
  MissedTouchdown,              ///< a free foot went below the ground within one solver step
  RolledBack,                   ///< flexible: a leg behind the hub landed while the wheel moved backwards
  FellBack,                     ///< rigid: the roll-back guard β + α ↓ 0 fired
  AtRest,                       ///< came to rest in double support
  SlidAway,                     ///< slides down the slope on its feet without turning, ever faster
  NoLanding,                    ///< no new leg landed within sim.max_step_time
  BalancedAtVertical,           ///< NoLanding on one foot at rest at the true vertical (simulation.hpp)
  TimeLimit,                    ///< sim.max_time reached
  UprightOutsideSingleSupport,  ///< the upright section crossed outside single support on that leg
  Sensitivities,                ///< the reset's Jacobian could not be formed
  // The hybrid loop (numerics/hybrid_simulation.hpp).
  SolverFailure,      ///< the integrator threw (step size underflow, ...)
  RepeatedEvent,      ///< an event fired again at its own restart point
  Zeno,               ///< kZenoCount events within kZenoWindow
  WallTime,           ///< sim.max_wall_time of wall clock
  StepRate,           ///< sim.max_step_rate exceeded over a window
  StepRateFromStart,  ///< sim.max_step_rate below what stability alone needs
  // The Poincaré map (poincare.hpp).
  SectionNotReached,    ///< the run ended without crossing the section
  OtherMode,            ///< arrived at the section in another discrete mode
  IrreducibleCrossing,  ///< the crossing cannot be reduced to a section state (detail says how)
};

/// {reason, "name" (snake_case, for JSON and tests), "sentence" (the text files show; "{}": where the detail goes)}.
using FailureEntry = numerics::ReasonEntry<FailureReason>;

inline constexpr std::array<FailureEntry, 32> kFailureTable{{
    {FailureReason::InitialFootBelowGround, "initial_foot_below_ground", "initial state: foot {} is below the ground"},
    {FailureReason::Fell, "fell", "fell: a stance leg reached |beta| = pi/2"},
    {FailureReason::TooManyFeet, "too_many_feet", "more feet on the ground than supported"},
    {FailureReason::JamWithoutImpulse, "jam_without_impulse", "Painleve jam with no admissible impulse"},
    {FailureReason::PainleveParadox, "painleve_paradox",
     "Painleve paradox: every contact mode either slips with D <= 0 or breaks a contact condition, and no "
     "admissible impulse stops the jammed feet"},
    {FailureReason::NoConsistentMode, "no_consistent_mode", "no consistent contact mode"},
    {FailureReason::PointMassLanding, "point_mass_landing",
     "I = 0: a landing after a flight has no consistent motion (the leg would have to snap to the friction-cone "
     "edge)"},
    {FailureReason::PointMassSingleSlip, "point_mass_single_slip",
     "I = 0: single-support slip has no consistent motion (the leg would snap to the friction-cone edge, "
     "tan(beta) = -mu_k s)"},
    {FailureReason::PointMassDoubleSupport, "point_mass_double_support",
     "I = 0: no consistent contact mode in double support"},
    {FailureReason::SlipJam, "slip_jam", "slip with a non-positive friction denominator (Painleve jam)"},
    {FailureReason::PointMassTorqueBalance, "point_mass_torque_balance",
     "I = 0: the torque balance does not fix the angular velocity"},
    {FailureReason::PointMassSingular, "point_mass_singular",
     "no consistent motion: the constrained equations are singular (point mass, I = 0)"},
    {FailureReason::MissedModeChange, "missed_mode_change",
     "missed event: the contact mode became inconsistent within one solver step"},
    {FailureReason::MissedTouchdown, "missed_touchdown", "missed event: a free foot went below the ground"},
    {FailureReason::RolledBack, "rolled_back",
     "rolled back: a leg behind the hub landed while the wheel moved backwards"},
    {FailureReason::FellBack, "fell_back", "rolled back: the wheel fell back onto the previous leg"},
    {FailureReason::AtRest, "at_rest", "stopped: the wheel came to rest in double support"},
    {FailureReason::SlidAway, "slid_away",
     "slid away: the wheel slides down the slope on its feet without turning, ever faster"},
    {FailureReason::NoLanding, "no_landing", "stopped: no new leg landed within sim.max_step_time"},
    {FailureReason::BalancedAtVertical, "balanced_at_vertical",
     "balanced at the vertical: no new leg landed within sim.max_step_time, the wheel at rest on one foot at the "
     "vertical"},
    {FailureReason::TimeLimit, "time_limit", "time limit sim.max_time reached"},
    {FailureReason::UprightOutsideSingleSupport, "upright_outside_single_support",
     "the upright section was crossed outside single support on that leg"},
    {FailureReason::Sensitivities, "sensitivities", "sensitivities"},
    {FailureReason::SolverFailure, "solver_failure", "solver failure"},
    {FailureReason::RepeatedEvent, "repeated_event", "an event fired again at its own restart point"},
    {FailureReason::Zeno, "zeno", "Zeno sequence: too many events in too short a time"},
    {FailureReason::WallTime, "wall_time", "wall-time limit sim.max_wall_time reached"},
    {FailureReason::StepRate, "step_rate", "work limit sim.max_step_rate reached"},
    {FailureReason::StepRateFromStart, "step_rate_from_start", "work limit sim.max_step_rate exceeded from the start"},
    {FailureReason::SectionNotReached, "section_not_reached", "the {} section was not reached"},
    {FailureReason::OtherMode, "other_mode", "arrived at the section in another mode"},
    {FailureReason::IrreducibleCrossing, "irreducible_crossing", "{}"},
}};

constexpr std::array<EnumName<FailureReason>, kFailureTable.size()> enum_names(FailureReason) {
  return numerics::reason_names(kFailureTable);
}

/// The reason's sentence (as files show it, "{}" where a detail goes); std::logic_error if missing.
std::string_view failure_sentence(FailureReason reason);

/// The I = 0 reasons: the point-mass wheel's equations do not fix the motion (ill-posed).
constexpr bool ill_posed_point_mass(FailureReason r) {
  return r == FailureReason::PointMassLanding || r == FailureReason::PointMassSingleSlip ||
         r == FailureReason::PointMassDoubleSupport || r == FailureReason::PointMassTorqueBalance ||
         r == FailureReason::PointMassSingular;
}

/// The reason of one of the hybrid loop's own failures.
FailureReason loop_failure_reason(numerics::LoopFailure what);

/// A run's or a map evaluation's failure: the reason, its detail, and the stage it happened in.
struct Failure {
  FailureReason reason = FailureReason::SolverFailure;
  std::string detail;  ///< numbers behind the reason (may be empty)
  std::string stage;   ///< where on the way ("transient", "reaching the section"; may be empty)

  /// "stage: sentence (detail)", as files and the console show it.
  std::string text() const;
  /// The same failure in a stage (an outer stage goes first: "outer: inner: ...").
  Failure in_stage(std::string_view outer) const;
};

/// The failure's text, or "" without one (a CSV cell).
std::string text_of(const std::optional<Failure>& failure);

std::ostream& operator<<(std::ostream& out, const Failure& failure);

}  // namespace flexgait::rimless
