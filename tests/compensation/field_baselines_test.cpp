// The field's baselines as control.compensation choices, against hand computations:
// ROBOTIS's stance hip roll feed-forward δ = ±0.017 sin(π s) (peak at mid single support, sign of
// the modelled sag, nothing in double support, nothing on other joints); TALOS's stance hip roll
// δ = sat(LP₁Hz(τ)/K, ±0.01) with the first-order filter's closed form y_n = τ (1 − (1 − g)ⁿ).
#include <gtest/gtest.h>

#include <cmath>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/walking/leg_kinematics.hpp"

namespace flexgait::compensation {
namespace {

using humanoid::JointVector;
using humanoid::kJoints;
using humanoid::kLeftHipRoll;
using humanoid::kRightHipRoll;
using walking::Matrix3d;
using walking::Pose;
using walking::Vector3d;

constexpr double kPeriod = 0.004;  // [s]

/// Standing on the left foot, the pelvis centre over its sole (the stance hip outboard of it: the
/// weight loads the hip roll), the right foot 5 cm up.
struct LeftStance {
  walking::RobotModel model = walking::make_robot_model(humanoid::RobotParams{});
  JointVector q{};
  SupportPlan plan;
  LeftStance() {
    const double y = model.leg[0].anchor[0].y();
    plan.soles = {Pose{Vector3d(0, y, 0), Matrix3d::Identity()}, Pose{Vector3d(0, -y, 0.05), Matrix3d::Identity()}};
    plan.swinging = {false, true};
    plan.zmp_ref = plan.soles[0].p.head<2>();
    for (int side = 0; side < 2; ++side) {
      const walking::IkSolution ik = walking::leg_inverse_kinematics(
          model.leg[side], Pose{plan.soles[side].p - Vector3d(0, y, 0.72), Matrix3d::Identity()});
      for (int i = 0; i < humanoid::kLegJoints; ++i) q[humanoid::leg_first_joint(side) + i] = ik.q[i];
    }
  }
};

CompensationParams params(CompensationMode mode) {
  CompensationParams p;
  p.mode = mode;
  return p;
}

TEST(FieldBaselines, RobotisFeedForwardIsOneDegreeAtMidSingleSupport) {
  LeftStance s;
  DeformationCompensator c(s.model, params(CompensationMode::kRobotis), kPeriod);
  const double sign = [&] {  // the sag's direction: the sign of the modelled stance hip roll torque
    DeformationCompensator model(s.model, params(CompensationMode::kInput), kPeriod);
    model.input(s.q, Matrix3d::Identity(), s.plan);
    return model.input_torque()[kLeftHipRoll] > 0 ? 1.0 : -1.0;
  }();
  for (const double phase : {0.0, 0.25, 0.5, 0.8, 1.0}) {
    s.plan.single_support_phase = phase;
    const JointVector cmd = c.input(s.q, Matrix3d::Identity(), s.plan);
    for (int j = 0; j < kJoints; ++j) {
      const double expected = j == kLeftHipRoll ? sign * 0.017 * std::sin(M_PI * phase) : 0.0;
      EXPECT_NEAR(cmd[j] - s.q[j], expected, 1e-15) << "joint " << j << " phase " << phase;
    }
  }
  s.plan.single_support_phase = 0.5;
  EXPECT_NEAR(std::abs(c.input(s.q, Matrix3d::Identity(), s.plan)[kLeftHipRoll] - s.q[kLeftHipRoll]), 0.017, 1e-15);
  // Double support: nothing.
  s.plan.swinging = {false, false};
  s.plan.single_support_phase = -1;
  const JointVector cmd = c.input(s.q, Matrix3d::Identity(), s.plan);
  for (int j = 0; j < kJoints; ++j) EXPECT_EQ(cmd[j], s.q[j]);
  // It reads the motor-side encoders: no output compensator.
  EXPECT_FALSE(params(CompensationMode::kRobotis).output());
}

TEST(FieldBaselines, TalosLowPassesTheStanceHipRollTorqueOverK) {
  LeftStance s;
  CompensationParams p = params(CompensationMode::kTalos);
  p.k_joint = 5000;  // large enough that 0.01 rad is not reached within the test
  DeformationCompensator c(s.model, p, kPeriod);
  DeformationCompensator model(s.model, params(CompensationMode::kInput), kPeriod);
  model.input(s.q, Matrix3d::Identity(), s.plan);
  const double tau = model.input_torque()[kLeftHipRoll];
  ASSERT_GT(std::abs(tau), 5.0);
  const double g = 1.0 - std::exp(-2.0 * M_PI * 1.0 * kPeriod);  // 1 Hz
  for (int n = 1; n <= 250; ++n) {
    const JointVector cmd = c.input(s.q, Matrix3d::Identity(), s.plan);
    const double expected = std::clamp(tau * (1.0 - std::pow(1.0 - g, n)) / 5000.0, -0.01, 0.01);
    ASSERT_NEAR(cmd[kLeftHipRoll] - s.q[kLeftHipRoll], expected, 1e-14) << n;
    ASSERT_EQ(cmd[kRightHipRoll], s.q[kRightHipRoll]);  // the swinging leg's input is 0
    for (int j = 0; j < kJoints; ++j)
      if (j != kLeftHipRoll && j != kRightHipRoll) {
        ASSERT_EQ(cmd[j], s.q[j]);
      }
  }
  // After 1 s (the filter's time constant is 1/(2π) s) at the belief k = 1000, τ/K exceeds 0.01: saturated.
  DeformationCompensator soft(s.model, params(CompensationMode::kTalos), kPeriod);
  JointVector cmd{};
  for (int n = 0; n < 250; ++n) cmd = soft.input(s.q, Matrix3d::Identity(), s.plan);
  ASSERT_GT(std::abs(tau) / 1000.0, 0.01);
  EXPECT_NEAR(std::abs(cmd[kLeftHipRoll] - s.q[kLeftHipRoll]), 0.01, 1e-15);
  EXPECT_FALSE(p.output());
}

}  // namespace
}  // namespace flexgait::compensation
