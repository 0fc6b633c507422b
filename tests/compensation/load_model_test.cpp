// control.load_model (issue 20): the measured load (ankle F/T wrenches, read by the output
// compensator) equals the thesis's weight split when the readings are what the split assumes — the robot standing still
// in double support, half the weight under each sole centre — exactly without noise and to the F/T noise with it; the
// output compensator then finds the same joint angles. The dynamic load adds exactly the Newton–Euler
// inertial torques of the planned motion (a constant joint acceleration, differentiated by the
// compensator), and at rest it is the measured load.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/walking/leg_kinematics.hpp"
#include "flexgait/walking/robot_model_dynamics.hpp"

#include "double_support_stance.hpp"

namespace flexgait::compensation {
namespace {

using humanoid::JointVector;
using humanoid::kJoints;
using walking::Matrix3d;
using walking::Pose;
using walking::Vector3d;

constexpr double kPeriod = 0.004;  // [s]

using fixtures::Stance;

CompensationParams params(LoadModel load) {
  CompensationParams p;
  p.mode = CompensationMode::kBoth;
  p.load_model = load;
  return p;
}

TEST(LoadModel, MeasuredEqualsTheWeightSplitStandingStillWithoutNoise) {
  const Stance s;
  DeformationCompensator gravity(s.model, params(LoadModel::kGravity), kPeriod);
  DeformationCompensator measured(s.model, params(LoadModel::kMeasured), kPeriod);
  measured.sense(s.readings());
  const JointVector a = gravity.input(s.q, Matrix3d::Identity(), s.plan());
  const JointVector ta = gravity.input_torque();
  const JointVector b = measured.input(s.q, Matrix3d::Identity(), s.plan());
  const JointVector tb = measured.input_torque();
  for (int j = 0; j < kJoints; ++j) {
    EXPECT_NEAR(tb[j], ta[j], 1e-9) << j;  // rounding on O(100) Nm
    EXPECT_NEAR(b[j], a[j], 1e-12) << j;
  }
  EXPECT_GT(std::abs(ta[humanoid::kLeftKnee]), 5.0);  // the comparison is not of zeros
  // The output compensator solves the same equation: the same joint angles.
  JointVector encoder = a;
  const OutputEstimate eg = gravity.output(encoder, Matrix3d::Identity(), s.plan());
  const OutputEstimate em = measured.output(encoder, Matrix3d::Identity(), s.plan());
  ASSERT_TRUE(eg.converged && em.converged);
  for (int j = 0; j < kJoints; ++j) EXPECT_NEAR(em.newton[j], eg.newton[j], 1e-11) << j;
}

TEST(LoadModel, MeasuredEqualsTheWeightSplitStandingStillToTheFtNoise) {
  // F/T noise σ_f = 0.5 N, σ_τ = 0.05 Nm per axis (an ATI Mini85-class sensor), white, through the
  // first-order low-pass (gain a = 1 − e^{−T/τ}): std σ √(a / (2 − a)). Each joint torque moves by
  // J_sᵀ Δw (J_s the leg's Jacobian at the sensor): its std is √(Σ J² σ²); the tolerance is 5 std.
  const double sf = 0.5, st = 0.05;
  const Stance s;
  CompensationParams p = params(LoadModel::kMeasured);
  DeformationCompensator gravity(s.model, params(LoadModel::kGravity), kPeriod);
  DeformationCompensator measured(s.model, p, kPeriod);
  const auto exact = s.readings();
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0, 1);
  for (int k = 0; k < 2000; ++k) {
    auto noisy = exact;
    for (auto& r : noisy)
      for (int i = 0; i < 3; ++i) r.force[i] += sf * n(rng), r.torque[i] += st * n(rng);
    measured.sense(noisy);
  }
  const double a = 1.0 - std::exp(-kPeriod / p.load_filter_time), filtered = std::sqrt(a / (2 - a));
  // The output side reads the F/T (the input side is a feed-forward of the plan's loads).
  const JointVector encoder = gravity.input(s.q, Matrix3d::Identity(), s.plan());
  const OutputEstimate eg = gravity.output(encoder, Matrix3d::Identity(), s.plan());
  const OutputEstimate em = measured.output(encoder, Matrix3d::Identity(), s.plan());
  ASSERT_TRUE(eg.converged && em.converged);
  walking::RobotModelData data;
  walking::forward_kinematics(s.model, data, Pose{Vector3d::Zero(), Matrix3d::Identity()}, s.q);
  for (int side = 0; side < 2; ++side) {
    const Vector3d sensor = data.frame[s.model.foot[side]].p;
    const walking::LegJacobian J = walking::leg_jacobian(s.model, data, side, sensor);
    for (int i = 0; i < humanoid::kLegJoints; ++i) {
      const int j = humanoid::leg_first_joint(side) + i;
      const double sd =
          filtered * std::sqrt(sf * sf * J.col(i).head<3>().squaredNorm() + st * st * J.col(i).tail<3>().squaredNorm());
      EXPECT_NEAR(em.gravity_torque[j], eg.gravity_torque[j], 5 * sd) << j;
      // θ̂ moves by (K + G)⁻¹ Δτ ≈ Δτ / k: 5 sd / k.
      EXPECT_NEAR(em.newton[j], eg.newton[j], 5 * sd / p.k_joint) << j;
    }
  }
}

TEST(LoadModel, DynamicAddsTheInertialTorquesOfThePlannedMotion) {
  const Stance s;
  DeformationCompensator measured(s.model, params(LoadModel::kMeasured), kPeriod);
  DeformationCompensator dynamic(s.model, params(LoadModel::kDynamic), kPeriod);
  SupportPlan plan = s.plan();
  plan.pelvis = Pose{Vector3d(0, 0, 0.72), Matrix3d::Identity()};
  walking::PlannedMotion& motion = plan.motion;
  for (int j = 0; j < kJoints; ++j) {
    motion.velocity[j] = 0.3 * std::cos(j + 1.0);      // [rad/s]
    motion.acceleration[j] = 0.5 * std::sin(j + 1.0);  // [rad/s²]
  }
  motion.pelvis.velocity = Vector3d(0.2, -0.1, 0.0);
  motion.pelvis.acceleration = Vector3d(0.4, -0.7, 0.1);
  motion.pelvis.angular_velocity = Vector3d(0, 0, 0.2);
  motion.pelvis.angular_acceleration = Vector3d(0, 0, -0.5);
  motion.valid = true;
  const auto ft = s.readings();
  dynamic.sense(ft);
  dynamic.input(s.q, Matrix3d::Identity(), plan);
  measured.sense(ft);
  measured.input(s.q, Matrix3d::Identity(), plan);
  // Expected: the Newton–Euler inertial part alone (no gravity, the feet's wrenches given).
  walking::RobotModelData data;
  walking::forward_kinematics(s.model, data, Pose{Vector3d::Zero(), Matrix3d::Identity()}, s.q);
  walking::FootWrenches nothing;
  nothing.given = {true, true};
  walking::RobotDynamicsData dyn;
  walking::inverse_dynamics(s.model, data, motion.pelvis, motion.velocity, motion.acceleration, dyn, nothing, 0.0);
  double largest = 0;
  for (int j = humanoid::kLeftHipYaw; j < kJoints; ++j) {
    // 1e-9 Nm: the two sums differ by their order only (torques O(10-100) Nm)
    EXPECT_NEAR(dynamic.input_torque()[j] - measured.input_torque()[j], dyn.tau[j], 1e-9) << j;
    largest = std::max(largest, std::abs(dyn.tau[j]));
  }
  EXPECT_GT(largest, 0.05);  // the inertial torques are not negligible here
}

TEST(LoadModel, DynamicAtRestIsMeasured) {
  const Stance s;
  DeformationCompensator measured(s.model, params(LoadModel::kMeasured), kPeriod);
  DeformationCompensator dynamic(s.model, params(LoadModel::kDynamic), kPeriod);
  SupportPlan plan = s.plan();
  plan.pelvis = Pose{Vector3d(0, 0, 0.72), Matrix3d::Identity()};
  for (int k = 0; k < 3; ++k) {
    dynamic.sense(s.readings());
    dynamic.input(s.q, Matrix3d::Identity(), plan);
  }
  measured.sense(s.readings());
  measured.input(s.q, Matrix3d::Identity(), plan);
  for (int j = 0; j < kJoints; ++j) EXPECT_EQ(dynamic.input_torque()[j], measured.input_torque()[j]) << j;
}

TEST(LoadModel, PlanHorizontalForceAddsMinusJacobianTransposeOfItsShareAtTheCentreOfPressure) {
  // control.plan_horizontal_force f: the input side's ground force on a stance foot gains
  // share · M · f · c̈_xy at the split's centre of pressure, so each joint's torque gains
  // −Jᵀ(cop) (share M f c̈_x, share M f c̈_y, 0) (eq. 4's virtual work) and nothing else; linear in f.
  // Left foot in single support, the reference ZMP off its centre, so the point is not the sole's.
  const Stance s;
  SupportPlan plan = s.plan();
  plan.swinging = {false, true};
  plan.zmp_ref = s.soles[0].p.head<2>() + Eigen::Vector2d(0.02, -0.01);
  plan.pelvis = Pose{Vector3d(0, 0, 0.72), Matrix3d::Identity()};
  plan.motion.com_acceleration = Vector3d(0.3, -0.6, 0.0);  // [m/s²]
  plan.motion.valid = true;
  JointVector torque[3];
  const double shares[3] = {0.0, 0.5, 1.0};
  for (int i = 0; i < 3; ++i) {
    CompensationParams p = params(LoadModel::kDynamic);
    p.plan_horizontal_force = shares[i];
    DeformationCompensator c(s.model, p, kPeriod);
    c.sense(s.readings());
    c.input(s.q, Matrix3d::Identity(), plan);
    torque[i] = c.input_torque();
  }
  walking::RobotModelData data;
  walking::forward_kinematics(s.model, data, Pose{Vector3d::Zero(), Matrix3d::Identity()}, s.q);
  const FootLoads loads =
      support_loads(plan.zmp_ref, plan.soles, plan.swinging, s.model.sole_length, s.model.sole_width);
  ASSERT_EQ(loads.share[0], 1.0);
  const Pose sole = walking::sole_pose(s.model, data, 0);
  const Vector3d cop = sole.p + sole.R * Vector3d(loads.cop[0].x(), loads.cop[0].y(), 0);
  ASSERT_GT((cop - sole.p).norm(), 0.01);
  const Vector3d force(s.model.total_mass * 0.3, s.model.total_mass * -0.6, 0.0);  // f = 1 [N]
  const walking::LegJacobian J = walking::leg_jacobian(s.model, data, 0, cop);
  const walking::LegTorque expected = -J.topRows<3>().transpose() * force;
  for (int i = 0; i < humanoid::kLegJoints; ++i) {
    const int j = humanoid::leg_first_joint(0) + i;
    // 1e-9 Nm: rounding of sums of O(100) Nm
    EXPECT_NEAR(torque[2][j] - torque[0][j], expected(i), 1e-9) << j;
    EXPECT_NEAR(torque[1][j] - torque[0][j], 0.5 * expected(i), 1e-9) << j;
    const int r = humanoid::leg_first_joint(1) + i;  // the swing leg carries no ground force
    EXPECT_EQ(torque[2][r], torque[0][r]) << r;
  }
  EXPECT_GT(std::abs(expected(1)), 10.0);  // the stance hip roll's share is not negligible
}

}  // namespace
}  // namespace flexgait::compensation
