#include "flexgait/experiments/push_recovery.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "flexgait/experiments/push_timing.hpp"
#include "flexgait/walking/footstep_plan.hpp"

namespace flexgait::experiments {

PushRecovery bracket_first_fall(const std::function<bool(double)>& falls, double lower, double upper, double tolerance,
                                double scan_step) {
  PushRecovery out;
  const auto run = [&](double impulse) {
    ++out.runs;
    return falls(impulse);
  };
  double lo = lower, hi = upper;
  bool fell_on_scan = false;
  if (scan_step > 0) {
    for (int i = 1; lower + i * scan_step < upper; ++i) {
      const double impulse = lower + i * scan_step;
      if (run(impulse)) {
        fell_on_scan = true;
        hi = impulse;
        break;
      }
      lo = impulse;
    }
  }
  if (!fell_on_scan && !run(upper)) {
    out.bracketed = false;
    out.recovered = upper;
    out.fell = std::numeric_limits<double>::quiet_NaN();
    return out;
  }
  while (hi - lo > tolerance) {
    const double mid = 0.5 * (lo + hi);
    (run(mid) ? hi : lo) = mid;
  }
  out.recovered = lo;
  out.fell = hi;
  return out;
}

PushRecovery largest_recoverable_push(WalkRunParams base, const Eigen::Vector2d& direction, double upper,
                                      double tolerance, double scan_step, double lower) {
  const Eigen::Vector2d u = direction.normalized();
  double bound = 0;
  const auto falls = [&](double impulse) {
    const double f = impulse / base.push.duration;
    base.push.force = {f * u.x(), f * u.y(), 0.0};
    const WalkMetrics m = run_walk(base).metrics;
    if (m.pushed) bound = m.capture_point_bound;
    return m.fell;
  };
  PushRecovery out = bracket_first_fall(falls, lower, upper, tolerance, scan_step);
  out.bound = bound;
  return out;
}

Eigen::Vector2d push_direction_vector(PushDirection d) {
  switch (d) {
    case PushDirection::kForward:
      return {1, 0};
    case PushDirection::kBackward:
      return {-1, 0};
    case PushDirection::kLeft:
      return {0, 1};
    case PushDirection::kRight:
      return {0, -1};
  }
  throw std::logic_error("push_direction_vector: unknown direction");
}

PushRecoveryRunParams push_recovery_from_config(const Config& config) {
  PushRecoveryRunParams p;
  p.run = walk_run_from_config(config);
  p.test = record_from_config<PushRecoveryParams>(config);
  check_with_origin(config, [&] {
    for (const char* key :
         {"disturbance.push.force_x", "disturbance.push.force_y", "disturbance.push.force_z", "disturbance.push.time"})
      if (config.real(key) != 0)
        throw ConfigError(key, std::string(key) + ": set by the push-recovery test (push_recovery.*); leave it 0");
    if (config.integer("disturbance.push.step") != 0)
      throw ConfigError("disturbance.push.step",
                        "disturbance.push.step: set by the push-recovery test (push_recovery.step); leave it 0");
    if (p.test.scan_step > 0 && p.test.scan_step < p.test.tolerance)
      throw ConfigError("push_recovery.scan_step",
                        fmt::format("push_recovery.scan_step: {:g} N s is finer than push_recovery.tolerance = {:g} N "
                                    "s; allowed: 0 (bisection alone) or at least the tolerance",
                                    p.test.scan_step, p.test.tolerance));
    if (p.run.push.duration <= 0)
      throw ConfigError("disturbance.push.duration", "disturbance.push.duration: the push needs a duration > 0");
    if (p.test.situation == PushSituation::kWalking && p.test.step >= p.run.walk.steps)
      throw ConfigError("push_recovery.step",
                        "push_recovery.step: " + std::to_string(p.test.step) +
                            " must be a step before the last, below walk.steps = " + std::to_string(p.run.walk.steps));
  });
  return p;
}

namespace {

/// The walking situation's push: disturbance.push.* at mid single support of push_recovery.step.
twin::Push walking_push(const PushRecoveryRunParams& p) {
  twin::Push push = p.run.push;
  push.time = 0;
  push.step = p.test.step;
  push.phase = 0.5;
  return push;
}

}  // namespace

double push_recovery_time(const PushRecoveryRunParams& p) {
  if (p.test.situation == PushSituation::kStanding) return p.test.stand_time;
  return push_start_time(walking_push(p), walking::plan_footsteps(p.run.walk));  // mid single support
}

PushRecoveryResult run_push_recovery(const PushRecoveryRunParams& p) {
  WalkRunParams base = p.run;
  PushRecoveryResult out;
  out.situation = p.test.situation;
  out.direction = p.test.direction;
  out.push_time = push_recovery_time(p);
  if (p.test.situation == PushSituation::kStanding) {
    base.walk.steps = 0;
    base.walk.end_time = out.push_time + p.test.settle_time;
    base.push.time = out.push_time;
  } else {
    base.push = walking_push(p);
  }
  const Eigen::Vector2d u = push_direction_vector(p.test.direction);
  double upper = p.test.upper, lower = 0;
  for (int doubling = 0;; ++doubling) {
    const PushRecovery r = largest_recoverable_push(base, u, upper, p.test.tolerance, p.test.scan_step, lower);
    out.runs += r.runs;
    if (r.bracketed) {
      out.recovered = r.recovered;
      out.fell_at = r.fell;
      out.bound = r.bound;
      break;
    }
    if (doubling == 3) {  // upper still recovered after three doublings: recovered = upper, no fall seen
      out.recovered = upper;
      out.fell_at = std::numeric_limits<double>::quiet_NaN();
      base.push.force = {upper / base.push.duration * u.x(), upper / base.push.duration * u.y(), 0};
      out.bound = run_walk(base).metrics.capture_point_bound;
      ++out.runs;
      break;
    }
    if (p.test.scan_step > 0) lower = upper;  // (the scan goes on above the recovered upper)
    upper *= 2;                               // upper recovered: a wider bracket
  }
  out.fraction = out.bound > 0 ? out.recovered / out.bound : std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace flexgait::experiments
