#pragma once
/// \file simulation.hpp
/// What a rimless-wheel simulation returns (both the flexible and the rigid model): a sampled
/// log, the events, the steps with their gait labels, and the energy ledger; and where the log,
/// the events and the steps go while the run goes (RunSink).
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/rimless/contact.hpp"
#include "flexgait/rimless/energy.hpp"
#include "flexgait/rimless/gait.hpp"
#include "flexgait/rimless/mode_selection.hpp"
#include "flexgait/rimless/outcome.hpp"

namespace flexgait::rimless {

/// Poincaré sections (docs/theory/rimless.md, "Poincaré map, fixed points, stability"): the touchdown of a new leg
/// (before its
/// contact mode is chosen), or a leg passing upright, β = 0 upward (the paper's "vertical
/// equilibrium surface").
enum class Section { Touchdown, Upright };
constexpr std::array<EnumName<Section>, 2> enum_names(Section) {
  return {{{Section::Touchdown, "touchdown"}, {Section::Upright, "upright"}}};
}

struct ContactSample {
  int leg = -1;  ///< -1: slot empty
  FootMode mode = FootMode::Stick;
  double N = 0, T = 0;     ///< ground reaction [N]
  double c = 0, cdot = 0;  ///< foot position [m] and velocity [m/s] along the slope
};

struct LogSample {
  double t = 0;               ///< [s]
  std::array<double, 6> q{};  ///< (x, y, θ, ẋ, ẏ, θ̇)
  std::array<ContactSample, kMaxContacts> contact{};
  EnergyTerms energy;
  double w_damp = 0, w_fric = 0;  ///< dissipated work since t = 0 [J]
};

/// What a run records at an event: the guard events of mode_selection.hpp (first, in
/// EventKind's order and with its names), and the run's own marks.
enum class RunEvent : std::uint8_t {
  Touchdown,
  LiftOff,
  StickToSlip,
  SlipToStick,
  SlipJam,
  FallOver,  // = EventKind
  Start,     ///< t = 0, after the modes at t = 0 were chosen
  Jam,       ///< feet stopped by a jam impulse at this event
  Section,   ///< the run crossed its stop section (RunSpec::stop_at)
  Failure,   ///< the run stopped early; EventRecord::message says why
};
inline RunEvent run_event(EventKind kind) {
  return static_cast<RunEvent>(kind);
}
/// "touchdown", "stick_to_slip", ..., "start", "jam", "section", "failure" (events.csv's kind).
const char* run_event_name(RunEvent kind);

/// One row of events.csv, as numbers: its text is made only when it is written.
struct EventRecord {
  double t = 0;  ///< [s]
  RunEvent kind = RunEvent::Start;
  int leg = -1;
  ContactSet contacts;  ///< feet on the ground after the event
  std::string message;  ///< Failure only: why the run stopped (made once, at the stop)
};

/// The hybrid state at the start of a smooth segment (after the reset at an event).
struct Restart {
  double t = 0;               ///< [s]
  std::vector<double> state;  ///< full state vector (flexible: dim state_size(w); rigid: (β, β̇))
  ContactSet contacts;
};

/// Where a run's record goes while the run goes, chosen by the caller: samples, events and
/// steps, each in the order they are made. The default of the simulators keeps them in the
/// SimulationResult (RunCollector); output.hpp's RunFiles writes them to CSV files as they come,
/// so that memory does not grow with the run.
class RunSink {
 public:
  virtual ~RunSink() = default;
  /// The mechanical energy at t = 0 [J], before the first sample (the log's balance is relative to it).
  virtual void on_start(double energy_initial) { (void)energy_initial; }
  /// A log sample (only with SimulationOptions::log): every sim.sample_dt and on both sides of every event.
  virtual void on_sample(const LogSample& sample) { (void)sample; }
  virtual void on_event(const EventRecord& event) { (void)event; }
  /// A step once its record is final (the next-but-one step started, or the run ended), in order.
  virtual void on_step(const StepRecord& step) { (void)step; }
  /// The start of every smooth segment (t = 0 included): time [s], full state after the reset
  /// (flexible: dim state_size(w); rigid: (β, β̇)), feet on the ground.
  virtual void on_restart(double t, std::span<const double> state, const ContactSet& contacts) {
    (void)t, (void)state, (void)contacts;
  }
};

struct SimulationResult;

/// The in-memory record (the simulators' default): samples, events and steps into the
/// result's vectors.
class RunCollector final : public RunSink {
 public:
  explicit RunCollector(SimulationResult& result) : result_(result) {}
  void on_sample(const LogSample& sample) override;
  void on_event(const EventRecord& event) override;
  void on_step(const StepRecord& step) override;

 private:
  SimulationResult& result_;
};

struct SimulationResult {
  /// Filled by the in-memory record (RunCollector) only; empty when a run streams to a sink.
  std::vector<LogSample> samples;
  std::vector<EventRecord> events;
  std::vector<StepRecord> steps;
  std::optional<Failure> failure;               ///< why the run stopped early; empty if it completed
  int steps_completed = 0;                      ///< touchdowns of new legs
  long long event_count = 0;                    ///< events recorded (events.csv's rows), kept or streamed
  std::vector<std::string> gaits;               ///< the gait label of every completed step, in order
  StepRecord last_step;                         ///< the step under way at the end (or the last one)
  double t_final = 0;                           ///< [s]
  double energy_initial = 0, energy_final = 0;  ///< mechanical energy [J]
  double work_damping = 0, work_friction = 0;   ///< [J]
  /// |E_final + W_damp + W_fric - E_initial| / (KE_0 + m g L0 + W_damp + W_fric): relative to the
  /// energy that flowed, independent of where the potential's zero is.
  double energy_balance_error = 0;
  double mean_speed = 0;      ///< hub displacement along the slope / time, to the last touchdown [m/s]
  int jams = 0;               ///< feet stopped by jam impulses
  int ambiguous_choices = 0;  ///< events where more than one mode combination was consistent
  long long solver_steps = 0, rhs_evals = 0;
  std::vector<double> final_state;  ///< full state vector at t_final
  ContactSet final_contacts;

  /// The fields of `summary.json` (after the model's name), in order.
  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("steps", s.steps_completed, {.doc = "touchdowns of new legs"});
    v("gaits", s.gaits, {.doc = "gait label of every completed step (stance-foot phases in single support)"});
    v("mean_speed", s.mean_speed,
      {.unit = "m/s", .doc = "hub displacement along the slope over time, to the last touchdown"});
    v("t_final", s.t_final, {.unit = "s", .doc = "simulated time"});
    v("energy_initial", s.energy_initial, {.unit = "J", .doc = "mechanical energy at the start"});
    v("energy_final", s.energy_final, {.unit = "J", .doc = "mechanical energy at the end"});
    v("work_damping", s.work_damping, {.unit = "J", .doc = "energy dissipated by the leg dampers"});
    v("work_friction", s.work_friction, {.unit = "J", .doc = "energy dissipated by friction and jam impulses"});
    v("energy_balance_error", s.energy_balance_error,
      {.doc = "|E_final + W_damp + W_fric − E_initial| over the energy that flowed"});
    v("jams", s.jams, {.doc = "feet stopped by jam impulses"});
    v("ambiguous_mode_choices", s.ambiguous_choices,
      {.doc = "events where more than one mode combination was consistent"});
    std::int64_t events = s.event_count;
    v("events", events, {.doc = "hybrid events"});
    std::int64_t solver_steps = s.solver_steps, rhs_evals = s.rhs_evals;
    v("solver_steps", solver_steps, {.doc = "integrator steps"});
    v("rhs_evals", rhs_evals, {.doc = "right-hand-side evaluations"});
    std::optional<std::string> failure;
    if (s.failure) failure = s.failure->text();
    v("failure", failure, {.doc = "why the run stopped early; null when it completed"});
  }
};

/// "3:stick 4:slip+" for a contact set; "flight" if empty.
std::string describe_contacts(const ContactSet& contacts);

/// On one foot the wheel is an inverted pendulum whose only equilibrium is the stance leg at the
/// true vertical (β = -φ); it leaves a neighbourhood of it at the rate λ ≈ sqrt(g / L0). A wheel
/// still within 1e-3 rad and 1e-3 sqrt(g / L0) of it when no leg has landed for max_step_time
/// balances there (from rest exactly at the vertical round-off tips it over only after ~14 s on
/// configs/rimless.yaml; from 1e-3 it needs ln(α / 1e-3) / λ ≈ 1.8 s more): the outcome is named
/// (FailureReason::BalancedAtVertical), not left to the limit. beta: the stance leg's angle from
/// the slope's normal, omega = θ̇.
bool balanced_at_vertical(const WheelParams& w, double beta, double omega);

}  // namespace flexgait::rimless
