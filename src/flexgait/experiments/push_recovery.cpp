#include "flexgait/experiments/push_recovery.hpp"

#include <stdexcept>

namespace flexgait::experiments {

PushRecovery largest_recoverable_push(WalkRunParams base, const Eigen::Vector2d& direction, double upper,
                                      double tolerance) {
  const Eigen::Vector2d u = direction.normalized();
  PushRecovery out;
  const auto falls = [&](double impulse) {
    const double f = impulse / base.push.duration;
    base.push.force = {f * u.x(), f * u.y(), 0.0};
    const WalkMetrics m = run_walk(base).metrics;
    ++out.runs;
    if (m.pushed) out.bound = m.capture_point_bound;
    return m.fell;
  };
  if (!falls(upper)) throw std::invalid_argument("largest_recoverable_push: the upper end is recovered");
  double lo = 0, hi = upper;
  while (hi - lo > tolerance) {
    const double mid = 0.5 * (lo + hi);
    (falls(mid) ? hi : lo) = mid;
  }
  out.recovered = lo;
  out.fell = hi;
  return out;
}

}  // namespace flexgait::experiments
