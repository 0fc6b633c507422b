// The step tracker: a tracker whose final steps are taken as they come holds two records at
// most and hands out exactly the records of one that keeps them all.
#include "flexgait/rimless/gait.hpp"

#include <gtest/gtest.h>

namespace flexgait::rimless {
namespace {

ContactSet feet(std::initializer_list<std::pair<int, FootMode>> list) {
  ContactSet c;
  for (const auto& [leg, mode] : list) {
    c.leg[c.count] = leg;
    c.mode[c.count++] = mode;
  }
  return c;
}

bool same(const StepRecord& a, const StepRecord& b) {
  return a.index == b.index && a.stance_leg == b.stance_leg && a.t_start == b.t_start && a.t_end == b.t_end &&
         a.x_start == b.x_start && a.x_end == b.x_end && a.single_support == b.single_support &&
         a.contact == b.contact && a.complete == b.complete;
}

TEST(StepTracker, TakingFinalStepsKeepsTwoRecordsAndTheSameSteps) {
  constexpr int legs = 10;
  StepTracker all, bounded;
  std::vector<StepRecord> taken;
  for (StepTracker* t : {&all, &bounded}) t->start(0.0, 0.0, 1.0, feet({{0, FootMode::Stick}}), legs);
  int stance = 0;
  for (int i = 1; i <= 1000; ++i) {
    const int next = (stance + legs - 1) % legs;
    const double t = 0.5 * i;
    // Single support slips then sticks; the next leg lands slipping; the old foot leaves after.
    for (StepTracker* tr : {&all, &bounded}) {
      tr->observe(feet({{stance, FootMode::SlipForward}}));
      tr->observe(feet({{stance, FootMode::Stick}}));
      tr->touchdown(t, 0.1 * i, 1.0, next, feet({{stance, FootMode::Stick}, {next, FootMode::SlipForward}}));
      tr->observe(feet({{stance, FootMode::SlipBackward}, {next, FootMode::Stick}}));
      tr->observe(feet({{next, FootMode::Stick}}));
    }
    for (const StepRecord& s : bounded.final_steps()) taken.push_back(s);
    bounded.drop_final_steps();
    EXPECT_LE(bounded.steps().size(), 2u);
    stance = next;
  }
  for (StepTracker* tr : {&all, &bounded}) tr->finish(600.0, 123.0);
  for (const StepRecord& s : bounded.steps()) taken.push_back(s);
  ASSERT_EQ(taken.size(), all.steps().size());
  for (std::size_t i = 0; i < taken.size(); ++i) EXPECT_TRUE(same(taken[i], all.steps()[i])) << "step " << i + 1;
  EXPECT_EQ(bounded.gaits(), all.gaits());
  EXPECT_EQ(all.gaits().size(), 1000u);
  // Each step: the stance foot sticks alone (after the old foot left), slips, sticks.
  EXPECT_EQ(all.gaits().front(), "stick-slip-stick");
  EXPECT_EQ(all.gaits().back(), "stick-slip-stick");
  ASSERT_NE(bounded.last_complete(), nullptr);
  EXPECT_EQ(bounded.last_complete()->index, 1000);
}

// The touchdown-stick prefix: the landing foot (leg 9) slips back, sticks and slips forward again,
// all in double support, then slips on and sticks in single support: "touchdown-stick slip-stick".
// Without the stick in double support, or when single support begins sticking, no prefix.
TEST(StepTracker, AStickInTheLandingDoubleSupportThenASlipIsNamed) {
  const auto step = [](std::initializer_list<FootMode> landing, std::initializer_list<FootMode> single) {
    StepTracker t;
    t.start(0.0, 0.0, 1.0, feet({{0, FootMode::Stick}}), 10);
    bool first = true;
    for (FootMode m : landing) {
      if (first)
        t.touchdown(1.0, 0.1, 1.0, 9, feet({{0, FootMode::SlipForward}, {9, m}}));
      else
        t.observe(feet({{0, FootMode::SlipForward}, {9, m}}));
      first = false;
    }
    for (FootMode m : single) t.observe(feet({{9, m}}));
    t.touchdown(2.0, 0.2, 1.0, 8, feet({{9, FootMode::SlipForward}, {8, FootMode::SlipBackward}}));
    return t.gaits().back();
  };
  using enum FootMode;
  EXPECT_EQ(step({SlipBackward, Stick, SlipForward}, {SlipForward, Stick}), "touchdown-stick slip-stick");
  EXPECT_EQ(step({SlipBackward, SlipForward}, {SlipForward, Stick}), "slip-stick");
  EXPECT_EQ(step({SlipBackward, Stick}, {Stick, SlipForward}), "stick-slip");
}

}  // namespace
}  // namespace flexgait::rimless
