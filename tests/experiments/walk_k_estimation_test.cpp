// control.k_estimation (issue 20) on the twin: the true gears are k = 1250 Nm/rad, the
// controller's belief starts at 1000; ten steps at 3 s/step with the IMU's AHRS attitude bring
// each identified joint group's estimate within 6 % of the truth (measured: 1194 to 1302, within
// 4.5 %). Off (the default) writes no estimate: no k_est_ columns, no k_estimate in summary.json.
#include <gtest/gtest.h>

#include <string>

#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/experiments/walk_output.hpp"

namespace flexgait::experiments {
namespace {

WalkRunParams ten_steps(double step_time) {
  WalkRunParams p;
  p.walk.steps = 10;
  p.walk.step_time = step_time;
  p.plant.k_joint = 1250.0;
  p.control.k_joint = 1000.0;
  p.estimator.source = walking::AttitudeSource::kAhrs;
  return p;
}

TEST(WalkKEstimation, TenStepsAt3sFindTheTrueStiffnessWithin6Percent) {
  WalkRunParams p = ten_steps(3.0);
  p.control.k_estimation = compensation::KEstimation::kOn;
  const WalkResult r = run_walk(p);
  ASSERT_FALSE(r.metrics.fell) << r.metrics.fall_text();
  ASSERT_TRUE(r.k_estimation);
  int identified = 0;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    if (!r.k_identified[j]) continue;
    ++identified;
    ::testing::Test::RecordProperty("k_" + std::string(humanoid::kJointNames[j]), std::to_string(r.k_estimate[j]));
    EXPECT_NEAR(r.k_estimate[j], 1250.0, 0.06 * 1250.0) << humanoid::kJointNames[j];
  }
  EXPECT_EQ(identified, 10);  // the leg roll and pitch joints; the hip yaws are not observed
  const std::string summary = walk_summary_json(r), joints = walk_joints_csv(r);
  EXPECT_NE(summary.find("\"k_estimate_mean\""), std::string::npos);
  EXPECT_NE(joints.find("k_est_l_knee"), std::string::npos);
}

// The field's estimators (the tilt observer), dynamic loads and the identification's attitude from the gyro
// (control.k_estimation_attitude_time, pulled to the observer over 10⁵ s): measured 1195 to 1222 at 3 s/step
// (within 4.4 %; 1154 to 1331 with the observer's attitude itself) and 1178 to 1248 at 1 s/step (within 5.7 %,
// the modelled stance torques' error; 1178 to 1471). The twin's gyro is ideal.
void expect_gyro_attitude_within(double step_time, double tolerance) {
  WalkRunParams p = ten_steps(step_time);
  p.estimator.source = walking::AttitudeSource::kTilt;
  p.control.load_model = compensation::LoadModel::kDynamic;
  p.control.k_estimation = compensation::KEstimation::kOn;
  p.control.k_estimation_attitude_time = 1e5;
  const WalkResult r = run_walk(p);
  ASSERT_FALSE(r.metrics.fell) << r.metrics.fall_text();
  for (int j = 0; j < humanoid::kJoints; ++j)
    if (r.k_identified[j]) {
      EXPECT_NEAR(r.k_estimate[j], 1250.0, tolerance * 1250.0) << humanoid::kJointNames[j];
    }
}

TEST(WalkKEstimation, TheGyrosAttitudeFindsTheStiffnessWithin5PercentAt3s) { expect_gyro_attitude_within(3.0, 0.05); }
TEST(WalkKEstimation, TheGyrosAttitudeFindsTheStiffnessWithin7PercentAt1s) { expect_gyro_attitude_within(1.0, 0.07); }

// A realistic gyro (issue 20): a bias of 0.001 rad/s on each axis and a bias walk of 1e-5 rad/s/√s. The gyro is
// calibrated standing still (control.k_estimation_gyro_rest: 1 s of a 5 s start stance; the bias is the gyro's
// turn less the legs'), the F/T low-pass is 0.01 s (its lag biases the torques' changes). At 3 s/step each
// stance's tilt offset is estimated (control.k_estimation_stance_offset: the drift cancels): measured 1212 to 1297
// (within 3.8 %; 3.9–4.0 % with noise seeds 2 to 4; without the offsets 4.9 %, 7.7 % with an ideal gyro). At
// 1 s/step without the offsets (with them 25 %: the modelled torques' changes within a stance are off): 1253 to
// 1277 (within 2.2 %; 1.0–2.7 % with seeds 2 to 4). Before (the gyro alone from the start): 784 to 9112 at 3 s,
// 977 to 1845 at 1 s.
void expect_drifting_gyro_within(double step_time, bool stance_offset, double tolerance) {
  WalkRunParams p = ten_steps(step_time);
  p.walk.start_time = 5.0;
  p.estimator.source = walking::AttitudeSource::kTilt;
  p.plant.imu.gyro_bias = 0.001;
  p.plant.imu.gyro_bias_walk = 1e-5;
  p.control.load_model = compensation::LoadModel::kDynamic;
  p.control.load_filter_time = 0.01;
  p.control.k_estimation = compensation::KEstimation::kOn;
  p.control.k_estimation_attitude_time = 1e5;
  p.control.k_estimation_gyro_rest = 1.0;
  p.control.k_estimation_stance_offset = stance_offset;
  const WalkResult r = run_walk(p);
  ASSERT_FALSE(r.metrics.fell) << r.metrics.fall_text();
  for (int j = 0; j < humanoid::kJoints; ++j)
    if (r.k_identified[j]) {
      EXPECT_NEAR(r.k_estimate[j], 1250.0, tolerance * 1250.0) << humanoid::kJointNames[j];
    }
}

TEST(WalkKEstimation, ACalibratedDriftingGyroFindsTheStiffnessWithin5PercentAt3s) {
  expect_drifting_gyro_within(3.0, true, 0.05);
}
TEST(WalkKEstimation, ACalibratedDriftingGyroFindsTheStiffnessWithin5PercentAt1s) {
  expect_drifting_gyro_within(1.0, false, 0.05);
}

// control.k_estimation = calibrate (chain_stiffness_calibration.hpp) on the twin: the 90 s calibration of
// configs/calibrate-stiffness.yaml, the true stiffness 1250 Nm/rad × 1.2 at the hip rolls and knees and × 0.8
// at the hip pitches, ankle pitches and ankle rolls; the belief starts at 1000. Measured (README): the hips and
// knees within 5.7 %, the ankles within 8.7 % (the right ankle roll: its torque moves least in double support).
// The bounds: 8 % and 12 %. (That the belief holds until the calibration ends: chain_stiffness_calibration_test.)
// The calibration stance (configs/calibrate-stiffness.yaml without the walk) on a twin whose leg joints'
// gears are scaled per joint; `scale(side, joint in leg)` gives the factor on 1250 Nm/rad.
struct Calibrated {
  WalkResult result;
  humanoid::JointVector truth;  ///< the twin's k [Nm/rad]
};

template <class Scale>
Calibrated calibrate(Scale scale) {
  WalkRunParams p;
  p.walk.steps = 0;
  p.walk.calibration.time = 90.0;
  p.walk.start_time = 94.0;
  p.walk.end_time = 0.5;
  p.plant.k_joint = 1250.0;
  p.control.k_joint = 1000.0;
  p.control.k_estimation = compensation::KEstimation::kCalibrate;
  p.control.load_model = compensation::LoadModel::kMeasured;
  p.control.load_filter_time = 0.01;
  for (int side = 0; side < 2; ++side)
    for (int i = 1; i < 6; ++i) p.plant.k_scale[humanoid::leg_first_joint(side) + i] = scale(side, i);
  Calibrated c{run_walk(p), {}};
  EXPECT_FALSE(c.result.metrics.fell) << c.result.metrics.fall_text();
  EXPECT_TRUE(c.result.k_estimation);
  for (int j = 0; j < humanoid::kJoints; ++j) c.truth[j] = p.plant.k_joint * p.plant.k_scale[j];
  return c;
}

// Each identified joint's estimate within `hips_knees` or `ankles` (relative) of the twin's k; all ten
// roll and pitch joints identified.
void expect_each_joint_within(const Calibrated& c, double hips_knees, double ankles) {
  const WalkResult& r = c.result;
  int identified = 0;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    if (!r.k_identified[j]) continue;
    ++identified;
    const double truth = c.truth[j];
    const bool ankle = (j - humanoid::leg_first_joint(j < humanoid::kRightHipYaw ? 0 : 1)) >= 4;
    ::testing::Test::RecordProperty("k_" + std::string(humanoid::kJointNames[j]), std::to_string(r.k_estimate[j]));
    EXPECT_NEAR(r.k_estimate[j], truth, (ankle ? ankles : hips_knees) * truth) << humanoid::kJointNames[j];
  }
  EXPECT_EQ(identified, 10);
}

// The issue's scaling (hip roll and knee 1.2; hip pitch, ankle pitch and roll 0.8) on both legs: the
// issue's target, each joint within 10 %. Measured: 5.5 % (left knee), the ankles 2.5 %.
TEST(WalkKEstimation, TheCalibrationStanceFindsEachJointWithin10Percent) {
  expect_each_joint_within(calibrate([](int, int i) { return (i == 1 || i == 3) ? 1.2 : 0.8; }), 0.10, 0.10);
}

// The left leg scaled as the issue's, the right the reverse, so the two ankle rolls differ by 50 %. The
// chain sees an ankle's compliance through the sole resting on the floor, and MuJoCo's soft contact lets
// the sole rock (about 1/13 of the gear's compliance here; README): the ankles are held to 25 %, the hips
// and knees to 8 %. Measured: 5.3 % and 16.8 % (right ankle roll). The first motion design (soles' rolls
// 0.003 rad near a by-product of two other components) put the left ankle roll at its bound, 900 % off.
TEST(WalkKEstimation, TheCalibrationStanceSeparatesLeftAndRightAnkles) {
  const Calibrated c = calibrate([](int side, int i) {
    const double issue = (i == 1 || i == 3) ? 1.2 : 0.8;
    return side == 0 ? issue : 2.0 - issue;
  });
  expect_each_joint_within(c, 0.08, 0.25);
}

TEST(WalkKEstimation, OffWritesNoEstimate) {
  WalkRunParams p = ten_steps(3.0);
  p.walk.steps = 1;
  const WalkResult r = run_walk(p);
  EXPECT_FALSE(r.k_estimation);
  EXPECT_EQ(walk_summary_json(r).find("k_estimate"), std::string::npos);
  EXPECT_EQ(walk_joints_csv(r).find("k_est_"), std::string::npos);
}

}  // namespace
}  // namespace flexgait::experiments
