// The walking height and step width derived from a robot: the builtin gets ROBOTIS's
// numbers exactly, and the rule is the stated one on a robot of other proportions.
#include "flexgait/walking/stance_defaults.hpp"
#include "flexgait/walking/walk_params.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string_view>

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

// The scaled defaults: the builtin against itself is scale 1 (its own values, bit-equal), and the
// rules are the stated powers (Froude: time as sqrt(leg), length as leg) to 3 significant digits.
TEST(ScaledDefaults, BuiltinIsItsOwnReferenceAndRulesAreThePowersStated) {
  const RobotModel model = make_robot_model(humanoid::RobotParams{});
  const double pelvis = stance_defaults(model).pelvis_height;
  const RobotScale one = robot_scale(model, pelvis, model, pelvis);
  EXPECT_EQ(one.mass, 1.0);
  EXPECT_EQ(one.leg, 1.0);
  EXPECT_EQ(one.com_height, 1.0);
  for (const ScaledDefault& d : kScaledDefaults) EXPECT_EQ(scaled_default(d, 0.723, one), 0.723) << d.key;
  const RobotScale four{2.0, 4.0, 9.0};
  const auto rule = [](std::string_view key) {
    for (const ScaledDefault& d : kScaledDefaults)
      if (d.key == key) return d;
    ADD_FAILURE() << key;
    return ScaledDefault{};
  };
  EXPECT_EQ(scaled_default(rule("walk.step_time"), 1.0, four), 2.0);      // sqrt(4)
  EXPECT_EQ(scaled_default(rule("walk.step_length"), 0.1, four), 0.4);    // 4
  EXPECT_EQ(scaled_default(rule("walk.preview_time"), 1.6, four), 4.8);   // sqrt(9)
  EXPECT_EQ(scaled_default(rule("plant.k_joint"), 1000, four), 8000);     // mass x leg
  EXPECT_EQ(scaled_default(rule("plant.gear_damping"), 80, four), 1280);  // mass x leg^1.5
  EXPECT_EQ(scaled_default(rule("balance.dcm_ki"), 10, four), 1.11);      // 10/9 to 3 digits
  // A robot of other proportions: the leg ratio is its thigh + shank over the builtin's 0.6 m.
  humanoid::RobotParams r;
  r.thigh = 0.15;
  r.shank = 0.15;
  const RobotModel half = make_robot_model(r);
  EXPECT_NEAR(robot_scale(half, stance_defaults(half).pelvis_height, model, pelvis).leg, 0.5, 1e-12);
}

// The physics step from the gears: the step as given while the fastest gear mode turns at most
// kMaxGearPhasePerStep (the builtin's 0.224 rad in 1 ms) per step, else halved until it does (0.6 rad per ms: a
// quarter of 1 ms, since half would turn 0.3 rad); the fastest mode is sqrt(k / I) over the mapped joints,
// unmapped ones ignored.
TEST(ScaledDefaults, PhysicsStepKeepsTheGearsPhasePerStep) {
  EXPECT_EQ(gear_physics_step(224, 0.001), 0.001);
  EXPECT_EQ(gear_physics_step(100, 0.001), 0.001);
  EXPECT_EQ(gear_physics_step(400, 0.001), 0.0005);
  EXPECT_EQ(gear_physics_step(600, 0.001), 0.00025);
  EXPECT_EQ(gear_physics_step(0, 0.001), 0.001);
  humanoid::LoadedRobot robot;
  robot.bodies.resize(2);
  for (int b = 0; b < 2; ++b) {
    humanoid::LoadedJoint j;
    j.link_inertia = b == 0 ? 0.25 : 0.01;
    robot.bodies[static_cast<std::size_t>(b)].joints.push_back(j);
  }
  robot.joint.fill({-1, -1});
  robot.joint[humanoid::kLeftKnee] = {0, 0};
  humanoid::JointVector k{};
  k.fill(100.0);
  EXPECT_EQ(fastest_gear_mode(robot, k), 20.0);  // sqrt(100 / 0.25); the 0.01 joint is not mapped
  robot.joint[humanoid::kRightKnee] = {1, 0};
  EXPECT_EQ(fastest_gear_mode(robot, k), 100.0);  // sqrt(100 / 0.01)
}

}  // namespace
}  // namespace flexgait::walking
