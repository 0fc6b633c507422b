// The walk's judge against synthetic trajectories: a true walk passes every check (also one that
// drifts as a whole), and a thrown, sliding, flipped or mis-stepping robot gets its named outcome
// at the period the limit is passed.
#include "flexgait/experiments/walk_judge.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace flexgait::experiments {
namespace {

constexpr double kDt = 0.008;         // control period [s]
constexpr double kHeight = 0.7;       // pelvis height [m]
constexpr double kTolerance = 0.075;  // half a 0.15 m wide sole [m]

JudgeLimits limits() {
  JudgeLimits L;
  L.pelvis_height = kHeight;
  L.position_tolerance = kTolerance;
  L.sole_lift_tolerance = 0.022;  // a tenth of a 0.22 m sole
  return L;
}

/// Standing on both soles where planned at (0, ±0.1).
SupportSample standing(double t) {
  SupportSample s;
  s.t = t;
  s.sole_contact = {true, true};
  s.pelvis_height = kHeight;
  s.sole = {Eigen::Vector2d(0, 0.1), Eigen::Vector2d(0, -0.1)};
  return s;
}

PlannedSupport plan_of(const SupportSample& s) {
  PlannedSupport p;
  p.sole = s.sole;
  return p;
}

TEST(WalkJudge, ATrueWalkPassesEveryCheck) {
  // Ten 0.2 m steps, alternating, one sole always down; each lands 1 cm from its plan.
  WalkJudge judge(limits());
  SupportSample s = standing(0);
  PlannedSupport plan = plan_of(s);
  const int per_step = 100;
  for (int step = 0; step < 10; ++step) {
    const int swing = step % 2;
    for (int i = 0; i < per_step; ++i) {
      s.t += kDt;
      plan.swinging[swing] = i < per_step / 2;
      s.sole_contact[swing] = !plan.swinging[swing];
      if (i == per_step / 2) {  // touchdown
        plan.sole[swing].x() += 0.2;
        s.sole[swing] = plan.sole[swing] + Eigen::Vector2d(0.01, 0);
      }
      ASSERT_FALSE(judge.check(s, plan)) << "t = " << s.t;
    }
    EXPECT_FALSE(judge.landing(s, swing, plan));
  }
  EXPECT_FALSE(judge.at_end(s, plan));
  EXPECT_EQ(judge.support_error_max(), 0.0);  // no sole moved while down
}

TEST(WalkJudge, AWalkThatDriftsAsAWholeTakesItsPlannedSteps) {
  // Each 0.2 m step lands 2 cm to the left of the planned step from its standing sole (the
  // controller has no global position): after ten steps the robot is 0.2 m off its plan in the
  // world, and every step and the walk pass.
  WalkJudge judge(limits());
  SupportSample s = standing(0);
  PlannedSupport plan = plan_of(s);
  for (int step = 0; step < 10; ++step) {
    const int swing = step % 2, stance = 1 - swing;
    s.t += kDt;  // lift-off
    plan.swinging[swing] = true;
    s.sole_contact[swing] = false;
    ASSERT_FALSE(judge.check(s, plan));
    s.t += kDt;  // touchdown
    plan.swinging[swing] = false;
    plan.sole[swing].x() += 0.2;
    s.sole_contact[swing] = true;
    s.sole[swing] = s.sole[stance] + (plan.sole[swing] - plan.sole[stance]) + Eigen::Vector2d(0, 0.02);
    ASSERT_FALSE(judge.check(s, plan)) << "step " << step;
    ASSERT_FALSE(judge.landing(s, swing, plan)) << "step " << step;
  }
  EXPECT_NEAR(s.sole[1].y() - plan.sole[1].y(), 0.2, 1e-12);
  EXPECT_FALSE(judge.at_end(s, plan));
}

TEST(WalkJudge, ARobotThrownUpIsAirborneOnceTheFlightOutlastsTheLimit) {
  // The pelvis rises 80 m (a vertical push): no fall criterion of a sinking or tilting pelvis
  // fires; the contact clock does, at the first period more than airborne_time after the last
  // contact (0.1 s = 12.5 periods: the 13th).
  WalkJudge judge(limits());
  SupportSample s = standing(1.0);
  ASSERT_FALSE(judge.check(s, plan_of(s)));
  const PlannedSupport plan = plan_of(s);
  s.sole_contact = {false, false};
  int periods = 0;
  std::optional<FallReason> r;
  while (!r && periods < 1000) {
    s.t += kDt;
    s.pelvis_height += 1.0;
    r = judge.check(s, plan);
    ++periods;
  }
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, FallReason::kAirborne);
  EXPECT_EQ(periods, 13);
  EXPECT_EQ(judge.at_end(s, plan), FallReason::kAirborne);  // a run ending in the air is not supported
}

TEST(WalkJudge, AShortLiftOffOfBothSolesIsNotAFlight) {
  // 0.08 s without contact (a hop within the limit), then down again: no outcome.
  WalkJudge judge(limits());
  SupportSample s = standing(0);
  const PlannedSupport plan = plan_of(s);
  for (int i = 0; i < 10; ++i) {
    s.t += kDt;
    s.sole_contact = {false, false};
    ASSERT_FALSE(judge.check(s, plan));
  }
  s.t += kDt;
  s.sole_contact = {true, true};
  EXPECT_FALSE(judge.check(s, plan));
}

TEST(WalkJudge, ASlidingRobotSlidesWhenItsSolesPassTheTolerance) {
  // Both soles slide sideways at 0.5 m/s, upright and in contact: slid once they are more than
  // 0.075 m from where they came down, i.e. after 0.15 s (18.75 periods: the 19th).
  WalkJudge judge(limits());
  SupportSample s = standing(0);
  const PlannedSupport plan = plan_of(s);
  ASSERT_FALSE(judge.check(s, plan));  // down here
  int periods = 0;
  std::optional<FallReason> r;
  while (!r && periods < 1000) {
    s.t += kDt;
    for (auto& p : s.sole) p.y() += 0.5 * kDt;
    r = judge.check(s, plan);
    ++periods;
  }
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, FallReason::kSlid);
  EXPECT_EQ(periods, 19);
  EXPECT_GT(judge.support_error_max(), kTolerance);
}

TEST(WalkJudge, ASwingingSoleAwayFromItsPlanIsNotSliding) {
  WalkJudge judge(limits());
  SupportSample s = standing(0);
  PlannedSupport plan = plan_of(s);
  plan.swinging[0] = true;
  s.sole_contact[0] = false;
  s.sole[0].x() += 0.3;  // mid-swing, far from the landing spot
  EXPECT_FALSE(judge.check(s, plan));
}

TEST(WalkJudge, APelvisTurnedUpsideDownIsFlippedAndATiltedOneTilted) {
  WalkJudge flipped(limits()), tilted(limits());
  SupportSample s = standing(0);
  const PlannedSupport plan = plan_of(s);
  s.pelvis_R = Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitX()).toRotationMatrix();  // R(2,2) = cos 2 < 0
  EXPECT_EQ(flipped.check(s, plan), FallReason::kFlipped);
  s.pelvis_R = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitY()).toRotationMatrix();  // pitch 0.7 > 0.6
  EXPECT_EQ(tilted.check(s, plan), FallReason::kPelvisTilted);
}

TEST(WalkJudge, AWalkEndsSupportedOnlyWithEverySoleItStandsOnDown) {
  WalkJudge judge(limits());
  SupportSample s = standing(10.0);
  PlannedSupport plan = plan_of(s);
  EXPECT_FALSE(judge.at_end(s, plan));
  s.sole_contact[0] = false;  // one sole lifted at the end (a push lifted the robot onto one foot)
  EXPECT_EQ(judge.at_end(s, plan), FallReason::kUnsupported);
  plan.swinging[0] = true;  // (a plan that ends mid-step: that sole may be up)
  EXPECT_FALSE(judge.at_end(s, plan));
  plan.swinging[0] = false;
  s.sole_contact[0] = true;
  s.sole_height[0] = 0.028;  // on the floor, but on an edge: its centre 2.8 cm up (limit 2.2 cm)
  EXPECT_EQ(judge.at_end(s, plan), FallReason::kUnsupported);
  s.sole_height[0] = 0.02;
  EXPECT_FALSE(judge.at_end(s, plan));
}

TEST(WalkJudge, AStepLandsOnlyOnTheFloorWithinTheToleranceOfItsPlannedStep) {
  // The left sole's step from the right one, against the plan's; the whole pair 1 m off the plan
  // in the world changes nothing.
  WalkJudge judge(limits());
  SupportSample s = standing(0);
  const PlannedSupport plan = plan_of(s);
  for (auto& p : s.sole) p += Eigen::Vector2d(1.0, -1.0);
  const Eigen::Vector2d landed = s.sole[0];
  EXPECT_FALSE(judge.landing(s, 0, plan));
  s.sole[0] = landed + Eigen::Vector2d(0.07, 0);  // inside 0.075
  EXPECT_FALSE(judge.landing(s, 0, plan));
  s.sole[0] = landed + Eigen::Vector2d(0.08, 0);  // outside
  EXPECT_EQ(judge.landing(s, 0, plan), FallReason::kMissedStep);
  s.sole[0] = landed;
  s.sole_contact[0] = false;  // where planned, but in the air
  EXPECT_EQ(judge.landing(s, 0, plan), FallReason::kMissedStep);
}

}  // namespace
}  // namespace flexgait::experiments
