// The builtin walking controller in the loop's slot: its context is what it used (the readings
// after its health check), its support plan's single-support phase runs from 0 at lift-off to 1
// at touchdown and is −1 in double support.
#include "flexgait/loop/walking_control.hpp"

#include <gtest/gtest.h>

#include "flexgait/experiments/walk_experiment.hpp"

namespace flexgait::loop {
namespace {

TEST(WalkingControl, ItsContextIsWhatItUsedAndItsPhaseRunsThroughEachStep) {
  experiments::WalkRunParams p;
  p.walk.steps = 2;
  experiments::WalkLoop w = experiments::make_walk_loop(p);
  const walking::WalkingController& c = w.control->controller();
  const walking::Step& first = c.plan().steps.front();
  double last_phase = -1, largest = -1;
  int last_step = -2;
  bool saw_single = false, saw_double = false;
  while (w.loop->time() < first.t_land + 0.2) {
    ASSERT_FALSE(w.loop->step());
    const ControlContext* context = w.control->context();
    ASSERT_NE(context, nullptr);
    EXPECT_EQ(context->sensors.encoder, c.sensors().encoder);
    EXPECT_EQ(context->sensors_good, c.status().sensor_flags == 0);
    const double s = context->support.single_support_phase;
    if (c.status().swinging[0] || c.status().swinging[1]) {
      saw_single = true;
      EXPECT_GE(s, 0.0);
      EXPECT_LE(s, 1.0);
      if (c.status().step == last_step) {
        EXPECT_GE(s, last_phase - 1e-12);  // non-decreasing within a step
      }
      last_step = c.status().step;
      last_phase = s;
      largest = std::max(largest, s);
    } else {
      saw_double = true;
      EXPECT_EQ(s, -1.0);
    }
  }
  EXPECT_TRUE(saw_single && saw_double);
  EXPECT_NEAR(largest, 1.0, 0.02);  // touchdown reached
}

}  // namespace
}  // namespace flexgait::loop
