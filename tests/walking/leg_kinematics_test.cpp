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
      worst_pose =
          std::max({worst_pose, (back.p - target.p).cwiseAbs().maxCoeff(), (back.R - target.R).cwiseAbs().maxCoeff()});
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
  far.p = leg.hip + leg.sole_shift + Vector3d(0, 0, -(leg.thigh + leg.shank + leg.ankle_to_sole + 0.05));
  const IkSolution ik = leg_inverse_kinematics(leg, far);
  EXPECT_EQ(ik.status, IkStatus::kOutOfReach);
  EXPECT_NEAR(ik.clamped_by, 0.05, 1e-12);
  EXPECT_NEAR(ik.q[3], 0.0, 1e-7);  // straight knee
  const Pose reached = leg_forward_kinematics(leg, ik.q);
  EXPECT_NEAR((reached.p - far.p).norm(), 0.05, 1e-7);
}

// A leg of another layout: the hip pitch axis 20 mm ahead of the hip
// yaw and roll axes, 0.25 m thigh and shank, the sole 60 mm below the ankle.
LegGeometry offset_pitch_leg() {
  LegGeometry leg;
  leg.analytic = false;
  leg.axis = {Vector3d::UnitZ(), Vector3d::UnitX(), Vector3d::UnitY(),
              Vector3d::UnitY(), Vector3d::UnitY(), Vector3d::UnitX()};
  leg.anchor = {Vector3d(0, 0.075, -0.03), Vector3d(0, 0, -0.05), Vector3d(0.02, 0, 0),
                Vector3d(0, 0, -0.25),     Vector3d(0, 0, -0.25), Vector3d::Zero()};
  leg.sole = Vector3d(0, 0, -0.06);
  return leg;
}

// Numeric IK: FK∘IK = identity to 1e-10 over random reachable poses (the bound; Newton's
// last steps are undamped, so the residual ends near rounding, ~1e-16 m).
TEST(LegKinematics, NumericInverseOfForwardIsIdentity) {
  std::mt19937_64 rng(9);
  const LegGeometry leg = offset_pitch_leg();
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    const LegAngles q = random_angles(rng);
    const Pose target = leg_forward_kinematics(leg, q);
    const IkSolution ik = leg_inverse_kinematics(leg, target);
    ASSERT_EQ(ik.status, IkStatus::kOk) << i;
    const Pose back = leg_forward_kinematics(leg, ik.q);
    worst = std::max({worst, (back.p - target.p).cwiseAbs().maxCoeff(), (back.R - target.R).cwiseAbs().maxCoeff()});
  }
  EXPECT_LT(worst, 1e-10);
}

// On the analytic layout the numeric IK keeps the analytic solution it starts from (its Newton
// steps do not move it off: the same branch, knee > 0, to 1e-9 rad).
TEST(LegKinematics, NumericAgreesWithAnalyticOnTheBuiltinLeg) {
  std::mt19937_64 rng(13);
  LegGeometry analytic = leg_geometry(humanoid::RobotParams{}, 1);
  LegGeometry chain = analytic;
  chain.analytic = false;
  chain.axis = {Vector3d::UnitZ(), Vector3d::UnitX(), Vector3d::UnitY(),
                Vector3d::UnitY(), Vector3d::UnitY(), Vector3d::UnitX()};
  chain.anchor = {analytic.hip,
                  Vector3d::Zero(),
                  Vector3d::Zero(),
                  Vector3d(0, 0, -analytic.thigh),
                  Vector3d(0, 0, -analytic.shank),
                  Vector3d::Zero()};
  chain.sole = Vector3d(0, 0, -analytic.ankle_to_sole) + analytic.sole_shift;  // the sole 14 mm outward
  for (int i = 0; i < 500; ++i) {
    LegAngles q = random_angles(rng);
    const Pose target = leg_forward_kinematics(analytic, q);
    const IkSolution a = leg_inverse_kinematics(analytic, target), b = leg_inverse_kinematics(chain, target);
    ASSERT_EQ(b.status, IkStatus::kOk);
    const Pose pa = leg_forward_kinematics(chain, a.q);  // the chain's FK is the analytic one
    EXPECT_LT((pa.p - target.p).norm(), 1e-12);
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(a.q[j], b.q[j], 1e-9) << i << " joint " << j;
  }
}

TEST(LegKinematics, NumericOutOfReachIsFlagged) {
  const LegGeometry leg = offset_pitch_leg();
  Pose far;
  far.p = Vector3d(0.02, 0.075, -0.08 - 0.5 - 0.06 - 0.05);  // 50 mm below the straight leg's sole
  const IkSolution ik = leg_inverse_kinematics(leg, far);
  EXPECT_EQ(ik.status, IkStatus::kOutOfReach);
  // Damped least squares settles at the nearest reachable point: the straight leg, 50 mm short.
  EXPECT_NEAR(ik.clamped_by, 0.05, 1e-6);
}

}  // namespace
}  // namespace flexgait::walking
