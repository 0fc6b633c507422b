#pragma once
/// \file push_timing.hpp
/// A push timed by the walking phase (docs/guide/humanoid.md): `step` n ≥ 1 starts it in the single support of
/// the plan's n-th step, at the fraction `phase` of it (0 lift-off, 1 touchdown):
///     t = t_lift,n + phase (t_land,n − t_lift,n);
/// `step` 0 keeps the push's own `time`.
#include <string>
#include <vector>

#include "flexgait/twin/disturbance.hpp"
#include "flexgait/walking/footstep_plan.hpp"

namespace flexgait::experiments {

/// The start time of `push` in `plan` [s]. Requires push.step ≤ plan.steps.size().
double push_start_time(const twin::Push& push, const walking::WalkPlan& plan);

/// `pushes` with their start times resolved in `plan` (step 0: as given).
std::vector<twin::Push> timed_pushes(std::vector<twin::Push> pushes, const walking::WalkPlan& plan);

/// Throws ConfigError naming `key_prefix` + "step" (or "time") for a push whose step is beyond
/// the plan, or that gives both a time and a step (key_prefix e.g. "disturbance.pushes[2]." or
/// "disturbance.push.").
void check_push_timing(const twin::Push& push, const walking::WalkPlan& plan, const std::string& key_prefix);

}  // namespace flexgait::experiments
