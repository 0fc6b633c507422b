#include "flexgait/experiments/push_timing.hpp"

#include <fmt/format.h>

#include "flexgait/core/config.hpp"

namespace flexgait::experiments {

double push_start_time(const twin::Push& push, const walking::WalkPlan& plan) {
  if (push.step <= 0) return push.time;
  const walking::Step& s = plan.steps.at(static_cast<std::size_t>(push.step - 1));
  return s.t_lift + push.phase * (s.t_land - s.t_lift);
}

std::vector<twin::Push> timed_pushes(std::vector<twin::Push> pushes, const walking::WalkPlan& plan) {
  for (twin::Push& p : pushes) p.time = push_start_time(p, plan);
  return pushes;
}

void check_push_timing(const twin::Push& push, const walking::WalkPlan& plan, const std::string& key_prefix) {
  if (push.step <= 0) return;
  if (push.time != 0)
    throw ConfigError(key_prefix + "time", fmt::format("key '{}time' = '{}': a push is timed by its time or by "
                                                       "{}step and {}phase, not both",
                                                       key_prefix, push.time, key_prefix, key_prefix));
  if (static_cast<std::size_t>(push.step) > plan.steps.size())
    throw ConfigError(key_prefix + "step",
                      fmt::format("key '{}step' = '{}': the walk has {} steps; allowed: 0 (timed "
                                  "by {}time) to {}",
                                  key_prefix, push.step, plan.steps.size(), key_prefix, plan.steps.size()));
}

}  // namespace flexgait::experiments
