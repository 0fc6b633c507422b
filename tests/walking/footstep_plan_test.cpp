// The footstep plan and its ZMP reference: geometry of the footprints (width kept, headings
// turned), a continuous ZMP reference at the stance sole in single support, the swing foot's path.
#include "flexgait/walking/footstep_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

TEST(FootstepPlan, FeetMotionIsTheDerivativeOfTheFeetTarget) {
  // feet_motion against central differences of step e = 1e-5 s: of feet_target's positions (and of
  // its rotations, ω ≈ log(R(t + e) R(t − e)ᵀ) / 2e) for the rates, of feet_motion's own rates for
  // the accelerations. Truncation e²/6 of the third derivative (≲ 1e3 m/s³ or rad/s³ here: 1e-7)
  // and rounding 1e-16 / e of the positions (1e-11): agreement to 1e-6 of the largest value, on a
  // turning walk over a ramp (heights and slopes blend, the sole's attitude turns about two axes).
  WalkParams w;
  w.steps = 4;
  w.turn = 0.15;
  WalkPlan plan = plan_footsteps(w);
  set_footprint_heights(plan, [](double x, double y) { return 0.05 * x + 0.04 * x * x - 0.03 * y; });
  ASSERT_GT(plan.steps[2].to.slope.norm(), 0.03);
  const double e = 1e-5;
  int swinging = 0;
  for (const double t :
       {0.5 * (plan.steps[0].t_begin + plan.steps[0].t_lift), plan.steps[1].t_lift + 0.01,
        plan.steps[2].t_lift + 0.3 * (plan.steps[2].t_land - plan.steps[2].t_lift),
        plan.steps[2].t_lift + 0.7 * (plan.steps[2].t_land - plan.steps[2].t_lift), plan.steps[3].t_land - 0.02}) {
    const FeetTarget before = feet_target(plan, w.swing_height, t - e),
                     after = feet_target(plan, w.swing_height, t + e);
    const FeetMotion m = feet_motion(plan, w.swing_height, t), m0 = feet_motion(plan, w.swing_height, t - e),
                     m1 = feet_motion(plan, w.swing_height, t + e);
    for (int side = 0; side < 2; ++side) {
      const Vector3d v = (after.sole[side].p - before.sole[side].p) / (2 * e);
      const Vector3d omega = rotation_vector(after.sole[side].R * before.sole[side].R.transpose()) / (2 * e);
      const Vector3d a = (m1.velocity[side] - m0.velocity[side]) / (2 * e);
      const Vector3d alpha = (m1.angular_velocity[side] - m0.angular_velocity[side]) / (2 * e);
      const double scale = std::max({1.0, m.acceleration[side].norm(), m.angular_acceleration[side].norm()});
      EXPECT_LT((m.velocity[side] - v).norm(), 1e-6 * scale) << t << " side " << side;
      EXPECT_LT((m.angular_velocity[side] - omega).norm(), 1e-6 * scale) << t << " side " << side;
      EXPECT_LT((m.acceleration[side] - a).norm(), 1e-6 * scale) << t << " side " << side;
      EXPECT_LT((m.angular_acceleration[side] - alpha).norm(), 1e-6 * scale) << t << " side " << side;
      if (m.acceleration[side].norm() > 1.0 && m.angular_velocity[side].norm() > 0.05) ++swinging;
    }
    EXPECT_NEAR(m.floor_velocity, (after.floor_z - before.floor_z) / (2 * e), 1e-6) << t;
    EXPECT_NEAR(m.floor_acceleration, (m1.floor_velocity - m0.floor_velocity) / (2 * e), 1e-6) << t;
  }
  EXPECT_GE(swinging, 2);  // (the mid-swing instants move and turn)
}

}  // namespace
}  // namespace flexgait::walking
