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
  s.imu.accel = {0, 0, 9.81};                                 // level, at rest
  return s;
}

/// The readings fresh at time t (stamps of now).
const humanoid::SensorReadings& at(humanoid::SensorReadings& s, double t) {
  s.t = t;
  s.encoder_stamp.fill(t);
  for (auto& ft : s.ft) ft.stamp = t;
  s.imu.gyro_stamp = s.imu.accel_stamp = s.imu.quat_stamp = t;
  return s;
}

/// These synthetic readings are constant: not stuck.
HealthParams constant_readings() {
  HealthParams h;
  h.stuck_samples = 0;
  return h;
}

TEST(WalkingController, UpdateAllocatesNothing) {
  WalkParams w;
  w.steps = 4;
  humanoid::SensorReadings s = standing_sensors(250.0);
  for (const BalanceMode mode : {BalanceMode::kPd, BalanceMode::kDcm}) {
    BalanceParams balance;
    balance.mode = mode;
    WalkingController c(humanoid::RobotParams{}, w, balance, 0.004, EstimatorParams{}, constant_readings());
    const long before = g_allocations.load();
    for (int k = 0; k < static_cast<int>(c.plan().duration / 0.004); ++k) c.update(at(s, k * 0.004), k * 0.004);
    EXPECT_EQ(g_allocations.load() - before, 0) << name_of(mode);
    EXPECT_FALSE(c.safe_stop().active);
  }
  // A safe stop (the right F/T sensor stops sending at 3 s) allocates nothing either.
  WalkingController d(humanoid::RobotParams{}, w, BalanceParams{}, 0.004, EstimatorParams{}, constant_readings());
  const long before_stop = g_allocations.load();
  for (int k = 0; k < static_cast<int>(d.plan().duration / 0.004); ++k) {
    const double t = k * 0.004;
    at(s, t);
    if (t > 3.0) s.ft[1].stamp = 3.0;
    d.update(s, t);
  }
  EXPECT_EQ(g_allocations.load() - before_stop, 0);
  EXPECT_TRUE(d.safe_stop().active);
  EXPECT_EQ(d.safe_stop().sensor, humanoid::kFtRight);
}

TEST(WalkingController, CommandsRealiseThePlanThroughItsOwnKinematics) {
  WalkParams w;
  w.steps = 4;
  BalanceParams b;
  b.enabled = false;  // the plan itself, no sensor feedback
  WalkingController c(humanoid::RobotParams{}, w, b, 0.004, EstimatorParams{}, constant_readings());
  RobotModelData data;
  humanoid::SensorReadings s = standing_sensors(250.0);
  double worst_sole = 0, worst_com = 0;
  for (int k = 0; k < static_cast<int>(c.plan().duration / 0.004); ++k) {
    const humanoid::JointVector& q = c.update(at(s, k * 0.004), k * 0.004);
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
  EXPECT_FALSE(c.safe_stop().active);
  EXPECT_EQ(c.plan().steps.size(), 4U);
}

TEST(WalkingController, ASafeStopEndsThePlanAtTheNextDoubleSupport) {
  // The left F/T sensor stops sending at t_fail; once stale beyond the hold time the plan is cut:
  // mid-swing the step in flight completes; in double support the coming step is dropped. The
  // ZMP reference then blends to the middle of the feet where they stand, and stays there.
  WalkParams w;
  w.steps = 6;
  const HealthParams h = constant_readings();
  for (const double t_fail : {2.6, 3.2}) {  // swinging in step 1 / double support of step 2 at failure
    WalkingController c(humanoid::RobotParams{}, w, BalanceParams{}, 0.004, EstimatorParams{}, h);
    humanoid::SensorReadings s = standing_sensors(250.0);
    int stop_step = -2;
    for (int k = 0; k < static_cast<int>(c.plan().duration / 0.004); ++k) {
      const double t = k * 0.004;
      at(s, t);
      if (t > t_fail) s.ft[0].stamp = t_fail;
      c.update(s, t);
      if (c.safe_stop().active && stop_step == -2) stop_step = c.status().step;
    }
    ASSERT_TRUE(c.safe_stop().active) << t_fail;
    const double t_stop = c.safe_stop().t;
    EXPECT_GT(t_stop, t_fail + h.hold_time);  // stale after max_age, failed after hold_time more
    EXPECT_LT(t_stop, t_fail + h.max_age + h.hold_time + 0.01);
    const WalkPlan full = plan_footsteps(w);
    const auto& cut = c.plan();
    const bool swinging = t_stop + 0.004 >= full.steps[stop_step].t_lift;
    EXPECT_EQ(cut.steps.size(), static_cast<std::size_t>(stop_step + (swinging ? 1 : 0))) << t_fail;
    // Standing at the end: the ZMP reference at the middle of the final feet.
    const Eigen::Vector2d mid(0.5 * (cut.final[0].x + cut.final[1].x), 0.5 * (cut.final[0].y + cut.final[1].y));
    EXPECT_LT((c.status().zmp_ref - mid).norm(), 1e-12);
    EXPECT_EQ(c.status().sensor_flags & (1U << humanoid::kFtLeft), 1U << humanoid::kFtLeft);
  }
}

}  // namespace
}  // namespace flexgait::walking
