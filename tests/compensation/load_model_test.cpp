// control.load_model: the measured load (ankle F/T wrenches, read by the output
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

// A failed F/T sensor reads NaN: the output compensator takes that foot's load from the plan's split (the gravity
// form) and the filter keeps its state, so a NaN neither reaches the estimate nor outlives the fault.
TEST(LoadModel, ANonFiniteFtReadingFallsBackToThePlansSplitAndDoesNotLinger) {
  const Stance s;
  DeformationCompensator gravity(s.model, params(LoadModel::kGravity), kPeriod);
  DeformationCompensator failed(s.model, params(LoadModel::kMeasured), kPeriod);
  auto nan = s.readings();
  nan[0].force[2] = std::nan("");
  failed.sense(s.readings());
  failed.sense(nan);
  const JointVector encoder = gravity.input(s.q, Matrix3d::Identity(), s.plan());
  const OutputEstimate eg = gravity.output(encoder, Matrix3d::Identity(), s.plan());
  const OutputEstimate ef = failed.output(encoder, Matrix3d::Identity(), s.plan());
  ASSERT_TRUE(eg.converged);
  ASSERT_TRUE(ef.converged);
  // The left foot's split load and the right foot's reading are both half the weight at the sole centre here.
  for (int j = 0; j < kJoints; ++j) EXPECT_NEAR(ef.newton[j], eg.newton[j], 1e-11) << j;
  DeformationCompensator recovered(s.model, params(LoadModel::kMeasured), kPeriod);
  recovered.sense(s.readings());
  failed.sense(s.readings());  // the sensor back: the same state as a filter that never saw the NaN
  const OutputEstimate er = recovered.output(encoder, Matrix3d::Identity(), s.plan());
  const OutputEstimate ea = failed.output(encoder, Matrix3d::Identity(), s.plan());
  for (int j = 0; j < kJoints; ++j) EXPECT_EQ(ea.newton[j], er.newton[j]) << j;
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

TEST(LoadModel, PlanGroundWrenchClosesTheWholeBodysNewtonEuler) {
  // control.plan_horizontal_force f > 0: the input side's ground wrench is the plan's own — the whole body's
  // Newton–Euler of the planned motion with no foot loaded gives the wrench W = (f₀, n₀) the world must supply at the
  // pelvis. In single support (its centre of pressure inside the stance sole) all of W goes through the stance foot,
  // so each stance joint i carries the body above it: τ_i = u_i · (n_i − n_W(p_i)), with (f_i, n_i) the free
  // recursion's wrench of the subtree below joint i and n_W(p_i) = n₀ + (p₀ − p_i) × f₀ (Featherstone 2008, §5.3).
  // The swing leg is its own Newton–Euler. The pelvis accelerates towards the right so that the plan's centre of
  // pressure, p = c − (z_c/g) c̈ for a point mass, lies under the left sole.
  const Stance s;
  SupportPlan plan = s.plan();
  plan.swinging = {false, true};
  plan.pelvis = Pose{Vector3d(0, 0, 0.72), Matrix3d::Identity()};
  plan.motion.valid = true;
  plan.motion.pelvis.acceleration = Vector3d(0.2, -1.25, 0.3);         // [m/s²]
  plan.motion.pelvis.angular_velocity = Vector3d(0.05, -0.1, 0.02);    // [rad/s]
  plan.motion.pelvis.angular_acceleration = Vector3d(0.3, 0.2, -0.1);  // [rad/s²]
  for (int j = 0; j < kJoints; ++j) {
    plan.motion.velocity[j] = 0.1 * std::sin(j + 1.0);      // [rad/s]
    plan.motion.acceleration[j] = 0.5 * std::cos(2.0 * j);  // [rad/s²]
  }
  CompensationParams p = params(LoadModel::kDynamic);
  p.plan_horizontal_force = 1.0;
  DeformationCompensator c(s.model, p, kPeriod);
  c.sense(s.readings());
  c.input(s.q, Matrix3d::Identity(), plan);
  const JointVector& tau = c.input_torque();

  walking::RobotModelData data;
  walking::forward_kinematics(s.model, data, Pose{Vector3d::Zero(), Matrix3d::Identity()}, s.q);
  walking::RobotDynamicsData free;
  walking::inverse_dynamics(s.model, data, plan.motion.pelvis, plan.motion.velocity, plan.motion.acceleration, free);
  const Vector3d f0 = free.joint_wrench[0].force, n0 = free.joint_wrench[0].moment, p0 = data.frame[0].p;
  // The centre of pressure lies inside the left sole (else the split would clamp it and the identity not hold).
  const Pose sole = walking::sole_pose(s.model, data, 0);
  const Vector3d n = n0 + p0.cross(f0);
  const Vector3d cop((sole.p.z() * f0.x() - n.y()) / f0.z(), (n.x() + sole.p.z() * f0.y()) / f0.z(), sole.p.z());
  const Vector3d local = sole.R.transpose() * (cop - sole.p);
  ASSERT_LT(std::abs(local.x()), 0.4 * s.model.sole_length);
  ASSERT_LT(std::abs(local.y()), 0.4 * s.model.sole_width);
  for (int b = 0; b < walking::kBodies; ++b) {
    const auto& body = s.model.bodies[static_cast<std::size_t>(b)];
    if (body.joint < 0 || body.joint == humanoid::kWaistYaw) continue;
    const bool left = body.joint >= humanoid::leg_first_joint(0) && body.joint < humanoid::leg_first_joint(0) + 6;
    const bool right = body.joint >= humanoid::leg_first_joint(1) && body.joint < humanoid::leg_first_joint(1) + 6;
    if (!left && !right) continue;
    const Vector3d u = data.frame[b].R * body.axis;
    const Vector3d ground = left ? Vector3d(n0 + (p0 - data.frame[b].p).cross(f0)) : Vector3d::Zero();
    const Vector3d carried = free.joint_wrench[b].moment - ground;
    // 1e-9 Nm: the same sums in another order (torques O(10-100) Nm)
    EXPECT_NEAR(tau[body.joint], u.dot(carried), 1e-9) << body.joint;
  }
  EXPECT_GT(std::abs(tau[humanoid::kLeftHipRoll]), 10.0);  // the stance hip roll carries the body above it
}

}  // namespace
}  // namespace flexgait::compensation
