// The walking height and step width derived from a robot (issue 16): the builtin gets ROBOTIS's
// numbers exactly, and the rule is the stated one on a robot of other proportions.
#include "flexgait/walking/stance_defaults.hpp"
#include "flexgait/walking/walk_params.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flexgait::walking {
namespace {

TEST(StanceDefaults, BuiltinRobotGetsRobotisWalkingHeightAndHipWidth) {
  const RobotModel model = make_robot_model(humanoid::RobotParams{});
  const LegReach reach = leg_reach(model);
  // 0.093 m hip axes + 0.3 + 0.3 m legs + 0.1145 m ankle to sole; hips at ±0.093 m.
  EXPECT_NEAR(reach.stretched_height, 0.8075, 1e-12);
  EXPECT_NEAR(reach.length, 0.6, 1e-12);
  EXPECT_NEAR(reach.hip_spacing, 0.186, 1e-12);
  const StanceDefaults d = stance_defaults(model);
  EXPECT_EQ(d.pelvis_height, 0.723);  // the value typed as the default before (bit-equal: rounded to 1 mm)
  EXPECT_EQ(d.step_width, 0.186);
  EXPECT_EQ(d.pelvis_height, WalkParams{}.pelvis_height);
  EXPECT_EQ(d.step_width, WalkParams{}.step_width);
  // The knee angle this crouch means for equal thigh and shank: 2 acos(hip-to-ankle / (2 · 0.3)).
  EXPECT_NEAR(2 * std::acos(hip_to_ankle(reach, d.pelvis_height) / 0.6), 1.07431, 1e-5);
}

TEST(StanceDefaults, FollowsTheLegsOfAnotherRobot) {
  humanoid::RobotParams r;
  r.thigh = 0.25;
  r.shank = 0.35;
  r.ankle_to_sole = 0.08;
  r.hip_yaw_offset_y = 0.07;
  const RobotModel model = make_robot_model(r);
  const LegReach reach = leg_reach(model);
  const double stretched = r.hip_axes_depth + 0.6 + 0.08;
  EXPECT_NEAR(reach.stretched_height, stretched, 1e-12);
  const StanceDefaults d = stance_defaults(model);
  EXPECT_NEAR(d.pelvis_height, stretched - kCrouchShare * 0.6, 5e-4 + 1e-12);  // to the millimetre
  EXPECT_EQ(d.step_width, 0.14);
  EXPECT_NEAR(hip_to_ankle(reach, d.pelvis_height), d.pelvis_height - r.hip_axes_depth - 0.08, 1e-12);
}

}  // namespace
}  // namespace flexgait::walking
