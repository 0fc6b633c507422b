// control.k_estimation: the RLS with forgetting converges on synthetic data with a
// known k in the number of samples its covariance predicts (σ/sqrt(Σ τ²)), tracks a change, and
// ignores non-finite data; the stiffness estimator, fed a flat-footed stance whose encoders read
// θ_link + τ/k, finds k per leg and joint group, stays bounded and positive under bad data, and
// keeps its estimate (counting the period) on a NaN or a stale F/T reading; the gyro's attitude
// (control.k_estimation_attitude_time) removes an attitude error that follows the torque; the stance offsets
// (control.k_estimation_stance_offset) remove an attitude error constant over each stance; the calibration at
// rest (control.k_estimation_gyro_rest) finds a gyro's bias while the pelvis turns slowly on still legs; per joint
// (control.k_estimation_per_joint) independent torques find each joint's own gear and proportional ones leave the
// parallel joints unconfident; the gear's torque from the current's loses the rotor's inertia exactly; a sole tilts
// under the ground's torque about its centre, not the ankle's; a parameter pushed past its bound is held there, not
// confident, and comes back with consistent data.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "flexgait/compensation/measured_gear_torque.hpp"
#include "flexgait/compensation/stiffness_estimator.hpp"

#include "double_support_stance.hpp"

namespace flexgait::compensation {
namespace {

using fixtures::kBelief;
using humanoid::JointVector;
using humanoid::kJoints;
using walking::Matrix3d;

constexpr double kPeriod = 0.004;  // [s]
constexpr double kTrue = 1250.0;   // [Nm/rad]
const humanoid::Imu kStill = [] {  // the IMU of a pelvis at rest, level: zero rate, +g up
  humanoid::Imu imu;
  imu.accel = {0.0, 0.0, 9.81};
  return imu;
}();

/// n samples of δ = τ/k + v, |τ| uniform in [20, 60] Nm with random sign, v ~ N(0, σ²).
struct Synthetic {
  std::mt19937 rng{7};
  std::uniform_real_distribution<double> magnitude{20.0, 60.0};
  std::bernoulli_distribution sign{0.5};
  double sigma = 1e-3;
  std::normal_distribution<double> noise{0.0, 1e-3};
  std::pair<double, double> next(double k) {
    const double tau = (sign(rng) ? 1 : -1) * magnitude(rng);
    return {tau, tau / k + noise(rng)};
  }
};

TEST(ForgettingRls, ConvergesInTheSamplesTheCovariancePredicts) {
  Synthetic s;
  const double c0 = 1 / kBelief, c = 1 / kTrue;
  ForgettingRls<1> rls(ForgettingRls<1>::Vector(c0), ForgettingRls<1>::Matrix(c0 * c0), 1.0);
  // Relative standard deviation ε after n samples: σ / (c sqrt(n E[τ²])), E[τ²] = (60³ − 20³)/(3·40).
  const double mean_square = (60.0 * 60 * 60 - 20.0 * 20 * 20) / 120.0, epsilon = 0.005;
  const int n = static_cast<int>(std::ceil(s.sigma * s.sigma / (epsilon * epsilon * c * c * mean_square)));
  EXPECT_LT(n, 100);  // (36 samples)
  double information = 1 / (c0 * c0);
  for (int i = 0; i < n; ++i) {
    const auto [tau, delta] = s.next(kTrue);
    rls.forget();
    ASSERT_TRUE(rls.update(ForgettingRls<1>::Vector(tau), delta, s.sigma * s.sigma));
    information += tau * tau / (s.sigma * s.sigma);
  }
  // The covariance is exactly the posterior's: 1/P = 1/P₀ + Σ τ²/σ².
  EXPECT_NEAR(rls.P()(0, 0) * information, 1.0, 1e-9);
  const double std_c = std::sqrt(rls.P()(0, 0));
  EXPECT_LT(std_c / c, 1.2 * epsilon);
  EXPECT_LT(std::abs(rls.x()[0] - c), 4 * std_c);  // within 4σ
  EXPECT_NEAR(1 / rls.x()[0], kTrue, 0.03 * kTrue);
}

TEST(ForgettingRls, ForgettingTracksAChangeAndNonFiniteDataChangesNothing) {
  Synthetic s;
  const double lambda = std::exp(-kPeriod / 0.5);  // memory 0.5 s = 125 samples
  ForgettingRls<1> rls(ForgettingRls<1>::Vector(1 / kBelief), ForgettingRls<1>::Matrix(1e-6), lambda);
  for (int i = 0; i < 2000; ++i) {
    const auto [tau, delta] = s.next(i < 1000 ? kTrue : kBelief);
    rls.forget();
    rls.update(ForgettingRls<1>::Vector(tau), delta, s.sigma * s.sigma);
  }
  EXPECT_NEAR(1 / rls.x()[0], kBelief, 0.01 * kBelief);  // 8 memories after the change
  const auto x = rls.x();
  const auto P = rls.P();
  EXPECT_FALSE(rls.update(ForgettingRls<1>::Vector(NAN), 0.01, 1e-6));
  EXPECT_FALSE(rls.update(ForgettingRls<1>::Vector(30.0), NAN, 1e-6));
  EXPECT_EQ(rls.x(), x);
  EXPECT_EQ(rls.P(), P);
}

// The covariance is the confidence the theory predicts (docs/guide/compensation.md, "Stiffness identified while
// walking"): over 400 seeds of white noise, the scatter of two parameters' estimates about the truth against P.
// Without forgetting P is the posterior covariance, so the scatter's variance is P. With forgetting λ in steady
// state the estimate is a least squares weighted λ^n, whose variance σ² Σλ^{2n}h² / (Σλ^n h²)² is
// P Σλ^{2n}/Σλ^n = P (1 − λ)/(1 − λ²) = P/(1 + λ): P overstates it by √(1 + λ) ≈ √2 (a conservative confidence).
// Tolerance: a variance from 400 draws has a relative std of √(2/400) = 7 %: 20 % is ~3σ.
TEST(ForgettingRls, TheCovarianceIsTheScatterOfTheEstimateOverSeeds) {
  const Eigen::Vector2d truth(1 / kTrue, 0.5 / kTrue);
  const double sigma = 1e-3;
  auto scatter = [&](double lambda, int samples, Eigen::Vector2d& p_mean) {
    Eigen::Vector2d sum_sq = Eigen::Vector2d::Zero();
    p_mean.setZero();
    constexpr int kSeeds = 400;
    for (int seed = 0; seed < kSeeds; ++seed) {
      std::mt19937 rng(static_cast<unsigned>(seed + 11));
      std::uniform_real_distribution<double> h(-60.0, 60.0);
      std::normal_distribution<double> noise(0.0, sigma);
      ForgettingRls<2> rls(Eigen::Vector2d(1 / kBelief, 1 / kBelief),
                           Eigen::Vector2d(1 / kBelief, 1 / kBelief).array().square().matrix().asDiagonal(), lambda);
      for (int i = 0; i < samples; ++i) {
        const Eigen::Vector2d hi(h(rng), h(rng));
        rls.forget();
        rls.update(hi, hi.dot(truth) + noise(rng), sigma * sigma);
      }
      sum_sq += (rls.x() - truth).array().square().matrix();
      p_mean += rls.P().diagonal();
    }
    p_mean /= kSeeds;
    return Eigen::Vector2d(sum_sq / kSeeds);
  };
  Eigen::Vector2d P;
  const Eigen::Vector2d plain = scatter(1.0, 300, P);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(plain[i] / P[i], 1.0, 0.2) << i;
  const double lambda = std::exp(-1.0 / 50);  // a memory of 50 samples, 1000 samples: steady state
  const Eigen::Vector2d forgetting = scatter(lambda, 1000, P);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(forgetting[i] / P[i] * (1 + lambda), 1.0, 0.2) << i;
}

using fixtures::readings;
using fixtures::Stance;

/// The modelled torque's identification: one 1/k per leg joint group.
CompensationParams estimation_params() {
  CompensationParams p = fixtures::identification_params(KEstimation::kOn);
  return p;
}

/// An estimator of estimation_params() with change(params) applied; rest_end: the end of the gyro's calibration [s].
template <class Change>
StiffnessEstimator estimator(const Stance& s, const Change& change, double rest_end = 0.0) {
  CompensationParams p = estimation_params();
  change(p);
  return StiffnessEstimator(s.model, p, kPeriod, rest_end);
}

/// Each leg joint's own gear in the per-joint tests (hip yaw first): 0.8 to 1.2 × kTrue.
constexpr std::array<double, humanoid::kLegJoints> kJointScale = {1.0, 0.8, 1.2, 0.9, 1.1, 0.85};

double true_stiffness(int joint) {
  for (int side = 0; side < 2; ++side)
    if (humanoid::in_leg(joint, side)) return kTrue * kJointScale[joint - humanoid::leg_first_joint(side)];
  return kTrue;
}

/// `periods` periods of the still stance with random torques in [−40, 40] Nm, the encoders reading θ_link + τ/k
/// (k = stiffness(joint)) and the controller's attitude attitude(k, τ); the IMU reads a pelvis at rest.
template <class Attitude, class Stiffness>
void feed_random_torques(StiffnessEstimator& e, const Stance& s, const Attitude& attitude, int periods,
                         const Stiffness& stiffness) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> torque(-40.0, 40.0);
  JointVector tau{}, encoder{};
  for (int k = 0; k < periods; ++k) {
    for (int j = 0; j < kJoints; ++j) {
      tau[j] = torque(rng);
      encoder[j] = s.q[j] + tau[j] / stiffness(j);  // θ_enc = θ_link + τ/k
    }
    e.update(k * kPeriod, encoder, attitude(k, tau), kStill, tau, readings(s, k * kPeriod), s.plan(), true);
  }
}

/// 500 periods of it on gears of kTrue.
template <class Attitude>
void feed_random_torques(StiffnessEstimator& e, const Stance& s, const Attitude& attitude) {
  feed_random_torques(e, s, attitude, 500, [](int) { return kTrue; });
}

TEST(StiffnessEstimator, FindsEachLegsRollAndPitchStiffnessFromTheFlatFootsTilt) {
  const Stance s;
  StiffnessEstimator e(s.model, estimation_params(), kPeriod);
  feed_random_torques(e, s, [](int, const JointVector&) { return Matrix3d::Identity(); });
  EXPECT_GT(e.samples(), 950);  // (a few random torques fall below control.k_estimation_min_torque)
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < humanoid::kLegJoints; ++i) {
      const int j = humanoid::leg_first_joint(side) + i;
      if (i == 0) {  // hip yaw: not observed, the belief
        EXPECT_FALSE(e.identified(j));
        EXPECT_EQ(e.estimate()[j], kBelief);
        continue;
      }
      // The tilt is linearised in the deflections (≈ 0.03 rad): second-order terms of ≈ 1 %.
      EXPECT_NEAR(e.estimate()[j], kTrue, 0.02 * kTrue) << humanoid::kJointNames[j];
      EXPECT_EQ(e.stiffness()[j], e.estimate()[j]) << "confident: the compensators use it";
    }
  EXPECT_TRUE(e.confident(humanoid::leg_first_joint(0) + 1));  // (the left hip roll's group)
  EXPECT_TRUE(e.confident(humanoid::leg_first_joint(1) + 2));  // (the right hip pitch's)
}

// control.k_estimation_per_joint: each leg joint with a gear of its own (0.8 to 1.2 × 1250 Nm/rad), torques drawn
// independently per joint, as measured torques vary: the parallel joints separate and each joint's 1/k is found
// (2 %: the linearisation of the tilt, as above), confident, with a relative std of its own. The confidence is the
// RLS covariance the theory predicts (ForgettingRls tests); per joint it is larger than per group (five parameters
// from the same two tilt components).
TEST(StiffnessEstimator, PerJointFindsEachJointsOwnGearFromIndependentTorques) {
  const Stance s;
  StiffnessEstimator e = estimator(s, [](CompensationParams& p) { p.k_estimation_per_joint = true; });
  feed_random_torques(
      e, s, [](int, const JointVector&) { return Matrix3d::Identity(); }, 2000, true_stiffness);
  for (int j = 0; j < kJoints; ++j) {
    if (!e.identified(j)) continue;
    EXPECT_NEAR(e.estimate()[j], true_stiffness(j), 0.02 * true_stiffness(j)) << humanoid::kJointNames[j];
    EXPECT_TRUE(e.confident(j)) << humanoid::kJointNames[j];
    EXPECT_EQ(e.stiffness()[j], e.estimate()[j]) << humanoid::kJointNames[j];
  }
  // One parameter per joint: the knee's and the hip pitch's confidences differ (a group would share one).
  EXPECT_NE(e.relative_std(humanoid::kLeftKnee), e.relative_std(humanoid::kLeftHipPitch));
}

// Per joint, torques that move in proportion (τ_j = w_j s(t), as the parallel joints' modelled torques nearly do
// while walking) leave the parallel joints apart undetermined: the tilt sees only Σ_j a_j w_j c_j. Their relative
// std stays near the prior's (100 %), far above control.k_estimation_confidence: the compensators keep the belief.
TEST(StiffnessEstimator, PerJointTorquesInProportionLeaveTheParallelJointsUnconfident) {
  const Stance s;
  StiffnessEstimator e = estimator(s, [](CompensationParams& p) { p.k_estimation_per_joint = true; });
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> load(10.0, 40.0);
  JointVector tau{}, encoder{};
  for (int k = 0; k < 2000; ++k) {
    const double scale = load(rng);
    for (int j = 0; j < kJoints; ++j) {
      tau[j] = scale * (1.0 + 0.1 * j);
      encoder[j] = s.q[j] + tau[j] / kTrue;
    }
    e.update(k * kPeriod, encoder, Matrix3d::Identity(), kStill, tau, readings(s, k * kPeriod), s.plan(), true);
  }
  for (const int j : {humanoid::kLeftHipPitch, humanoid::kLeftKnee, humanoid::kLeftAnklePitch}) {
    EXPECT_GT(e.relative_std(j), 0.2) << humanoid::kJointNames[j];
    EXPECT_FALSE(e.confident(j)) << humanoid::kJointNames[j];
    EXPECT_EQ(e.stiffness()[j], kBelief) << humanoid::kJointNames[j];
  }
}

// The soles tilt in their contacts under the ground's torque about each sole's centre (sole_contact, sole_tilt), as
// the F/T sensor gives it, not under the ankle's. The stance's ground force at each sole's centre: no tilt but the
// foot's own weight's moment about the sensor, which walking::foot_contact leaves in (m g |c_xy| / k_sole: 6e-6 rad),
// though the builtin's sole is 14 mm outward of the ankle so the ankle's axes carry the force's moment (asserted
// > 3 Nm). The same force 10 mm ahead and 20 mm inward of the centre adds M = (Δ_y f_z, −Δ_x f_z) about the centre:
// θ = −M/k_sole about the sole's x and y more, to 1e-10 relative (round-off).
TEST(StiffnessEstimator, ASoleTiltsUnderTheGroundsTorqueAboutItsCentreNotTheAnkles) {
  const fixtures::Stance s;
  CompensationParams p;
  p.sole_stiffness_roll = 25000.0;
  p.sole_stiffness_pitch = 50000.0;
  walking::RobotModelData d;
  walking::forward_kinematics(s.model, d, walking::Pose{walking::Vector3d::Zero(), Matrix3d::Identity()}, s.q);
  for (int side = 0; side < 2; ++side) {
    const walking::Pose& foot = d.frame[static_cast<std::size_t>(s.model.foot[side])];
    const walking::Vector3d centre = walking::sole_pose(s.model, d, side).p;
    const double fz = 0.5 * s.model.total_mass * s.model.gravity;
    const walking::Vector3d ground(0, 0, fz);
    // The sensor's reading with the ground's force at `at` (the fixture's, at any point; the sensor at the ankle).
    auto reading = [&](const walking::Vector3d& at) {
      humanoid::ForceTorque ft = fixtures::readings(s, 0.0)[static_cast<std::size_t>(side)];
      const walking::Vector3d extra = foot.R.transpose() * (-(at - centre).cross(ground));  // (the moved force's)
      for (int a = 0; a < 3; ++a) ft.torque[static_cast<std::size_t>(a)] += extra[a];
      return ft;
    };
    const walking::Vector3d at_centre = sole_tilt(sole_contact(s.model, reading(centre), foot.R, side), p);
    const auto& foot_body = s.model.bodies[static_cast<std::size_t>(s.model.foot[side])];
    const double weight_moment = foot_body.mass * s.model.gravity * (foot.R * foot_body.com).head<2>().norm();
    EXPECT_LE(at_centre.norm(), weight_moment / p.sole_stiffness_roll + 1e-12) << side;
    EXPECT_GT(std::abs((centre - foot.p).cross(ground).x()), 3.0) << side;  // (the ankle's: the sole's offset)
    const walking::Vector3d shift(0.01, side == 0 ? -0.02 : 0.02, 0.0);
    const walking::Vector3d moved = sole_tilt(sole_contact(s.model, reading(centre + shift), foot.R, side), p);
    const walking::Vector3d expected(-shift.y() * fz / p.sole_stiffness_roll, shift.x() * fz / p.sole_stiffness_pitch,
                                     0.0);
    EXPECT_LT((moved - at_centre - expected).norm(), 1e-10 * expected.norm()) << side;
  }
}

// The gear's torque from the current's (control.k_estimation_torque measured): the rotor's inertia times the
// encoder's second difference comes out exactly for a quadratic motion (the second difference is exact there; the
// round-off of θ's cancellation, ~1e-16 × 1 rad / T² × J, is ~1e-11 Nm). Before two earlier readings: the current's.
TEST(MeasuredGearTorque, TakesTheRotorsInertiaOutOfTheCurrentsTorque) {
  const double inertia = 0.8, accel = 3.0;  // [kg m^2], [rad/s^2]
  MeasuredGearTorque m(inertia, kPeriod);
  JointVector gear{}, motor{}, encoder{};
  for (int k = 0; k < 10; ++k) {
    const double t = k * kPeriod;
    for (int j = 0; j < kJoints; ++j) {
      gear[j] = 20.0 + j;
      motor[j] = gear[j] + inertia * accel;
      encoder[j] = 0.3 + 0.5 * t + 0.5 * accel * t * t;
    }
    const JointVector& out = m.update(motor, encoder);
    for (int j = 0; j < kJoints; ++j) EXPECT_NEAR(out[j], k < 2 ? motor[j] : gear[j], 1e-8) << k;
  }
}

// control.k_estimation_attitude_time: an attitude estimate whose roll error follows the left hip roll's torque
// (as an observer that reads the legs' kinematics partly takes the deflection for the pelvis's tilt) biases the
// left roll group; the gyro's attitude (the pelvis at rest: zero rate), pulled to that estimate over a time much
// longer than the run, does not.
TEST(StiffnessEstimator, TheGyrosAttitudeRemovesAnAttitudeErrorThatFollowsTheTorque) {
  const Stance s;
  auto run = [&](double attitude_time) {
    StiffnessEstimator e = estimator(s, [&](CompensationParams& p) { p.k_estimation_attitude_time = attitude_time; });
    // A roll error of 2e-4 rad/Nm × τ (≤ 0.008 rad, a quarter of the hip roll's deflection), none at the start.
    feed_random_torques(e, s, [](int k, const JointVector& tau) {
      return walking::rot_x(k == 0 ? 0.0 : 2e-4 * tau[humanoid::kLeftHipRoll]);
    });
    return e.estimate()[humanoid::kLeftHipRoll];
  };
  EXPECT_GT(std::abs(run(0.0) - kTrue), 0.05 * kTrue);  // the controller's attitude: biased
  // 2 s of data against t_a = 10⁴ s: the pull carries ≈ 2e-4 of the error; 2 % as in the flat-foot test above.
  EXPECT_NEAR(run(1e4), kTrue, 0.02 * kTrue);
}

// control.gear_damping d: the gear is a Kelvin–Voigt element, k δ + d δ̇ = τ, so the encoders read the torque through
// a lag d/k (80 Nm s/rad on 1250 Nm/rad: 64 ms) — at the gait's frequencies (torques of 5 ± 30 Nm at 0.8–1.3 Hz, per
// joint a phase of its own) a phase of up to 0.6 rad. The regressor through the same lag finds k; without it (the
// belief of d 0) the estimate is biased. The lag's k is what the compensators use: the belief until confident
// (80 ms against 64), then the estimate.
TEST(StiffnessEstimator, TheRegressorLagsTheTorqueAsTheGearsDeflectsBehindIt) {
  const Stance s;
  const double damping = 80.0;  // [Nm s/rad]
  auto run = [&](double believed_damping) {
    StiffnessEstimator e = estimator(s, [&](CompensationParams& p) {
      p.gear_damping = believed_damping;
      p.load_filter_time = 0;  // (the modelled torque is the load itself)
    });
    JointVector tau{}, deflection{}, encoder{};
    for (long k = 0; k < 5000; ++k) {  // 20 s
      const double t = k * kPeriod;
      for (int j = 0; j < kJoints; ++j) {
        const double f = 0.8 + 0.05 * j, phase = 0.7 * j;
        tau[j] = 5.0 + 30.0 * std::sin(2 * std::numbers::pi * f * t + phase);
        // Backward Euler of k δ + d δ̇ = τ over the period (the twin integrates the damping implicitly).
        deflection[j] =
            k == 0 ? tau[j] / kTrue : (tau[j] * kPeriod + damping * deflection[j]) / (kTrue * kPeriod + damping);
        encoder[j] = s.q[j] + deflection[j];
      }
      e.update(t, encoder, Matrix3d::Identity(), kStill, tau, readings(s, t), s.plan(), true);
    }
    double worst = 0;
    for (int j = 0; j < kJoints; ++j)
      if (e.identified(j)) worst = std::max(worst, std::abs(e.estimate()[j] / kTrue - 1));
    return worst;
  };
  // Measured: 26 % off without the lag, 0.1 % with it; 2 %: the linearisation, as the flat-foot test.
  EXPECT_GT(run(0.0), 0.10) << "the torque as it is";
  EXPECT_LT(run(damping), 0.02);
}

// control.k_estimation_stance_offset: torques of one sign, as a stance's load (uniform in [10, 50] Nm), and an
// attitude error that drifts from stance to stance (a gyro's drift, held constant within each stance: 1 mrad
// more about x and y after each swing, against ≈ 24 mrad of deflection tilt per joint): without the offsets the
// estimate is biased; with them each stance's tilt changes alone inform 1/k.
TEST(StiffnessEstimator, StanceOffsetsRemoveAnAttitudeErrorConstantOverEachStance) {
  const Stance s;
  auto run = [&](bool offsets) {
    StiffnessEstimator e = estimator(s, [&](CompensationParams& p) {
      p.k_estimation_stance_offset = offsets;
      p.k_estimation_attitude_time = 0;  // (the error is in the controller's attitude, used as it is)
    });
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> torque(10.0, 50.0);
    JointVector tau{}, encoder{};
    long k = 0;
    for (int stance = 0; stance < 8; ++stance) {
      SupportPlan swing = s.plan();
      swing.swinging = {true, true};  // one period of swing between stances: no sample, the offsets start anew
      e.update(k * kPeriod, s.q, Matrix3d::Identity(), kStill, tau, readings(s, k * kPeriod), swing, true);
      ++k;
      const Matrix3d error = walking::rot_x(0.001 * stance) * walking::rot_y(-0.001 * stance);
      for (int i = 0; i < 250; ++i, ++k) {
        for (int j = 0; j < kJoints; ++j) {
          tau[j] = torque(rng);
          encoder[j] = s.q[j] + tau[j] / kTrue;
        }
        e.update(k * kPeriod, encoder, error, kStill, tau, readings(s, k * kPeriod), s.plan(), true);
      }
    }
    double worst = 0;
    for (int j = 0; j < kJoints; ++j)
      if (e.identified(j)) worst = std::max(worst, std::abs(e.estimate()[j] / kTrue - 1));
    return worst;
  };
  EXPECT_GT(run(false), 0.05) << "without the offsets";
  // 2 %: the linearisation of the tilt (the flat-foot test above); the offsets cost the constant part of the
  // torques' information, the varying part (±20 Nm over 2000 samples) is plenty.
  EXPECT_LT(run(true), 0.02);
}

// control.k_estimation_gyro_rest: a gyro with bias b on a pelvis that turns slowly about x (ω = 3e-4 rad/s, as
// the twin follows its observer's drift in the start stance) over flat, still soles: the legs' encoders show the
// turn. b̂ = (the gyro's turn − the legs' turn) / the window recovers b; the mean alone would be off by ω.
TEST(StiffnessEstimator, TheCalibrationAtRestFindsTheGyrosBiasWhileThePelvisTurnsSlowly) {
  const Stance s;
  const double rest_end = 1.2, turn_rate = 3e-4;  // [s], [rad/s]
  StiffnessEstimator e = estimator(
      s, [](CompensationParams& p) { p.k_estimation_gyro_rest = 1.0; }, rest_end);
  const walking::Vector3d bias(0.001, -0.002, 0.0005), gravity(0, 0, 9.81);
  // The soles in the upright pelvis's frame; the pelvis turns about its origin, the soles stay.
  walking::RobotModelData data;
  walking::forward_kinematics(s.model, data, walking::Pose{walking::Vector3d::Zero(), Matrix3d::Identity()}, s.q);
  const std::array<walking::Pose, 2> soles = {walking::sole_pose(s.model, data, 0),
                                              walking::sole_pose(s.model, data, 1)};
  JointVector tau{};
  tau.fill(30.0);
  long k = 0;
  for (; k * kPeriod < rest_end + 2 * kPeriod; ++k) {
    const double t = k * kPeriod;
    const Matrix3d R = walking::rot_x(0.01 + turn_rate * t);
    JointVector encoder{};
    for (int side = 0; side < 2; ++side) {
      const walking::IkSolution ik = walking::leg_inverse_kinematics(
          s.model.leg[side], walking::Pose{R.transpose() * soles[side].p, R.transpose() * soles[side].R});
      for (int i = 0; i < humanoid::kLegJoints; ++i)
        encoder[humanoid::leg_first_joint(side) + i] = ik.q[i] + tau[i] / kBelief;
    }
    humanoid::Imu imu;
    const walking::Vector3d gyro = walking::Vector3d(turn_rate, 0, 0) + bias, accel = R.transpose() * gravity;
    for (int i = 0; i < 3; ++i) imu.delta_angle[i] = gyro[i] * kPeriod, imu.accel[i] = accel[i];
    const int used = e.update(t, encoder, R, imu, tau, readings(s, t), s.plan(), true);
    if (t < rest_end) {
      EXPECT_EQ(used, 0) << "no sample before the calibration";
    }
  }
  // The IMU's turns (of a constant rate) summed and the legs' turn: exact to round-off and to the
  // IK's tolerance (the turn is 3e-4 rad over 1 s: 1e-9 rad of error is 1e-9 rad/s).
  EXPECT_NEAR(e.gyro_bias().x(), bias.x(), 1e-8);
  EXPECT_NEAR(e.gyro_bias().y(), bias.y(), 1e-8);
  EXPECT_NEAR(e.gyro_bias().z(), bias.z(), 1e-8);
}

// Data that pushes a parameter past its bound (encoders reading the pitch joints' deflections backwards and twice
// over: an apparent 1/k of −2/k) with the stance's tilt offsets estimated beside it: the parameter is held at the
// bound with the states it correlates with at their conditional mean, and is never confident there (the compensators
// keep the belief). Consistent data afterwards brings every joint back within 2 % of its gear, confident. With the
// parameter clamped alone, the offsets ran away (1e40 rad within a second, on the twin with a drifting gyro).
TEST(StiffnessEstimator, AParameterHeldAtItsBoundKeepsTheBeliefAndComesBackWithConsistentData) {
  const fixtures::Stance s;
  StiffnessEstimator e = estimator(s, [](CompensationParams& p) {
    p.k_estimation_stance_offset = true;
    p.k_estimation_memory = 0.5;  // (the adversarial samples forgotten once consistent ones come)
  });
  const auto identity = [](int, const JointVector&) { return Matrix3d::Identity(); };
  const auto pitch = [](int j) {
    const int i = j - humanoid::leg_first_joint(humanoid::in_leg(j, 0) ? 0 : 1);
    return i == 2 || i == 3 || i == 4;  // (hip pitch, knee, ankle pitch)
  };
  feed_random_torques(e, s, identity, 500, [&](int j) { return pitch(j) ? -0.5 * kTrue : kTrue; });
  for (int j = 0; j < kJoints; ++j) {
    if (!e.identified(j) || !pitch(j)) continue;
    EXPECT_NEAR(e.estimate()[j], 10.0 * kBelief, 1e-9 * kBelief) << humanoid::kJointNames[j];  // (the bound)
    EXPECT_FALSE(e.confident(j)) << humanoid::kJointNames[j];
    EXPECT_EQ(e.stiffness()[j], kBelief) << humanoid::kJointNames[j];
  }
  feed_random_torques(e, s, identity, 2000, [](int) { return kTrue; });
  for (int j = 0; j < kJoints; ++j) {
    if (!e.identified(j)) continue;
    EXPECT_NEAR(e.estimate()[j], kTrue, 0.02 * kTrue) << humanoid::kJointNames[j];
    EXPECT_TRUE(e.confident(j)) << humanoid::kJointNames[j];
  }
}

TEST(StiffnessEstimator, BadDataKeepsTheEstimateAndAdversarialDataStaysBoundedAndPositive) {
  const Stance s;
  StiffnessEstimator e(s.model, estimation_params(), kPeriod);
  JointVector tau{}, encoder = s.q;
  tau.fill(30.0);
  for (int j = 0; j < kJoints; ++j) encoder[j] += tau[j] / kTrue;
  for (int k = 0; k < 100; ++k)
    e.update(k * kPeriod, encoder, Matrix3d::Identity(), kStill, tau, readings(s, k * kPeriod), s.plan(), true);
  const JointVector before = e.estimate();
  const double t = 100 * kPeriod;
  JointVector nan_encoder = encoder;
  nan_encoder[humanoid::kLeftKnee] = NAN;
  auto nan_ft = readings(s, t);
  nan_ft[1].force[2] = NAN;
  EXPECT_EQ(e.update(t, nan_encoder, Matrix3d::Identity(), kStill, tau, readings(s, t), s.plan(), true), 0);
  EXPECT_EQ(e.update(t, encoder, Matrix3d::Identity(), kStill, tau, nan_ft, s.plan(), true), 0);
  EXPECT_EQ(e.update(t, encoder, Matrix3d::Identity(), kStill, tau, readings(s, t - 0.1), s.plan(), true), 0);  // stale
  EXPECT_EQ(e.update(t, encoder, Matrix3d::Identity(), kStill, tau, readings(s, t), s.plan(), false), 0);  // flagged
  EXPECT_EQ(e.bad_data(), 4);
  EXPECT_EQ(e.estimate(), before);
  // Encoders bent the wrong way, far: the estimate hits its bound, k stays positive.
  for (int j = 0; j < kJoints; ++j) encoder[j] = s.q[j] - 0.3 * tau[j] / kTrue;
  for (int k = 0; k < 2000; ++k)
    e.update(t + k * kPeriod, encoder, Matrix3d::Identity(), kStill, tau, readings(s, t + k * kPeriod), s.plan(), true);
  for (int j = 0; j < kJoints; ++j) {
    EXPECT_GT(e.estimate()[j], 0.0);
    EXPECT_GE(e.estimate()[j], kBelief / 10 - 1e-9);
    EXPECT_LE(e.estimate()[j], kBelief * 10 + 1e-9);
    EXPECT_GT(e.stiffness()[j], 0.0);
  }
}

}  // namespace
}  // namespace flexgait::compensation
