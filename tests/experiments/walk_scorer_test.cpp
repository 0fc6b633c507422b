// The walk's scorer is an observer: composed by hand on a loop it gives run_walk's result to the
// last digit; a failed simulation is scored as the walk's failure.
#include "flexgait/experiments/walk_scorer.hpp"

#include <gtest/gtest.h>

#include "../support/mujoco_warnings.hpp"

#include "flexgait/experiments/walk_output.hpp"

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

}  // namespace
}  // namespace flexgait::experiments
