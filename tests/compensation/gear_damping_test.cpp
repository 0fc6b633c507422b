// control.gear_damping: the Kelvin–Voigt gear, τ = k δ + d δ̇, makes the deflection the
// torque through a first-order lag of time constant d/k. Against the recursion's closed form on a
// step of the load (the weight moved from the middle of the feet onto the left sole), and the
// output compensator against encoders that carry exactly that lagged deflection.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "double_support_stance.hpp"

namespace flexgait::compensation {
namespace {

using fixtures::Stance;
using humanoid::JointVector;
using humanoid::kJoints;
using walking::Matrix3d;

constexpr double kPeriod = 0.004;  // [s]

CompensationParams params(double damping) {
  CompensationParams p;
  p.mode = CompensationMode::kBoth;
  p.gear_damping = damping;
  p.newton.tolerance = 1e-12;  // (the solve to rounding: the recovered angles are checked to 1e-10 below)
  return p;
}

/// The stance's plan with the reference ZMP at the left sole (all the weight on it) or between the soles.
SupportPlan plan(const Stance& s, bool on_left) {
  SupportPlan p = s.plan();
  if (on_left) p.zmp_ref = s.soles[0].p.head<2>();
  return p;
}

TEST(GearDamping, InputDeflectionFollowsTheFirstOrderLagOfTheTorque) {
  const Stance s;
  const double d = 80.0;
  DeformationCompensator lagged(s.model, params(d), kPeriod), statics(s.model, params(0.0), kPeriod);
  // The first period starts from the static deflection.
  const JointVector c0 = lagged.input(s.q, Matrix3d::Identity(), plan(s, false));
  const JointVector s0 = statics.input(s.q, Matrix3d::Identity(), plan(s, false));
  for (int j = 0; j < kJoints; ++j) EXPECT_NEAR(c0[j], s0[j], 1e-15) << j;
  const JointVector before = statics.input_torque();
  const JointVector after = statics.input(s.q, Matrix3d::Identity(), plan(s, true)), tau = statics.input_torque();
  (void)after;
  const double k = params(d).k_joint, a = kPeriod / (kPeriod + d / k);
  JointVector c{};
  for (int n = 1; n <= 50; ++n) {
    c = lagged.input(s.q, Matrix3d::Identity(), plan(s, true));
    for (int j = humanoid::kLeftHipYaw; j < kJoints; ++j) {
      // δ_n = τ/k + (1 − a)^n (τ_0 − τ)/k; e^{−nT/(d/k)} within O(a) of it.
      const double expected = tau[j] / k + std::pow(1 - a, n) * (before[j] - tau[j]) / k;
      EXPECT_NEAR(c[j] - s.q[j], expected, 1e-12) << "joint " << j << " period " << n;
    }
  }
  double step = 0;
  for (int j = 0; j < kJoints; ++j) step = std::max(step, std::abs(tau[j] - before[j]));
  EXPECT_GT(step, 10.0);  // a real step [Nm]
}

TEST(GearDamping, OutputRecoversTheLinkAnglesUnderTheLaggedDeflection) {
  const Stance s;
  const double d = 80.0;
  DeformationCompensator lagged(s.model, params(d), kPeriod), statics(s.model, params(0.0), kPeriod);
  const double k = params(d).k_joint, a = kPeriod / (kPeriod + d / k);
  // The link angles stay at the stance's; the deflection lags the load's step as the gear does.
  statics.torque(s.q, Matrix3d::Identity(), plan(s, false));
  const JointVector before = statics.torque(s.q, Matrix3d::Identity(), plan(s, false));
  const JointVector tau = statics.torque(s.q, Matrix3d::Identity(), plan(s, true));
  JointVector delta{}, encoder{};
  for (int j = 0; j < kJoints; ++j) delta[j] = before[j] / k;
  for (int n = 0; n <= 30; ++n) {
    const bool step = n > 0;
    if (step)
      for (int j = 0; j < kJoints; ++j) delta[j] = a * tau[j] / k + (1 - a) * delta[j];
    for (int j = 0; j < kJoints; ++j) encoder[j] = s.q[j] + delta[j];
    const OutputEstimate& e = lagged.output(encoder, Matrix3d::Identity(), plan(s, step));
    ASSERT_TRUE(e.converged) << n;
    // Newton's tolerance 1e-12 rad on the residual, times (k/a) / (k/a + G) ≤ 1.
    for (int j = humanoid::kLeftHipYaw; j < kJoints; ++j) EXPECT_NEAR(e.newton[j], s.q[j], 1e-10) << j << " " << n;
  }
  // The static model reads the same encoders as a different pose (mid-lag: by ~half the step's deflection).
  const OutputEstimate& wrong = statics.output(encoder, Matrix3d::Identity(), plan(s, true));
  double off = 0;
  for (int j = 0; j < kJoints; ++j) off = std::max(off, std::abs(wrong.newton[j] - s.q[j]));
  EXPECT_GT(off, 1e-3);
}

}  // namespace
}  // namespace flexgait::compensation
