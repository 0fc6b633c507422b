// The walk's scorer is an observer: composed by hand on a loop it gives run_walk's result to the
// last digit; a failed simulation is scored as the walk's failure; a step's landing is taken once
// its foot is down, at the latest when the next step lifts, so a foot a push makes land late is a
// landing, not a missed step.
#include "flexgait/experiments/walk_scorer.hpp"

#include <gtest/gtest.h>

#include "../support/mujoco_warnings.hpp"

#include "flexgait/experiments/walk_output.hpp"
#include "flexgait/loop/closed_loop.hpp"

namespace flexgait::experiments {
namespace {

TEST(WalkScorer, AHandComposedLoopScoresAsRunWalk) {
  WalkRunParams p;
  p.walk.steps = 2;
  const WalkResult reference = run_walk(p);
  WalkLoop w = make_walk_loop(p);
  WalkScorer scorer(p, w.control->controller(), w.loop->truth(), w.pushes, {});
  w.loop->attach(scorer);
  const long ticks = std::lround(w.control->controller().plan().duration / p.plant.control_period);
  for (long k = 0; k < ticks && !scorer.fell(); ++k) ASSERT_FALSE(w.loop->step());
  const WalkResult r = scorer.finish(*w.loop);
  EXPECT_EQ(walk_summary_json(r), walk_summary_json(reference));
  EXPECT_EQ(walk_footsteps_csv(r), walk_footsteps_csv(reference));
  EXPECT_EQ(r.log.size(), reference.log.size());
}

TEST(WalkScorer, AFailedSimulationIsTheWalksFailure) {
  WalkRunParams p;
  p.walk.steps = 2;
  WalkLoop w = make_walk_loop(p);
  WalkScorer scorer(p, w.control->controller(), w.loop->truth(), w.pushes, {});
  w.loop->attach(scorer);
  twin::Push push;
  push.time = 0.0;
  push.force = {0, 0, 1e12};
  w.loop->plant().set_pushes({push});
  for (int k = 0; k < 50; ++k)
    if (w.loop->step()) break;
  const WalkResult r = scorer.finish(*w.loop);
  ASSERT_TRUE(r.metrics.failure.has_value());
  test_support::take_mujoco_warnings();  // the failure this test provokes (MuJoCo warns of it)
  EXPECT_EQ(r.metrics.outcome(), "simulation_failure");
  EXPECT_EQ(r.metrics.failure_time, w.loop->time());
}

TEST(WalkScorer, AStepsLandingIsTakenOnceItsFootIsDownAndAtTheLatestWhenTheNextStepLifts) {
  walking::WalkPlan plan;
  plan.steps.resize(2);
  plan.steps[0].t_land = 2.0;
  plan.steps[1].t_begin = 2.0;
  plan.steps[1].t_lift = 2.2;
  plan.steps[1].t_land = 3.0;
  plan.t_settle = 3.2;
  const double settle = 0.1;
  // Before touchdown + settle: never; then at once if the foot is down.
  EXPECT_FALSE(landing_due(plan, 0, settle, 2.09, true));
  EXPECT_TRUE(landing_due(plan, 0, settle, 2.1, true));
  // In the air: waited for until the next step lifts, then taken (and judged missed).
  EXPECT_FALSE(landing_due(plan, 0, settle, 2.19, false));
  EXPECT_TRUE(landing_due(plan, 0, settle, 2.2, false));
  // The last step: until the plan's last double support ends.
  EXPECT_FALSE(landing_due(plan, 1, settle, 3.19, false));
  EXPECT_TRUE(landing_due(plan, 1, settle, 3.2, false));
  EXPECT_FALSE(landing_due(plan, 2, settle, 10.0, true));  // no such step
}

/// Records whether the left sole touched the floor at one time.
class LeftSoleAt final : public loop::LoopObserver {
 public:
  explicit LeftSoleAt(double t) : t_(t) {}
  void observe(const loop::LoopStep& step) override {
    if (!seen_ && step.after.t >= t_ - 1e-9) {
      seen_ = true;
      down_ = step.after.sole_contact[0];
    }
  }
  bool seen() const { return seen_; }
  bool down() const { return down_; }

 private:
  double t_;
  bool seen_ = false, down_ = false;
};

TEST(WalkScorer, AFootAPushMakesLandLateIsALandingNotAMissedStep) {
  // The thesis's static load model, dcm with step adjustment, 6 steps at 1 s/step; 32 N s at the chest toward the
  // swing foot at mid single support of the 3rd step. The pushed step lands early and the robot rolls back over
  // it; the next (left) foot touches the floor, bounces off it, and comes down again 40 ms after its touchdown
  // plus half the double support, before the following step lifts (docs/guide/humanoid.md, "Pushes"). Taken at
  // touchdown plus half the double support, as the landing was before, it was judged a missed step.
  const WalkRunParams p = walk_run_from_config(
      resolve_config(walk_run_schema(), std::nullopt,
                     {"walk.steps=6", "balance.mode=dcm", "balance.step_adjustment=true", "control.load_model=gravity",
                      "control.gear_damping=0", "control.load_filter_time=0.1", "disturbance.push.step=3",
                      "disturbance.push.phase=0.5", "disturbance.push.force_y=-320", "disturbance.push.duration=0.1"}));
  const walking::Step left = walking::plan_footsteps(p.walk).steps[3];
  ASSERT_EQ(left.swing, 0);
  LeftSoleAt late(left.t_land + landing_settle(p));
  const WalkResult r = run_walk(p, {}, [&](WalkLoop& w) { w.loop->attach(late); });
  ASSERT_TRUE(late.seen());
  EXPECT_FALSE(late.down()) << "the left foot was down at its touchdown plus half the double support";
  EXPECT_EQ(r.metrics.outcome(), "walked") << r.metrics.outcome();
  EXPECT_EQ(r.landings.size(), 6U);
}

}  // namespace
}  // namespace flexgait::experiments
