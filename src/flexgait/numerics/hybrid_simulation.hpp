#pragma once
/// \file hybrid_simulation.hpp
/// The one loop of an event-driven hybrid simulation (both rimless wheels run on it): step the
/// integrator, sample its dense output, hand guard crossings to the model, watch for Zeno
/// sequences and for an event firing again at its own restart point, enforce the work limits,
/// restart after every reset, count the integrator's work.
///
/// The model (HybridModel) supplies its flow and guards (OdeSystem, given to the integrator)
/// and, Drake-style, what each guard crossing means: which events fired (its named guards),
/// whether each is admissible, and the reset that follows (each reset checks its own
/// postcondition). The loop knows no model, no units and no configuration keys: it reports its
/// own stops through HybridModel::loop_failed() and HybridModel::work_limit_reached().
#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/numerics/ode_integrator.hpp"

namespace flexgait::numerics {

/// One event at a guard crossing, as the loop sees it: the part of the model it concerns (a leg)
/// and the model's kind of event. Two events are the same when both fields are.
struct HybridEvent {
  int unit = -1;
  int kind = 0;
};

/// What follows a guard crossing or a reset.
enum class HybridNext {
  Stop,      ///< the run ends here (a section was reached, or the model failed)
  Continue,  ///< the flow goes on unchanged (no reset: a guard that only marks a place)
  Restart,   ///< the state was reset: the integrator restarts at the crossing
};

/// The loop's own failures (HybridModel::loop_failed() says which; the model names them in its
/// own outcome).
enum class LoopFailure {
  Solver,         ///< the integrator threw (step size underflow, too much work, ...)
  RepeatedEvent,  ///< an event fired again within kRepeatWindow of its own restart point
  Zeno,           ///< kZenoCount events within kZenoWindow
};
constexpr std::array<EnumName<LoopFailure>, 3> enum_names(LoopFailure) {
  return {
      {{LoopFailure::Solver, "solver"}, {LoopFailure::RepeatedEvent, "repeated_event"}, {LoopFailure::Zeno, "zeno"}}};
}

/// The work limits the loop enforces (HybridModel::work_limit_reached() says why it stopped).
enum class WorkLimit {
  WallTime,  ///< HybridLimits::max_wall_time of wall clock passed
  StepRate,  ///< more than HybridLimits::max_step_rate steps per simulated second, over kRateWindow steps
};

struct HybridLimits {
  bool sample = false;                                             ///< hand dense-output samples to the model
  double sample_dt = 0.0;                                          ///< sampling period from the start time [s]
  double max_wall_time = std::numeric_limits<double>::infinity();  ///< [s] of wall clock
  double max_step_rate = std::numeric_limits<double>::infinity();  ///< integrator steps per simulated second
  /// Called before the first integrator step and every 256 after it (e.g. to see a Ctrl-C); may
  /// throw to abandon the run, the exception passed on to run()'s caller. Empty: nothing called.
  std::function<void()> poll;
};

class HybridModel {
 public:
  virtual ~HybridModel() = default;
  /// True once the run has done what it was asked (checked before every integrator step).
  virtual bool finished() const = 0;
  /// Before the first integrator step: false (the model's outcome recorded) if the run cannot start.
  virtual bool ready(double t) {
    (void)t;
    return true;
  }
  /// The latest time the next integrator step may reach [s].
  virtual double stop_time() const = 0;
  /// A sample of the dense output at t (with HybridLimits::sample), y dim n.
  virtual void sample(double t, std::span<const double> y) { (void)t, (void)y; }
  /// After every integrator step, guard or not, with its end state (e.g. to arm guards).
  virtual void stepped(double t, std::span<const double> y) { (void)t, (void)y; }
  /// After a step that crossed no guard (status Step or StopTime): the model's checks (missed
  /// events, rest, time limits). false (the model's outcome recorded) stops the run.
  virtual bool smooth_step(double t, std::span<const double> y, StepStatus status) = 0;
  /// A guard crossed at t (the step's end), y the state there, fired as guards_fired(): where the
  /// events of that crossing happen. The model may move them back within the last step (a guard
  /// detected with a margin and located at its true zero), writing the state there into y;
  /// guards_crossed() is then called at the returned time.
  virtual double event_time(double t, std::span<double> y, std::span<const int> fired,
                            const OdeIntegrator& integrator) {
    (void)y, (void)fired, (void)integrator;
    return t;
  }
  /// A guard crossed at t, y the state there (before any reset), fired as guards_fired(). Writes
  /// the events into `events` and returns Restart to go on with them, or Stop (a section
  /// reached, a failure named) or Continue (nothing to reset).
  virtual HybridNext guards_crossed(double t, std::span<const double> y, std::span<const int> fired,
                                    const OdeIntegrator& integrator, std::vector<HybridEvent>& events) = 0;
  /// Whether event e at (t, y) may happen (false: the model's outcome recorded; the loop still looks at
  /// the other events of the instant, then stops).
  virtual bool admissible(double t, std::span<const double> y, const HybridEvent& e) {
    (void)t, (void)y, (void)e;
    return true;
  }
  /// The reset of the events at t: writes the new state into y and returns Restart (with the new
  /// guard directions in directions() and, with sensitivities, restart_sensitivities()), or Stop
  /// with the model's outcome recorded.
  virtual HybridNext reset(double t, std::span<double> y, std::span<const HybridEvent> events) = 0;
  /// The guard directions of the current mode (+1 upward, -1 downward, 0 both).
  virtual std::span<const int> directions() const = 0;
  /// With sensitivities: ∂y/∂y_ref after the latest reset, column-major n×n; empty without.
  virtual std::span<const double> restart_sensitivities() const { return {}; }
  /// After the integrator restarted at (t, y).
  virtual void restarted(double t, std::span<const double> y) { (void)t, (void)y; }
  /// The run stops at t for one of the loop's own reasons, with the detail behind it: the
  /// solver's message (Solver), the event in words (RepeatedEvent), the count and window (Zeno).
  virtual void loop_failed(LoopFailure what, double t, const std::string& detail) = 0;
  /// The run stops at a work limit at t; `measured` is the wall time [s] or the step rate [1/s].
  virtual void work_limit_reached(WorkLimit limit, double t, double measured) = 0;
  /// "leg 3 touchdown": an event in words (the repeated-event failure names it).
  virtual std::string describe(const HybridEvent& e) const = 0;
};

class HybridSimulation {
 public:
  static constexpr long long kRateWindow = 4096;  ///< steps over which the step rate is averaged
  static constexpr std::size_t kZenoCount = 64;   ///< this many events ...
  static constexpr double kZenoWindow = 1e-9;     ///< ... within this time [s] are a Zeno sequence
  static constexpr double kRepeatWindow = 1e-10;  ///< an event again within this time [s] of itself fails

  /// \param integrator restarted by the caller at the start (t0, y0) of the run; it must
  ///   outlive this object. n: its state dimension.
  HybridSimulation(OdeIntegrator& integrator, int n);

  /// Runs from the integrator's start time t0 until the model is finished or stops.
  /// \return the time reached [s].
  double run(HybridModel& model, const HybridLimits& limits, double t0);

 private:
  OdeIntegrator& integrator_;
  std::vector<double> y_;            // (dim n) state at the latest step's end
  std::vector<double> y_dense_;      // (dim n) one dense-output sample
  std::vector<HybridEvent> events_;  // the events of one instant
};

}  // namespace flexgait::numerics
