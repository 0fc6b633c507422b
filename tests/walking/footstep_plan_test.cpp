// The footstep plan and its ZMP reference: geometry of the footprints (width kept, headings
// turned), a continuous ZMP reference at the stance sole in single support, the swing foot's path.
#include "flexgait/walking/footstep_plan.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "flexgait/walking/ground_slope.hpp"

namespace flexgait::walking {
namespace {

TEST(FootstepPlan, FootprintsKeepTheWidthAndTurn) {
  WalkParams w;
  w.steps = 6;
  w.step_length = 0.0;
  w.turn = 0.2;
  const WalkPlan plan = plan_footsteps(w);
  ASSERT_EQ(plan.steps.size(), 6u);
  EXPECT_EQ(plan.steps.front().swing, 0);  // turning left: the left foot leads
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    const Step& s = plan.steps[i];
    // The landed foot sits step_width beside the stance foot, across the new heading.
    EXPECT_NEAR(std::hypot(s.to.x - s.stance.x, s.to.y - s.stance.y), w.step_width, 1e-12);
    const double expected_heading = std::min<double>(static_cast<double>(i + 1), 5.0) * w.turn;
    EXPECT_NEAR(s.to.yaw, expected_heading, 1e-12);
  }
  EXPECT_NEAR(plan.final[0].yaw, plan.final[1].yaw, 1e-12);  // the last step closes the feet
}

TEST(FootstepPlan, ZmpReferenceIsContinuousAndOnTheStanceSole) {
  WalkParams w;
  w.steps = 5;
  const WalkPlan plan = plan_footsteps(w);
  const double dt = 1e-4;
  double worst_jump = 0;
  for (double t = 0; t < plan.duration; t += dt)
    worst_jump = std::max(worst_jump, (zmp_reference(plan, t + dt) - zmp_reference(plan, t)).norm());
  // The fastest transfer: from one sole centre to the next, hypot(width, length), in
  // dsp_ratio·step_time, with the quintic's peak slope 15/8.
  EXPECT_LT(worst_jump, 1.9 * std::hypot(w.step_width, w.step_length) / (w.dsp_ratio * w.step_time) * dt);
  for (const Step& s : plan.steps) {
    const Eigen::Vector2d mid_swing = zmp_reference(plan, 0.5 * (s.t_lift + s.t_land));
    EXPECT_NEAR(mid_swing.x(), s.stance.x, 1e-12);
    EXPECT_NEAR(mid_swing.y(), s.stance.y, 1e-12);
  }
}

TEST(FootstepPlan, SwingFootRisesToItsHeightAndLandsWhereplanned) {
  WalkParams w;
  w.steps = 3;
  const WalkPlan plan = plan_footsteps(w);
  const Step& s = plan.steps[1];
  const FeetTarget apex = feet_target(plan, w.swing_height, 0.5 * (s.t_lift + s.t_land));
  EXPECT_NEAR(apex.sole[s.swing].p.z(), w.swing_height, 1e-12);
  EXPECT_TRUE(apex.swinging[s.swing]);
  EXPECT_FALSE(apex.swinging[1 - s.swing]);
  const FeetTarget landed = feet_target(plan, w.swing_height, s.t_land);
  EXPECT_NEAR(landed.sole[s.swing].p.x(), s.to.x, 1e-12);
  EXPECT_NEAR(landed.sole[s.swing].p.y(), s.to.y, 1e-12);
  EXPECT_NEAR(landed.sole[s.swing].p.z(), 0.0, 1e-12);
}

TEST(FootstepPlan, ToldTheFloorTheSolesLieOnItsSlopeAndBlendBetweenSlopesInTheSwing) {
  // A 5° ramp down from x = 0.15 m: the footprints at x = 0.2, 0.3 get its height and gradient
  // (central differences of a linear function: exact to rounding, 1e-12), the one at 0.1 stays
  // level; the swing from level to slope passes through the blended gradient.
  WalkParams w;
  w.steps = 3;
  WalkPlan plan = plan_footsteps(w);
  const double g = -std::tan(0.0873), x0 = 0.15;
  set_footprint_heights(plan, [&](double x, double) { return x < x0 ? 0.0 : (x - x0) * g; });
  const Step& s = plan.steps[1];  // from x = 0 to 0.2, over the ramp's start
  EXPECT_NEAR(s.to.z, (s.to.x - x0) * g, 1e-12);
  EXPECT_NEAR(s.to.slope.x(), g, 1e-12);
  EXPECT_EQ(s.from.slope, Eigen::Vector2d::Zero());
  const FeetTarget landed = feet_target(plan, w.swing_height, s.t_land);
  EXPECT_NEAR(landed.sole[s.swing].R(2, 0), -std::sin(0.0873), 1e-12);  // toe down: R_y(α)
  const double t_mid = 0.5 * (s.t_lift + s.t_land);
  const FeetTarget mid = feet_target(plan, w.swing_height, t_mid);
  const double b = quintic_blend(0.5);
  EXPECT_NEAR(ground_gradient_of(mid.sole[s.swing].R).x(), b * g, 1e-12);
}

}  // namespace
}  // namespace flexgait::walking
