// A push timed by the walking phase (experiments/push_timing.hpp): step n, phase s starts at
// t_lift + s (t_land − t_lift) of the plan's n-th step; step 0 keeps its own time; a step beyond the
// plan, or a time given beside a step, is refused naming its key.
#include "flexgait/experiments/push_timing.hpp"

#include <gtest/gtest.h>

#include <string>

#include "flexgait/walking/footstep_plan.hpp"

namespace flexgait::experiments {
namespace {

walking::WalkPlan three_steps() {
  walking::WalkParams w;
  w.steps = 3;
  return walking::plan_footsteps(w);
}

twin::Push timed(int step, double phase, double time = 0.0) {
  twin::Push p;
  p.step = step;
  p.phase = phase;
  p.time = time;
  return p;
}

TEST(PushTiming, PhaseRunsFromLiftOffToTouchdownOfItsStep) {
  const walking::WalkPlan plan = three_steps();
  ASSERT_EQ(plan.steps.size(), 3u);
  for (int n = 1; n <= 3; ++n) {
    const walking::Step& s = plan.steps[static_cast<std::size_t>(n - 1)];
    ASSERT_LT(s.t_lift, s.t_land);
    EXPECT_EQ(push_start_time(timed(n, 0.0), plan), s.t_lift);
    EXPECT_DOUBLE_EQ(push_start_time(timed(n, 1.0), plan), s.t_land);
    EXPECT_DOUBLE_EQ(push_start_time(timed(n, 0.3), plan), s.t_lift + 0.3 * (s.t_land - s.t_lift));
  }
  EXPECT_EQ(push_start_time(timed(0, 0.7, 1.25), plan), 1.25);
  const auto pushes = timed_pushes({timed(0, 0.0, 0.5), timed(2, 0.5)}, plan);
  EXPECT_EQ(pushes[0].time, 0.5);
  EXPECT_EQ(pushes[1].time, push_start_time(timed(2, 0.5), plan));
}

std::string refused_key(const twin::Push& push) {
  try {
    check_push_timing(push, three_steps(), "disturbance.pushes[1].");
  } catch (const ConfigError& e) {
    return e.key();
  }
  return "";
}

TEST(PushTiming, StepBeyondThePlanOrATimeBesideAStepIsRefused) {
  EXPECT_EQ(refused_key(timed(3, 0.5)), "");
  EXPECT_EQ(refused_key(timed(0, 0.0, 4.0)), "");
  EXPECT_EQ(refused_key(timed(4, 0.5)), "disturbance.pushes[1].step");
  EXPECT_EQ(refused_key(timed(1, 0.5, 2.0)), "disturbance.pushes[1].time");
}

}  // namespace
}  // namespace flexgait::experiments
