// The walking controller alone (no simulator): update allocates nothing, its commands reproduce
// the plan through the controller's own kinematics, and the standing pose puts the COM between
// the feet.
#include "flexgait/walking/walking_controller.hpp"

#include <gtest/gtest.h>

#include "../support/count_allocations.hpp"

using flexgait::testing::g_allocations;

namespace flexgait::walking {
namespace {

humanoid::SensorReadings standing_sensors(double weight_per_foot) {
  humanoid::SensorReadings s;
  for (auto& ft : s.ft) ft.force = {0, 0, -weight_per_foot};  // the leg presses on the foot
  return s;
}

TEST(WalkingController, UpdateAllocatesNothing) {
  WalkParams w;
  w.steps = 4;
  WalkingController c(humanoid::RobotParams{}, w, BalanceParams{}, 0.004);
  const humanoid::SensorReadings s = standing_sensors(250.0);
  const long before = g_allocations.load();
  for (int k = 0; k < static_cast<int>(c.plan().duration / 0.004); ++k) c.update(s, k * 0.004);
  EXPECT_EQ(g_allocations.load() - before, 0);
}

TEST(WalkingController, CommandsRealiseThePlanThroughItsOwnKinematics) {
  WalkParams w;
  w.steps = 4;
  BalanceParams b;
  b.enabled = false;  // the plan itself, no sensor feedback
  WalkingController c(humanoid::RobotParams{}, w, b, 0.004);
  RobotModelData data;
  const humanoid::SensorReadings s = standing_sensors(250.0);
  double worst_sole = 0, worst_com = 0;
  for (int k = 0; k < static_cast<int>(c.plan().duration / 0.004); ++k) {
    const humanoid::JointVector& q = c.update(s, k * 0.004);
    const ControllerStatus& st = c.status();
    forward_kinematics(c.model(), data, st.pelvis, q);
    for (int side = 0; side < 2; ++side) {
      const Pose sole = sole_pose(c.model(), data, side);
      worst_sole = std::max({worst_sole, (sole.p - st.sole[side].p).norm(), (sole.R - st.sole[side].R).norm()});
    }
    worst_com = std::max(worst_com, (center_of_mass(c.model(), data).head<2>() - st.com_ref).norm());
  }
  EXPECT_LT(worst_sole, 1e-12);  // the IK is exact (FK∘IK)
  // The pelvis is found by two fixed-point iterations per period on the COM, which contract by
  // the legs' share of the mass: sub-millimetre (measured ~1e-4 m).
  EXPECT_LT(worst_com, 1e-3);
}

}  // namespace
}  // namespace flexgait::walking
