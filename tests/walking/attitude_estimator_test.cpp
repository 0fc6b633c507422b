// The Mahony filter on synthetic IMU data: it starts at the accelerometer's tilt; from a wrong
// start it converges to a static tilt within the envelope of its small-error dynamics
// (θ̈ + k_P θ̇ + k_I θ = 0); it follows a constant rate; it learns and rejects a constant gyro bias;
// it allocates nothing.
#include "flexgait/walking/attitude_estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "../support/count_allocations.hpp"

using flexgait::testing::g_allocations;

namespace flexgait::walking {
namespace {

constexpr double kT = 0.004, kG = 9.81;

/// Gains for the synthetic tests: faster than the walking defaults (k_P = 1 rad/s, k_I = 0.1
/// rad/s²: poles −0.113 and −0.887 rad/s) so that a minute of data shows convergence; no
/// alignment phase and no levelling window (the start-up is tested on its own).
EstimatorParams test_gains() {
  EstimatorParams p;
  p.kp = 1.0;
  p.ki = 0.1;
  p.align_time = 0;
  p.level_time = 0;
  return p;
}

/// The accelerometer of a body at rest with attitude R: specific force Rᵀ g e_z.
Vector3d at_rest(const Matrix3d& R) {
  return R.transpose() * Vector3d(0, 0, kG);
}

/// Roll/pitch error between two attitudes [rad] (the angle between their "up" directions).
double tilt_error(const Matrix3d& a, const Matrix3d& b) {
  const Vector3d ua = a.transpose() * Vector3d::UnitZ(), ub = b.transpose() * Vector3d::UnitZ();
  return std::atan2(ua.cross(ub).norm(), ua.dot(ub));
}

/// |θ(t)|'s bound for θ(0) = θ0, b̃(0) = b0 under θ̈ + k_P θ̇ + k_I θ = 0 (real, distinct poles):
/// |A| e^{s1 t} + |B| e^{s2 t}.
double envelope(double kp, double ki, double theta0, double dtheta0, double t) {
  const double disc = std::sqrt(kp * kp - 4 * ki);
  const double s1 = 0.5 * (-kp + disc), s2 = 0.5 * (-kp - disc);
  const double A = (dtheta0 - s2 * theta0) / (s1 - s2), B = theta0 - A;
  return std::abs(A) * std::exp(s1 * t) + std::abs(B) * std::exp(s2 * t);
}

TEST(AttitudeEstimator, StartsAtTheAccelerometersTilt) {
  AttitudeEstimator f{test_gains()};
  const Matrix3d R = rpy_to_matrix(0.1, -0.2, 0.0);
  f.update(Vector3d::Zero(), nullptr, Vector3d::Zero(), kT);
  EXPECT_FALSE(f.initialised());  // nothing to start from without the accelerometer
  const Vector3d a = at_rest(R);
  f.update(Vector3d::Zero(), &a, Vector3d::Zero(), kT);
  ASSERT_TRUE(f.initialised());
  EXPECT_NEAR(roll_of(f.attitude()), 0.1, 1e-12);
  EXPECT_NEAR(pitch_of(f.attitude()), -0.2, 1e-12);
}

TEST(AttitudeEstimator, ConvergesToAStaticTiltWithinItsEnvelope) {
  // Start level, then the body is found tilted by 0.05 rad in roll (small: the linearised
  // dynamics hold to O(θ²) = 0.25 %) : the error must stay under the envelope of
  // θ̈ + k_P θ̇ + k_I θ = 0 with θ(0) = θ0, θ̇(0) = −k_P θ0 (b̃(0) = 0), plus 5 % for the
  // nonlinearity (sin θ) and the discretisation (k_P T = 0.004).
  EstimatorParams p = test_gains();
  AttitudeEstimator f{p};
  const Vector3d level = at_rest(Matrix3d::Identity());
  f.update(Vector3d::Zero(), &level, Vector3d::Zero(), kT);
  const double theta0 = 0.05;
  const Matrix3d R = rpy_to_matrix(theta0, 0, 0);
  const Vector3d a = at_rest(R);
  double worst_ratio = 0;
  for (int k = 1; k <= 15000; ++k) {  // 60 s
    f.update(Vector3d::Zero(), &a, Vector3d::Zero(), kT);
    const double t = k * kT;
    const double e = tilt_error(f.attitude(), R);
    const double bound = envelope(p.kp, p.ki, theta0, -p.kp * theta0, t);
    worst_ratio = std::max(worst_ratio, e / (1.05 * bound + 1e-9));
  }
  EXPECT_LE(worst_ratio, 1.0);
  EXPECT_LT(tilt_error(f.attitude(), R), 1e-4);  // envelope at 60 s: 0.0029 θ0 = 1.5e-4 rad
}

TEST(AttitudeEstimator, FollowsAConstantRate) {
  // Rotating about the vertical at 1 rad/s keeps the tilt: the gyro alone carries it, and the
  // accelerometer agrees, so the tilt error stays at round-off; a roll rate of 0.2 rad/s for 1 s
  // is integrated exactly (the update uses the exact exponential).
  AttitudeEstimator f{test_gains()};
  Matrix3d R = rpy_to_matrix(0.1, 0.05, 0);
  Vector3d a = at_rest(R);
  f.update(Vector3d::Zero(), &a, Vector3d::Zero(), kT);
  const Vector3d yaw_rate_body = R.transpose() * Vector3d(0, 0, 1.0);
  for (int k = 0; k < 1000; ++k) {
    R = R * Eigen::AngleAxisd(kT, yaw_rate_body.normalized()).toRotationMatrix();
    a = at_rest(R);
    f.update(yaw_rate_body, &a, Vector3d::Zero(), kT);
  }
  EXPECT_LT(tilt_error(f.attitude(), R), 1e-9);
  const Vector3d roll_rate(0.2, 0, 0);
  for (int k = 0; k < 250; ++k) {
    R = R * Eigen::AngleAxisd(0.2 * kT, Vector3d::UnitX()).toRotationMatrix();
    a = at_rest(R);
    f.update(roll_rate, &a, Vector3d::Zero(), kT);
  }
  EXPECT_LT(tilt_error(f.attitude(), R), 1e-9);
}

TEST(AttitudeEstimator, LearnsAndRejectsAConstantGyroBias) {
  // A gyro bias b on roll and pitch: without correction the attitude would drift b t (0.6 rad in
  // 60 s). With it the error peaks near b / k_P and decays with the slow pole; after 100 s the
  // envelope (θ(0) = 0, θ̇(0) = b) is 1.2e-5 rad and the bias estimate has converged.
  EstimatorParams p = test_gains();
  AttitudeEstimator f{p};
  const Matrix3d R = rpy_to_matrix(0.02, -0.03, 0);
  const Vector3d a = at_rest(R);
  const Vector3d bias(0.01, -0.01, 0);
  f.update(bias, &a, Vector3d::Zero(), kT);
  double peak = 0;
  for (int k = 0; k < 25000; ++k) {  // 100 s
    f.update(bias, &a, Vector3d::Zero(), kT);
    peak = std::max(peak, tilt_error(f.attitude(), R));
  }
  EXPECT_LT(peak, 1.05 * std::sqrt(2.0) * 0.01 / p.kp);  // both axes: |b| / k_P at most
  EXPECT_LT(tilt_error(f.attitude(), R), 1e-4);
  EXPECT_NEAR(f.bias().x(), 0.01, 1e-4);
  EXPECT_NEAR(f.bias().y(), -0.01, 1e-4);
}

TEST(AttitudeEstimator, TakesThePlannedAccelerationOut) {
  // A body at rest in attitude but accelerating 1 m/s² sideways as planned: with the
  // compensation the estimate stays on the true tilt; without, it tilts by atan(a/g) = 0.10 rad.
  for (bool compensate : {true, false}) {
    EstimatorParams p = test_gains();
    p.accel_compensation = compensate;
    AttitudeEstimator f{p};
    const Vector3d level = at_rest(Matrix3d::Identity());
    f.update(Vector3d::Zero(), &level, Vector3d::Zero(), kT);
    const Vector3d accel_world(0, 1.0, 0);
    const Vector3d a = Vector3d(0, 0, kG) + accel_world;  // level body: pelvis frame = world
    for (int k = 0; k < 15000; ++k) f.update(Vector3d::Zero(), &a, accel_world, kT);  // 60 s: e^{-0.113·60} = 1e-3
    const double e = tilt_error(f.attitude(), Matrix3d::Identity());
    if (compensate)
      EXPECT_LT(e, 1e-9);
    else
      EXPECT_NEAR(e, std::atan(1.0 / kG), 1e-3);
  }
}

TEST(AttitudeEstimator, AlignsFastThenSwitchesToTheSlowGains) {
  // The first reading taken while the body accelerates 0.5 m/s² sideways starts it 0.05 rad off;
  // at rest afterwards the alignment (k_P = align_kp = 5 rad/s, no bias integral) removes the
  // error as e^{−align_kp t} (1 s: 7e-3 of it), after which the slow gains apply.
  EstimatorParams p;  // the defaults, but no levelling window: the one reading starts it
  p.level_time = 0;
  AttitudeEstimator f{p};
  const Matrix3d R = rpy_to_matrix(0.03, -0.02, 0);
  const Vector3d first = R.transpose() * Vector3d(0, 0.5, kG);
  f.update(Vector3d::Zero(), &first, Vector3d::Zero(), kT);
  const double e0 = tilt_error(f.attitude(), R);
  EXPECT_NEAR(e0, std::atan(0.5 / kG), 1e-3);
  const Vector3d a = at_rest(R);
  const int n = static_cast<int>(std::lround(p.align_time / kT));
  for (int k = 0; k < n; ++k) f.update(Vector3d::Zero(), &a, Vector3d::Zero(), kT);
  // e^{−5·1} = 6.7e-3 of e0, +10 % for the discretisation (align_kp T = 0.02) and sin θ.
  EXPECT_LT(tilt_error(f.attitude(), R), 1.1 * std::exp(-p.align_kp * p.align_time) * e0);
  EXPECT_EQ(f.bias(), Vector3d::Zero());  // no bias learnt while aligning
  f.update(Vector3d::Zero(), &a, Vector3d::Zero(), kT);
  f.update(Vector3d(0.001, 0, 0), &a, Vector3d::Zero(), kT);
  EXPECT_NE(f.bias(), Vector3d::Zero());  // the slow gains now
}

TEST(AttitudeEstimator, LevelsOnTheFirstSteadyWindowAfterATransient) {
  // The twin's start: for 0.1 s the body pitches at 2 rad/s and the accelerometer swings (here
  // its direction turns 2 rad/s × T = 8 mrad per reading, beyond level_tolerance over a few
  // readings, at |a| = g so the magnitude gate alone would take it); then it is at rest in R.
  // The filter must wait for level_time of steady readings and start exactly at R's tilt (the
  // mean of equal readings: round-off, 1e-12), not at the first reading (0.1 rad off).
  EstimatorParams p;  // the defaults: level_time 0.3 s, level_tolerance 0.02 rad
  AttitudeEstimator f{p};
  const Matrix3d R = rpy_to_matrix(0.02, 0.05, 0);
  const Vector3d gyro(0, 2.0, 0);
  for (int k = 0; k < 25; ++k) {
    const Vector3d a = at_rest(R * rpy_to_matrix(0, -0.1 + 2.0 * kT * k, 0));
    f.update(gyro, &a, Vector3d::Zero(), kT);
    EXPECT_FALSE(f.initialised()) << k;
  }
  const Vector3d a = at_rest(R);
  const int n = static_cast<int>(std::lround(p.level_time / kT));  // readings in the window
  for (int k = 0; k < n; ++k) {
    EXPECT_FALSE(f.initialised()) << k;
    f.update(Vector3d::Zero(), &a, Vector3d::Zero(), kT);
  }
  ASSERT_TRUE(f.initialised());
  EXPECT_LT(tilt_error(f.attitude(), R), 1e-12);
}

TEST(AttitudeEstimator, TheLevellingWindowSpansASwayPeriodSoHalfASwingIsNotRest) {
  // The standing twin sways at 3.8 Hz (balance.ankle_gyro_gain 0.15); every reading here stays
  // within level_tolerance of the others (roll A sin(2π f t), A = 0.009 rad: spread 0.018 < 0.02),
  // so the first window passes for rest. Its mean is A (1 − cos 2π f L) / (2π f L) from level for
  // a window of L: 0.05 A over the default 0.3 s (1.14 periods), 0.72 A over 0.1 s (0.38 of one).
  const double A = 0.009, f_sway = 3.8;
  auto start_error = [&](double level_time) {
    EstimatorParams p;
    p.level_time = level_time;
    AttitudeEstimator e{p};
    for (int k = 0; !e.initialised() && k < 1000; ++k) {
      const double roll = A * std::sin(2 * M_PI * f_sway * kT * k);
      const Vector3d a = at_rest(rpy_to_matrix(roll, 0, 0));
      e.update(Vector3d(2 * M_PI * f_sway * A * std::cos(2 * M_PI * f_sway * kT * k), 0, 0), &a, Vector3d::Zero(), kT);
    }
    EXPECT_TRUE(e.initialised());
    return std::abs(roll_of(e.attitude()));
  };
  const double L = EstimatorParams{}.level_time;
  EXPECT_GE(L * f_sway, 1.0);
  const double mean = A * (1 - std::cos(2 * M_PI * f_sway * L)) / (2 * M_PI * f_sway * L);
  // (the window's mean over n readings against the integral's: within 5 % of A)
  const double at_default = start_error(L);
  EXPECT_NEAR(at_default, mean, 0.05 * A);
  EXPECT_LT(at_default, 0.15 * A);
  EXPECT_GT(start_error(0.1), 0.6 * A);  // half a swing passes for rest
}

TEST(AttitudeEstimator, StartsAfterAlignTimeWhenNeverSteadyFromTheMeanOfTheWait) {
  // Readings that alternate ±0.05 rad in roll (beyond level_tolerance = 0.02 rad) never make a
  // steady window: after align_time from the first reading the filter starts, so a walk never
  // waits for ever. It starts from the mean of the readings of the wait (the twin's sway damping
  // rocks it at ~4 Hz before walking; one reading was then up to 0.06 rad off): exactly the mean's
  // tilt to round-off, here atan(tan 0.05 / (n + 1)) from level (the odd reading out; 1 % above
  // 0.05 / (n + 1) covers the tangent); and, the wait having been the averaging, without the
  // high-gain alignment: the next reading 0.05 rad off turns it at k_P, not align_kp.
  EstimatorParams p;
  AttitudeEstimator f{p};
  const int n = static_cast<int>(std::lround(p.align_time / kT));
  Vector3d sum = Vector3d::Zero();
  for (int k = 0; k <= n; ++k) {
    const Vector3d a = at_rest(rpy_to_matrix(k % 2 == 0 ? 0.05 : -0.05, 0, 0));
    sum += a;
    f.update(Vector3d::Zero(), &a, Vector3d::Zero(), kT);
    ASSERT_EQ(f.initialised(), k == n) << k;
  }
  const double roll0 = roll_of(f.attitude());
  EXPECT_NEAR(roll0, std::atan2(sum.y(), sum.z()), 1e-12);
  EXPECT_LT(std::abs(roll0), 0.05 / (n + 1) * 1.01);
  const Vector3d a = at_rest(rpy_to_matrix(0.05, 0, 0));
  f.update(Vector3d::Zero(), &a, Vector3d::Zero(), kT);
  // One period of (32a) at k_P (the bias is still zero: it is learnt after the turn): a turn of
  // k_P T sin(0.05 − roll0), to round-off (align_kp would turn it 50 times as far).
  EXPECT_NEAR(roll_of(f.attitude()) - roll0, p.kp * kT * std::sin(0.05 - roll0), 1e-15);
}

TEST(AttitudeEstimator, EndsTheAlignmentOnceThePlanAccelerates) {
  // Started 0.05 rad off; 0.2 s aligning at align_kp while the plan accelerates the body 0.15 m/s²
  // forward (below align_accel = 0.2: still aligning); then 0.3 m/s² sideways, which the
  // accelerometer also sees, then at rest again. From the first 0.3 m/s² reading on it is, to the
  // last bit, the filter whose alignment lasted exactly those 0.2 s: the alignment ended for good.
  EstimatorParams p;
  p.level_time = 0;  // the first reading starts it
  p.align_accel = 0.2;
  EstimatorParams q = p;
  q.align_accel = 1e9;  // never ends early...
  q.align_time = 0.2;   // ...but ends after 50 periods
  AttitudeEstimator early{p}, timed{q};
  const Matrix3d R = rpy_to_matrix(0.03, -0.02, 0);
  const Vector3d first = R.transpose() * Vector3d(0, 0.5, kG);
  const Vector3d slow(0.15, 0, 0), planned(0, 0.3, 0);
  const Vector3d creeping = R.transpose() * (slow + Vector3d(0, 0, kG)),
                 moving = R.transpose() * (planned + Vector3d(0, 0, kG));
  const Vector3d still = at_rest(R);
  for (AttitudeEstimator* f : {&early, &timed}) {
    f->update(Vector3d::Zero(), &first, Vector3d::Zero(), kT);
    for (int k = 0; k < 50; ++k) f->update(Vector3d(0, 0, 1e-3), &creeping, slow, kT);
    EXPECT_EQ(f->bias(), Vector3d::Zero());  // aligning: no bias learnt
    for (int k = 0; k < 100; ++k) f->update(Vector3d(1e-3, 0, 0), &moving, planned, kT);
    for (int k = 0; k < 100; ++k) f->update(Vector3d(1e-3, 0, 0), &still, Vector3d::Zero(), kT);
  }
  EXPECT_EQ(early.attitude(), timed.attitude());
  EXPECT_EQ(early.bias(), timed.bias());
  EXPECT_NE(early.bias(), Vector3d::Zero());  // the slow gains learn the bias
  // Against the default filter, still aligning at that time (align_time 1 s).
  EstimatorParams d = p;
  d.align_accel = 1e9;
  AttitudeEstimator aligning{d};
  aligning.update(Vector3d::Zero(), &first, Vector3d::Zero(), kT);
  for (int k = 0; k < 50; ++k) aligning.update(Vector3d(0, 0, 1e-3), &creeping, slow, kT);
  aligning.update(Vector3d(1e-3, 0, 0), &moving, planned, kT);
  EXPECT_EQ(aligning.bias(), Vector3d::Zero());
}

TEST(AttitudeEstimator, UpdateAllocatesNothing) {
  AttitudeEstimator f{test_gains()};
  const Vector3d a = at_rest(rpy_to_matrix(0.1, 0.1, 0));
  const long before = g_allocations.load();
  for (int k = 0; k < 1000; ++k) f.update(Vector3d(0.01, 0.02, 0.03), &a, Vector3d(0.1, 0, 0), kT);
  EXPECT_EQ(g_allocations.load() - before, 0);
}

}  // namespace
}  // namespace flexgait::walking
