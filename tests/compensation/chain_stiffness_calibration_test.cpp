// control.k_estimation = calibrate: the two flat soles' relative tilt through the encoders.
// The information form of least squares equals the covariance-form RLS without forgetting (the same posterior).
// The regressor is the exact derivative of the relative tilt (central differences, with SO(3)'s inverse left
// Jacobian: without it the columns would be off by ≈ |φ|/2 = 3 % at this pose); fed a stance whose encoders read
// θ_link + τ/k with every joint's own k (±20 %) and each joint's torque on its own, the calibration finds each
// leg roll and pitch joint's k and the floor's relative tilt under the soles; the compensators keep the belief until
// the window ends; with Kelvin–Voigt gears the regressor's lag runs on through samples it does not use; bad data,
// a swinging foot and times outside the window give no sample; adversarial data stays
// bounded and positive.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "flexgait/compensation/chain_stiffness_calibration.hpp"
#include "flexgait/compensation/forgetting_rls.hpp"
#include "flexgait/walking/rotation.hpp"

#include "double_support_stance.hpp"

namespace flexgait::compensation {
namespace {

using fixtures::readings;
using fixtures::Stance;
using humanoid::JointVector;
using humanoid::kJoints;
using walking::Matrix3d;
using walking::Vector3d;

using fixtures::kBelief;

CompensationParams calibration_params() {
  return fixtures::identification_params(KEstimation::kCalibrate);
}

/// The true stiffness: 1250 Nm/rad × 1.2 (hip roll, knee) or × 0.8 (hip pitch, ankle pitch, ankle roll) on the
/// left, the other way round on the right.
JointVector true_stiffness() {
  JointVector k;
  k.fill(1250.0);
  for (int side = 0; side < 2; ++side) {
    const int f = humanoid::leg_first_joint(side);
    const double up = side == 0 ? 1.2 : 0.8, down = 2.0 - up;
    k[f + 1] *= up, k[f + 3] *= up;                        // hip roll, knee
    k[f + 2] *= down, k[f + 4] *= down, k[f + 5] *= down;  // hip pitch, ankle pitch, ankle roll
  }
  return k;
}

TEST(InformationLeastSquares, EqualsTheRlsWithoutForgettingAndHoldsAParameterWithNoPriorVariance) {
  using Fit = InformationLeastSquares<4>;
  Fit::Vector x0(1e-3, 2e-3, 0.5, 0.0), prior(1e-6, 4e-6, 0.01, 0.0);  // (the last: held at 0)
  ForgettingRls<4> rls(x0, ForgettingRls<4>::Matrix(prior.asDiagonal()), 1.0);
  Fit fit(x0, prior);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    const Fit::Vector h(40 * u(rng), 40 * u(rng), u(rng), u(rng));
    const double y = h.dot(Fit::Vector(8e-4, 1.5e-3, 0.45, 0.0)) + 1e-4 * u(rng);
    ASSERT_TRUE(rls.update(h, y, 1e-8));
    ASSERT_TRUE(fit.add(h, y, 1e-8));
  }
  fit.solve();
  // Both are the posterior; they differ by round-off only (the RLS's subtractions: ≈ 1e-12 relative here, where
  // the scales are mild).
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(fit.x()[i], rls.x()[i], 1e-9 * std::abs(rls.x()[i])) << i;
    EXPECT_NEAR(fit.variance(i), rls.P()(i, i), 1e-6 * rls.P()(i, i)) << i;
  }
  EXPECT_EQ(fit.x()[3], 0.0);
  EXPECT_EQ(fit.variance(3), 0.0);
  EXPECT_FALSE(fit.add(Fit::Vector(NAN, 0, 0, 0), 0.0, 1e-8));
}

TEST(ChainStiffnessCalibration, TheRegressorIsTheRelativeTiltsDerivative) {
  const Stance s;
  ChainStiffnessCalibration c(s.model, calibration_params(), 0.004, 0.0, 1.0);
  // A pose 0.02–0.05 rad off the stance: the soles' relative rotation φ is ≈ 0.06 rad.
  JointVector q = s.q, tau{};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.05, 0.05), t(-40.0, 40.0);
  for (int j = 0; j < kJoints; ++j) q[j] += u(rng), tau[j] = t(rng);
  // (no torque on the yaw joints: y then is the relative tilt itself, without their deflections by the belief)
  tau[humanoid::kLeftHipYaw] = tau[humanoid::kRightHipYaw] = 0;
  Eigen::Vector2d y;
  const auto H = c.regressor(q, tau, y);
  double phi = 0;
  {
    walking::RobotModelData d;
    walking::forward_kinematics(s.model, d, walking::Pose{Vector3d::Zero(), Matrix3d::Identity()}, q);
    phi =
        walking::rotation_vector(walking::sole_pose(s.model, d, 0).R.transpose() * walking::sole_pose(s.model, d, 1).R)
            .norm();
  }
  EXPECT_GT(phi, 0.03);
  int checked = 0;
  for (int j = 0; j < kJoints; ++j) {
    if (!c.identified(j)) continue;
    const double h = 1e-6;
    JointVector plus = q, minus = q;
    plus[j] += h, minus[j] -= h;
    Eigen::Vector2d y_plus, y_minus;
    c.regressor(plus, tau, y_plus);
    c.regressor(minus, tau, y_minus);
    const Eigen::Vector2d fd = (y_plus - y_minus) / (2 * h) * tau[j];
    int n = 0;  // (the joint's state: the identified joints in order)
    for (int i = 0; i < j; ++i) n += c.identified(i) ? 1 : 0;
    // Central differences: O(h²) truncation, ≈ 1e-10/h round-off: 1e-7 relative is ample.
    EXPECT_LT((H.col(n) - fd).norm(), 1e-7 * fd.norm() + 1e-12) << humanoid::kJointNames[j];
    ++checked;
  }
  EXPECT_EQ(checked, 10);
  EXPECT_EQ(H.rightCols<2>(), (Eigen::Matrix2d::Identity()));
}

/// n periods of the stance with each joint's torque drawn on its own in [−20, 20] Nm, the encoders θ_link + τ/k.
void feed(ChainStiffnessCalibration& c, const Stance& s, const JointVector& q_link, const JointVector& k, int n,
          double t0) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> torque(-20.0, 20.0);
  JointVector tau{}, encoder{};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < kJoints; ++j) {
      tau[j] = torque(rng);
      encoder[j] = q_link[j] + tau[j] / k[j];
    }
    const double t = t0 + i * 0.004;
    c.update(t, encoder, tau, readings(s, t), s.plan(), true);
  }
}

TEST(ChainStiffnessCalibration, FindsEachJointAndTheFloorsTiltWhenEachJointsTorqueMovesOnItsOwn) {
  const Stance s;
  // The right sole on a floor 0.01 rad rolled and 0.005 rad pitched against the left's: the right leg's link
  // angles by inverse kinematics to that sole.
  JointVector q = s.q;
  walking::RobotModelData d;
  walking::forward_kinematics(s.model, d, walking::Pose{Vector3d::Zero(), Matrix3d::Identity()}, q);
  const walking::Pose right = walking::sole_pose(s.model, d, 1);
  const Matrix3d tilt = walking::rot_x(0.01) * walking::rot_y(0.005);
  const walking::IkSolution ik =
      walking::leg_inverse_kinematics(s.model.leg[1], walking::Pose{right.p, right.R * tilt});
  for (int i = 0; i < humanoid::kLegJoints; ++i) q[humanoid::leg_first_joint(1) + i] = ik.q[i];
  walking::forward_kinematics(s.model, d, walking::Pose{Vector3d::Zero(), Matrix3d::Identity()}, q);
  const Vector3d y0 =
      walking::rotation_vector(walking::sole_pose(s.model, d, 0).R.transpose() * walking::sole_pose(s.model, d, 1).R);
  ASSERT_NEAR(y0.x(), 0.01, 1e-3) << "the inverse kinematics put the right sole on its tilted floor";

  const JointVector k = true_stiffness();
  ChainStiffnessCalibration c(s.model, calibration_params(), 0.004, 0.0, 4.0);
  feed(c, s, q, k, 1000, 0.0);
  EXPECT_EQ(c.samples(), 1000);
  for (int j = 0; j < kJoints; ++j) {
    if (!c.identified(j)) {
      EXPECT_EQ(c.estimate()[j], kBelief) << humanoid::kJointNames[j];  // the yaw joints and the waist
      continue;
    }
    // Linear in the deflections (|τ/k| ≤ 0.02 rad): the second-order terms are ≈ 1 % of them.
    EXPECT_NEAR(c.estimate()[j], k[j], 0.01 * k[j]) << humanoid::kJointNames[j];
    EXPECT_EQ(c.stiffness()[j], kBelief) << "the belief until the calibration ends";
    EXPECT_LT(c.relative_std(j), 0.01);
  }
  // After the window: no more samples, the compensators take the estimates.
  feed(c, s, q, k, 10, 4.1);
  EXPECT_EQ(c.samples(), 1000);
  for (int j = 0; j < kJoints; ++j) EXPECT_EQ(c.stiffness()[j], c.estimate()[j]) << humanoid::kJointNames[j];
}

/// Kelvin–Voigt gears (k δ + d δ̇ = τ) in the stance: each deflection is the torque over k through the
/// backward-Euler first-order lag lag[j] (the calibration's own filter), from the first torque on.
struct LaggedGears {
  JointVector lagged{};
  bool started = false;
  /// The encoders θ_link + lagged τ / k after one period with torque tau.
  JointVector encoder(const JointVector& q_link, const JointVector& tau, const JointVector& k, const JointVector& lag,
                      double period) {
    JointVector e;
    for (int j = 0; j < kJoints; ++j) {
      lagged[j] += (started ? period / (period + lag[j]) : 1.0) * (tau[j] - lagged[j]);
      e[j] = q_link[j] + lagged[j] / k[j];
    }
    started = true;
    return e;
  }
};

// Kelvin–Voigt gears (control.gear_damping d, k δ + d δ̇ = τ): the deflection is the torque over k through a
// first-order lag of d/k. With d = 20 Nm s/rad and the belief's k, the lag is 0.02 s, five periods; the stance's
// deflections are made by the same backward-Euler lag the calibration applies to its regressor. Every third
// period the left foot is barely loaded, so that sample is not used, but the time still passes: the lag must
// run on, or the regressor's torque would be that of the wrong instant. Each joint within 1 % (the stance's
// second-order terms, as above).
TEST(ChainStiffnessCalibration, TheGearsLagRunsOnThroughUnusedSamples) {
  const Stance s;
  CompensationParams p = calibration_params();
  p.gear_damping = 20.0;
  p.load_filter_time = 0.0;
  const double period = 0.004;
  JointVector lag;
  lag.fill(p.gear_damping / kBelief);
  ChainStiffnessCalibration c(s.model, p, period, 0.0, 10.0);
  const JointVector k = true_stiffness();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> torque(-20.0, 20.0);
  LaggedGears gears;
  JointVector tau{};
  for (int i = 0; i < 2000; ++i) {
    for (int j = 0; j < kJoints; ++j) tau[j] = torque(rng);
    const JointVector encoder = gears.encoder(s.q, tau, k, lag, period);
    const double t = i * period;
    std::array<humanoid::ForceTorque, 2> ft = readings(s, t);
    if (i % 3 == 2)
      for (int a = 0; a < 3; ++a) ft[0].force[a] *= 0.04, ft[0].torque[a] *= 0.04;
    c.update(t, encoder, tau, ft, s.plan(), true);
  }
  EXPECT_EQ(c.samples(), 1334);
  for (int j = 0; j < kJoints; ++j) {
    if (!c.identified(j)) continue;
    EXPECT_NEAR(c.estimate()[j], k[j], 0.01 * k[j]) << humanoid::kJointNames[j];
  }
}

// The soles tilt in their contacts (control.sole_stiffness_*) against the ground's torque about each sole's centre,
// which the F/T sensors read: in the stance below each period's torques move the centres of pressure so that the
// ground's torque on each foot balances its ankles' (the sole's centre under the ankle: no lever), and each sole
// tilts by θ = −M/k_sole, the ankle's link angles following it (the pelvis held). Told the soles' stiffness, the
// calibration finds each gear within 1 % (the stance's second-order terms, as above); believing the soles rigid, it
// finds each ankle as the gear and the sole in series, 1/(1/k + 1/k_sole), as exactly: the two are not separable
// when the sole's torque is the ankle's.
TEST(ChainStiffnessCalibration, TakesTheSolesTiltOutOfTheAnkles) {
  const Stance s;
  const JointVector k = true_stiffness();
  CompensationParams p = calibration_params();
  p.sole_stiffness_roll = 10000.0;
  p.sole_stiffness_pitch = 20000.0;
  walking::RobotModelData d;
  walking::forward_kinematics(s.model, d, walking::Pose{Vector3d::Zero(), Matrix3d::Identity()}, s.q);
  auto run = [&](const CompensationParams& belief) {
    ChainStiffnessCalibration c(s.model, belief, 0.004, 0.0, 4.0);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> torque(-20.0, 20.0);
    for (int n = 0; n < 1000; ++n) {
      const double t = n * 0.004;
      JointVector tau{}, encoder{};
      for (int j = 0; j < kJoints; ++j) tau[j] = torque(rng);
      std::array<humanoid::ForceTorque, 2> ft = readings(s, t);
      for (int j = 0; j < kJoints; ++j) encoder[j] = s.q[j] + tau[j] / k[j];
      for (int side = 0; side < 2; ++side) {
        const walking::LegJacobian J = walking::leg_jacobian(s.model, d, side, walking::sole_pose(s.model, d, side).p);
        Vector3d ground = Vector3d::Zero();  // the ground's torque on the foot about the sole's centre (world)
        for (int i : {4, 5}) ground -= J.block<3, 1>(3, i) * tau[humanoid::leg_first_joint(side) + i];  // (ankles)
        const Vector3d couple = d.frame[s.model.foot[side]].R.transpose() * ground;  // (foot frame, as the sensor)
        for (int a = 0; a < 3; ++a) ft[side].torque[a] -= couple[a];  // (the sensor reads the leg's wrench)
        const Vector3d tilt(-ground.x() / p.sole_stiffness_roll, -ground.y() / p.sole_stiffness_pitch, 0.0);
        for (int i : {4, 5})  // (the ankles' axes along y and x in the stance, so each takes its part of the tilt)
          encoder[humanoid::leg_first_joint(side) + i] += tilt.dot(J.block<3, 1>(3, i));
      }
      c.update(t, encoder, tau, ft, s.plan(), true);
    }
    return c;
  };
  CompensationParams rigid = p;
  rigid.sole_stiffness_roll = rigid.sole_stiffness_pitch = 0.0;
  const ChainStiffnessCalibration told = run(p), not_told = run(rigid);
  for (int j = 0; j < kJoints; ++j) {
    if (!told.identified(j)) continue;
    const bool pitch = j == humanoid::kLeftAnklePitch || j == humanoid::kRightAnklePitch;
    const bool roll = j == humanoid::kLeftAnkleRoll || j == humanoid::kRightAnkleRoll;
    const double sole = pitch ? p.sole_stiffness_pitch : roll ? p.sole_stiffness_roll : 0.0;
    const double series = sole > 0 ? 1.0 / (1.0 / k[j] + 1.0 / sole) : k[j];
    EXPECT_NEAR(told.estimate()[j], k[j], 0.01 * k[j]) << humanoid::kJointNames[j];
    EXPECT_NEAR(not_told.estimate()[j], series, 0.01 * series) << humanoid::kJointNames[j];
  }
  EXPECT_LT(not_told.estimate()[humanoid::kLeftAnkleRoll], 0.94 * k[humanoid::kLeftAnkleRoll]);  // (0.91: the sole)
}

// control.k_calibration_passes = 2: the second half is fitted afresh, its regressor's lag d/k taken at the first
// half's estimate. The stance's gears lag as Kelvin–Voigt elements do, by d/k of their true k (d = 20 Nm s/rad:
// 13 to 20 ms against the belief's 20 ms); each joint's torque is two sinusoids of its own, 0.5 to 3 Hz. One pass
// lags the regressor by the belief's d/k: measured 2.7 % off at worst (asserted: > 1.5 %). Two: the compensators
// take the first pass's estimate at the half, and the second finds each joint within 1 % (measured 0.8 %).
TEST(ChainStiffnessCalibration, ASecondPassLagsTheRegressorByTheFirstPassEstimate) {
  const Stance s;
  const JointVector k = true_stiffness();
  CompensationParams p = calibration_params();
  p.gear_damping = 20.0;
  p.load_filter_time = 0.0;
  const double period = 0.004, end = 4000 * period;
  JointVector lag;  // the true gears' d/k
  for (int j = 0; j < kJoints; ++j) lag[j] = p.gear_damping / k[j];
  auto run = [&](int passes, JointVector& at_half) {
    p.k_calibration_passes = passes;
    ChainStiffnessCalibration c(s.model, p, period, 0.0, end);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> frequency(0.5, 3.0), phase(0.0, 2 * M_PI);  // [Hz], [rad]
    std::array<std::array<double, 4>, kJoints> wave{};
    for (auto& w : wave) w = {2 * M_PI * frequency(rng), phase(rng), 2 * M_PI * frequency(rng), phase(rng)};
    LaggedGears gears;
    JointVector tau{};
    for (int i = 0; i < 4000; ++i) {
      for (int j = 0; j < kJoints; ++j) {
        const auto& w = wave[j];
        tau[j] = 12.0 * std::sin(w[0] * i * period + w[1]) + 8.0 * std::sin(w[2] * i * period + w[3]);
      }
      const JointVector encoder = gears.encoder(s.q, tau, k, lag, period);
      const double t = i * period;
      c.update(t, encoder, tau, readings(s, t), s.plan(), true);
      if (i == 2001) at_half = c.stiffness();
    }
    double worst = 0;
    for (int j = 0; j < kJoints; ++j)
      if (c.identified(j)) worst = std::max(worst, std::abs(c.estimate()[j] / k[j] - 1.0));
    return worst;
  };
  const ChainStiffnessCalibration probe(s.model, p, period, 0.0, end);  // (which joints are identified)
  JointVector half1{}, half2{};
  const double one = run(1, half1), two = run(2, half2);
  ::testing::Test::RecordProperty("one_pass_worst", std::to_string(one));
  ::testing::Test::RecordProperty("two_passes_worst", std::to_string(two));
  EXPECT_GT(one, 0.015);
  EXPECT_LT(two, 0.01);
  for (int j = 0; j < kJoints; ++j) {
    EXPECT_EQ(half1[j], kBelief) << "one pass: the belief until the end";
    if (probe.identified(j)) {
      EXPECT_NEAR(half2[j], k[j], 0.05 * k[j]) << "two: the first pass's estimate from the half on";
    }
  }
}

TEST(ChainStiffnessCalibration, BadDataASwingingFootOrTimesOutsideTheWindowGiveNoSample) {
  const Stance s;
  ChainStiffnessCalibration c(s.model, calibration_params(), 0.004, 1.0, 2.0);
  JointVector tau{};
  tau.fill(10.0);
  c.update(0.5, s.q, tau, readings(s, 0.5), s.plan(), true);  // before the window
  SupportPlan swing = s.plan();
  swing.swinging[1] = true;
  c.update(1.2, s.q, tau, readings(s, 1.2), swing, true);  // a foot swings
  EXPECT_EQ(c.samples(), 0);
  EXPECT_EQ(c.bad_data(), 0);
  JointVector nan_tau = tau;
  nan_tau[humanoid::kLeftKnee] = NAN;
  c.update(1.3, s.q, nan_tau, readings(s, 1.3), s.plan(), true);  // a NaN
  c.update(1.4, s.q, tau, readings(s, 1.3), s.plan(), true);      // an F/T reading 0.1 s old
  c.update(1.5, s.q, tau, readings(s, 1.5), s.plan(), false);     // the controller flags a sensor
  EXPECT_EQ(c.samples(), 0);
  EXPECT_EQ(c.bad_data(), 3);
  for (int j = 0; j < kJoints; ++j) EXPECT_EQ(c.estimate()[j], kBelief);
  // A foot barely loaded (its F/T reads 2 % of the weight): no sample either.
  std::array<humanoid::ForceTorque, 2> light = readings(s, 1.6);
  for (int a = 0; a < 3; ++a) light[0].force[a] *= 0.04, light[0].torque[a] *= 0.04;
  c.update(1.6, s.q, tau, light, s.plan(), true);
  EXPECT_EQ(c.samples(), 0);
}

TEST(ChainStiffnessCalibration, AdversarialDataStaysBoundedAndPositive) {
  const Stance s;
  ChainStiffnessCalibration c(s.model, calibration_params(), 0.004, 0.0, 10.0);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> garbage(-1.0, 1.0), torque(-100.0, 100.0);
  JointVector tau{}, encoder{};
  for (int i = 0; i < 2000; ++i) {
    for (int j = 0; j < kJoints; ++j) tau[j] = torque(rng), encoder[j] = s.q[j] + 0.2 * garbage(rng);
    const double t = i * 0.004;
    c.update(t, encoder, tau, readings(s, t), s.plan(), true);
  }
  EXPECT_GT(c.samples(), 1000);
  for (int j = 0; j < kJoints; ++j) {
    EXPECT_GT(c.estimate()[j], 0.0);
    EXPECT_GE(c.estimate()[j], kBelief / 10 * (1 - 1e-12));
    EXPECT_LE(c.estimate()[j], kBelief * 10 * (1 + 1e-12));
  }
}

}  // namespace
}  // namespace flexgait::compensation
