#include "flexgait/numerics/hybrid_simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace flexgait::numerics {

HybridSimulation::HybridSimulation(OdeIntegrator& integrator, int n)
    : integrator_(integrator), y_(static_cast<std::size_t>(n)), y_dense_(static_cast<std::size_t>(n)) {
  events_.reserve(16);
}

double HybridSimulation::run(HybridModel& model, const HybridLimits& limits, double t0) {
  OdeIntegrator& integ = integrator_;
  double t = t0;
  double next_sample = t0 + limits.sample_dt;
  long sample_index = 1;

  // Repeated-event watch: the latest event and its time.
  HybridEvent last_event{};
  double last_event_time = -std::numeric_limits<double>::infinity();
  // Zeno watch: the times of the latest kZenoCount events, a ring.
  std::array<double, kZenoCount> recent_events{};
  std::size_t events_seen = 0;

  const auto wall0 = std::chrono::steady_clock::now();
  long long solver_calls = 0;
  double window_start = t;  // where the current step-rate window began [s]
  while (!model.finished()) {
    ++solver_calls;
    if (solver_calls == 1 && !model.ready(t)) break;
    if (limits.poll && (solver_calls == 1 || solver_calls % 256 == 0)) limits.poll();
    if (solver_calls % 256 == 0) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      if (wall > limits.max_wall_time) {
        model.work_limit_reached(WorkLimit::WallTime, t, wall);
        break;
      }
    }
    if (solver_calls % kRateWindow == 0) {
      const double rate = static_cast<double>(kRateWindow) / std::max(t - window_start, 1e-300);
      if (rate > limits.max_step_rate) {
        model.work_limit_reached(WorkLimit::StepRate, t, rate);
        break;
      }
      window_start = t;
    }
    StepStatus status;
    try {
      status = integ.step(model.stop_time());
    } catch (const std::runtime_error& e) {
      model.loop_failed(LoopFailure::Solver, t, e.what());
      break;
    }
    t = integ.time();
    const auto state = integ.state();
    std::copy(state.begin(), state.end(), y_.begin());
    model.stepped(t, y_);
    if (status == StepStatus::Guard) t = model.event_time(t, y_, integ.guards_fired(), integ);
    if (limits.sample) {
      while (next_sample < t) {
        integ.interpolate(next_sample, y_dense_);
        model.sample(next_sample, y_dense_);
        next_sample = t0 + limits.sample_dt * static_cast<double>(++sample_index);
      }
    }

    if (status != StepStatus::Guard) {
      if (!model.smooth_step(t, y_, status)) break;
      continue;
    }

    // A guard crossed: the model names the events; the loop watches them; the model resets.
    events_.clear();
    const HybridNext next = model.guards_crossed(t, y_, integ.guards_fired(), integ, events_);
    if (next == HybridNext::Stop) break;
    if (next == HybridNext::Continue) continue;
    bool stop = false;
    for (const HybridEvent& e : events_) {
      // docs/theory/rimless.md, "Events and contact modes": an event must not fire again at its own restart point.
      if (e.unit == last_event.unit && e.kind == last_event.kind && t - last_event_time < kRepeatWindow) {
        model.loop_failed(LoopFailure::RepeatedEvent, t, model.describe(e));
        stop = true;
      }
      if (!model.admissible(t, y_, e)) stop = true;
      recent_events[events_seen++ % kZenoCount] = t;
    }
    // The newest of the latest kZenoCount event times is the slot written last, the oldest the next.
    if (events_seen >= kZenoCount &&
        recent_events[(events_seen - 1) % kZenoCount] - recent_events[events_seen % kZenoCount] < kZenoWindow) {
      model.loop_failed(LoopFailure::Zeno, t, fmt::format("{} events within {} s", kZenoCount, kZenoWindow));
      stop = true;
    }
    if (stop) break;

    const HybridNext after = model.reset(t, y_, events_);
    if (after == HybridNext::Stop) break;
    if (!events_.empty()) {
      last_event = events_.back();
      last_event_time = t;
    }
    if (after == HybridNext::Continue) continue;
    const std::span<const double> S = model.restart_sensitivities();
    if (S.empty())
      integ.restart(t, y_, model.directions());
    else
      integ.restart(t, y_, model.directions(), S);
    model.restarted(t, y_);
  }
  return t;
}

}  // namespace flexgait::numerics
