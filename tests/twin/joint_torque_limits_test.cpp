// Each joint's servo torque limit from the robot file (docs/guide/robot.md, "Torque limits"): while
// plant.torque_limit is derived, a joint the file's actuators limit keeps its own limit (gear ×
// forcerange) and the others take plant.torque_limit as derived; set by the user, it holds every joint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "../walking/model_agreement.hpp"
#include "flexgait/experiments/walk_experiment.hpp"

namespace flexgait::twin {
namespace {

/// unequal_actuators.xml's motors (gear 2 × forcerange), per leg from the hip yaw to the ankle roll [Nm].
constexpr std::array<double, humanoid::kLegJoints> kFileLimit = {60, 120, 120, 120, 12, 8};

TEST(PlantTorqueLimits, EachJointKeepsTheFilesLimitWhileDerived) {
  const experiments::WalkRunParams p = humanoid::testing::fixture_walk("unequal_actuators.yaml");
  EXPECT_EQ(p.plant.torque_limit, 120.0);  // the leg's largest (stance_defaults.hpp's rule)
  EXPECT_EQ(p.balance.capture_torque_limit, 120.0);
  const humanoid::JointVector limit = p.plant.servo_torque_limits();
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < humanoid::kLegJoints; ++i)
      EXPECT_EQ(limit[humanoid::leg_first_joint(side) + i], kFileLimit[static_cast<std::size_t>(i)]) << side << i;
  EXPECT_EQ(limit[humanoid::kWaistYaw], 120.0);  // no motor on the waist: plant.torque_limit as derived
  // The capture step's torque check holds each leg joint to the same limits (0: balance.capture_torque_limit).
  for (int j = 0; j < humanoid::kJoints; ++j)
    EXPECT_EQ(p.balance.capture_joint_torque_limit[j] > 0 ? p.balance.capture_joint_torque_limit[j]
                                                          : p.balance.capture_torque_limit,
              limit[j])
        << j;
  // The run's config.yaml keeps both keys auto (set, one value would hold every joint on a rerun).
  const char* dir = std::getenv("FLEXGAIT_TEST_DATA");
  const Config c =
      resolve_config(experiments::walk_run_schema(),
                     std::filesystem::path(dir ? dir : "tests/humanoid/data") / "unequal_actuators.yaml", {});
  const Config written = experiments::with_derived_values(c, experiments::walk_run_from_config(c));
  EXPECT_TRUE(written.derived("plant.torque_limit"));
  EXPECT_TRUE(written.derived("balance.capture_torque_limit"));
}

TEST(PlantTorqueLimits, AUserSetLimitHoldsEveryJoint) {
  const experiments::WalkRunParams p =
      humanoid::testing::fixture_walk("unequal_actuators.yaml", {"plant.torque_limit=70"});
  for (const double limit : p.plant.servo_torque_limits()) EXPECT_EQ(limit, 70.0);
  EXPECT_EQ(p.balance.capture_torque_limit, 70.0);
  for (const double limit : p.balance.capture_joint_torque_limit) EXPECT_EQ(limit, 0.0);  // 70 for every joint
}

// The twin's ground truth over a walk's start and first step: no servo torque beyond its own joint's
// limit (the servo's clamp is exact, so no tolerance), and the weak ankles' limits are reached (so a
// twin that held every joint at plant.torque_limit, 120 Nm, would fail here).
TEST(PlantTorqueLimits, NoServoTorqueExceedsItsJointsLimit) {
  experiments::WalkRunParams p = humanoid::testing::fixture_walk("unequal_actuators.yaml", {"walk.steps=2"});
  const humanoid::JointVector limit = p.plant.servo_torque_limits();
  experiments::WalkLoop w = experiments::make_walk_loop(p);
  const double end = w.control->controller().plan().steps.front().t_land + 0.2;
  humanoid::JointVector peak{};
  while (w.loop->time() < end && !w.loop->step()) {
    const GroundTruth& truth = w.loop->truth();
    for (int j = 0; j < humanoid::kJoints; ++j) peak[j] = std::max(peak[j], std::abs(truth.servo_torque[j]));
  }
  bool ankle_at_limit = false;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    EXPECT_LE(peak[j], limit[j]) << humanoid::kJointNames[j];
    if (limit[j] < p.plant.torque_limit && peak[j] == limit[j]) ankle_at_limit = true;
  }
  EXPECT_TRUE(ankle_at_limit);
}

}  // namespace
}  // namespace flexgait::twin
