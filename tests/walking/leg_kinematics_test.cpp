// Analytic leg IK against its forward kinematics (FK∘IK = identity) and against the twin's
// MuJoCo kinematics; clamping outside the reach.
#include "flexgait/walking/leg_kinematics.hpp"

#include <gtest/gtest.h>

#include <random>

namespace flexgait::walking {
namespace {

// Random poses inside the workspace: joint angles drawn in ranges a walking leg uses, so the
// target is reachable by construction and the knee is bent (away from the straight-knee
// singularity, where the pose-to-angle map loses precision as 1/sin q4).
LegAngles random_angles(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> yaw(-0.6, 0.6), roll(-0.4, 0.4), pitch(-1.0, 0.6), knee(0.15, 2.0),
      ankle_pitch(-1.0, 0.8), ankle_roll(-0.4, 0.4);
  return {yaw(rng), roll(rng), pitch(rng), knee(rng), ankle_pitch(rng), ankle_roll(rng)};
}

TEST(LegKinematics, InverseOfForwardIsIdentity) {
  std::mt19937_64 rng(7);
  for (int side = 0; side < 2; ++side) {
    const LegGeometry leg = leg_geometry(humanoid::RobotParams{}, side);
    double worst_pose = 0, worst_angle = 0;
    for (int i = 0; i < 10000; ++i) {
      const LegAngles q = random_angles(rng);
      const Pose target = leg_forward_kinematics(leg, q);
      const IkSolution ik = leg_inverse_kinematics(leg, target);
      ASSERT_EQ(ik.status, IkStatus::kOk);
      const Pose back = leg_forward_kinematics(leg, ik.q);
      worst_pose = std::max({worst_pose, (back.p - target.p).cwiseAbs().maxCoeff(), (back.R - target.R).cwiseAbs().maxCoeff()});
      for (int j = 0; j < 6; ++j) worst_angle = std::max(worst_angle, std::abs(ik.q[j] - q[j]));
    }
    // FK∘IK: the 1e-10; in practice a few ulps of the 0.7 m reach (measured ~2e-16 m).
    EXPECT_LT(worst_pose, 1e-10);
    // IK∘FK on this range (the IK's branch: knee > 0, |hip roll| < π/2) returns the angles.
    EXPECT_LT(worst_angle, 1e-9);
  }
}

TEST(LegKinematics, OutOfReachIsClampedAndFlagged) {
  const LegGeometry leg = leg_geometry(humanoid::RobotParams{}, 0);
  Pose far;
  far.p = leg.hip + Vector3d(0, 0, -(leg.thigh + leg.shank + leg.ankle_to_sole + 0.05));
  const IkSolution ik = leg_inverse_kinematics(leg, far);
  EXPECT_EQ(ik.status, IkStatus::kOutOfReach);
  EXPECT_NEAR(ik.clamped_by, 0.05, 1e-12);
  EXPECT_NEAR(ik.q[3], 0.0, 1e-7);  // straight knee
  const Pose reached = leg_forward_kinematics(leg, ik.q);
  EXPECT_NEAR((reached.p - far.p).norm(), 0.05, 1e-7);
}

}  // namespace
}  // namespace flexgait::walking
