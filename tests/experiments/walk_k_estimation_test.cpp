// control.k_estimation on the twin: the true gears are k = 1250 Nm/rad, the
// controller's belief starts at 1000; ten steps at 3 s/step with the IMU's AHRS attitude bring
// each identified joint group's estimate within 6 % of the truth (measured: 1197 to 1303, within
// 4.5 %). Off (the default) writes no estimate: no k_est_ columns, no k_estimate in summary.json.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "flexgait/compensation/chain_stiffness_calibration.hpp"
#include "flexgait/compensation/stiffness_estimator.hpp"
#include "flexgait/core/config.hpp"
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

// The field's estimators (the tilt observer), dynamic loads and the identification's attitude from the IMU's delta
// angles (control.k_estimation_attitude_time, pulled to the observer over 10⁵ s): measured 1237 to 1302 at 3 s/step
// (within 4.2 %) and 1193 to 1296 at 1 s/step (within 4.6 %, the modelled stance torques' error). (With one gyro
// sample per period: 1195 to 1222 and 1178 to 1248.) The twin's gyro is ideal.
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
      ::testing::Test::RecordProperty("k_" + std::string(humanoid::kJointNames[j]), std::to_string(r.k_estimate[j]));
      EXPECT_NEAR(r.k_estimate[j], 1250.0, tolerance * 1250.0) << humanoid::kJointNames[j];
    }
}

TEST(WalkKEstimation, TheGyrosAttitudeFindsTheStiffnessWithin5PercentAt3s) {
  expect_gyro_attitude_within(3.0, 0.05);
}
TEST(WalkKEstimation, TheGyrosAttitudeFindsTheStiffnessWithin7PercentAt1s) {
  expect_gyro_attitude_within(1.0, 0.07);
}

// A realistic gyro: a bias of 0.001 rad/s on each axis and a bias walk of 1e-5 rad/s/√s. The gyro is
// calibrated standing still (control.k_estimation_gyro_rest: 1 s of a 5 s start stance; the bias is the gyro's
// turn less the legs'), the F/T low-pass is 0.01 s (its lag biases the torques' changes). At 3 s/step each
// stance's tilt offset is estimated (control.k_estimation_stance_offset: the drift cancels). Measured with the IMU's
// delta angles: 1252 to 1319 at 3 s/step (within 5.5 %), 1250 to 1315 at 1 s/step without the offsets (within
// 5.2 %, the pitch groups: the modelled torques' bias). (With one gyro sample per period, aliased: 1212 to 1297 and
// 1253 to 1277, the sampled rate's drift partly cancelling that bias.) Before (the gyro alone from the start): 784 to
// 9112 at 3 s, 977 to 1845 at 1 s.
/// The walk with the drifting gyro, its estimate by the tilt observer, the dynamic loads and a short F/T low-pass (the
/// torques' changes right); `estimation`: with the identification as above (the gyro calibrated at rest, its
/// attitude pulled over 10⁵ s), else the belief kept.
WalkRunParams drifting_gyro_walk(double step_time, bool estimation, bool stance_offset) {
  WalkRunParams p = ten_steps(step_time);
  p.walk.start_time = 5.0;
  p.estimator.source = walking::AttitudeSource::kTilt;
  p.plant.imu.gyro_bias = 0.001;
  p.plant.imu.gyro_bias_walk = 1e-5;
  p.control.load_model = compensation::LoadModel::kDynamic;
  p.control.load_filter_time = 0.01;
  if (!estimation) return p;
  p.control.k_estimation = compensation::KEstimation::kOn;
  p.control.k_estimation_attitude_time = 1e5;
  p.control.k_estimation_gyro_rest = 1.0;
  p.control.k_estimation_stance_offset = stance_offset;
  return p;
}

/// The walk r did not fall and each identified joint is within `tolerance` of the twin's 1250 Nm/rad.
void expect_walked_within(const WalkResult& r, double tolerance) {
  ASSERT_FALSE(r.metrics.fell) << r.metrics.fall_text();
  for (int j = 0; j < humanoid::kJoints; ++j) {
    if (!r.k_identified[j]) continue;
    EXPECT_NEAR(r.k_estimate[j], 1250.0, tolerance * 1250.0) << humanoid::kJointNames[j];
  }
}

TEST(WalkKEstimation, ACalibratedDriftingGyroFindsTheStiffnessWithin7PercentAt3s) {
  expect_walked_within(run_walk(drifting_gyro_walk(3.0, true, true)), 0.07);
}
TEST(WalkKEstimation, ACalibratedDriftingGyroFindsTheStiffnessWithin7PercentAt1s) {
  expect_walked_within(run_walk(drifting_gyro_walk(1.0, true, false)), 0.07);
}

// The measured torques (control.k_estimation_torque measured) under the drifting gyro above, with the stance offsets:
// at 3 s/step the right leg's pitch group used to run onto its bound, the offsets beside it diverged, and the
// confident wrong estimate toppled the robot. Held at the bound with the correlated states projected, every group
// ends within 8.0 % (measured; the right pitch group) and the peak pelvis roll, 0.0067 rad, is below the wrong
// belief's, 0.0117 rad, this walk without estimation. Bounds: 10 % and the belief's roll.
TEST(WalkKEstimation, MeasuredTorquesWithADriftingGyroAndStanceOffsetsStayBelowTheBeliefsRollAt3s) {
  const WalkResult belief = run_walk(drifting_gyro_walk(3.0, false, false));
  WalkRunParams p = drifting_gyro_walk(3.0, true, true);
  p.control.k_estimation_torque = compensation::KTorque::kMeasured;
  const WalkResult r = run_walk(p);
  expect_walked_within(r, 0.10);
  EXPECT_LT(r.metrics.pelvis_roll_error_max, belief.metrics.pelvis_roll_error_max);
}

/// `humanoid walk`'s parameters for these keys (its defaults resolved as on the command line).
WalkRunParams walk_with(const std::vector<std::string>& keys) {
  return walk_run_from_config(resolve_config(walk_run_schema(), std::nullopt, keys));
}

/// Each identified joint of r within `tolerance` of k and confident (its relative std at most the threshold, so the
/// compensators use it); returns the worst relative error.
double expect_each_identified_within(const WalkRunParams& p, const WalkResult& r, double k, double tolerance) {
  double worst = 0;
  int identified = 0;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    if (!r.k_identified[j]) continue;
    ++identified;
    worst = std::max(worst, std::abs(r.k_estimate[j] / k - 1));
    EXPECT_NEAR(r.k_estimate[j], k, tolerance * k) << humanoid::kJointNames[j];
    EXPECT_GT(r.k_relative_std[j], 0.0) << humanoid::kJointNames[j];
    EXPECT_LE(r.k_relative_std[j], p.control.k_estimation_confidence) << humanoid::kJointNames[j];
  }
  EXPECT_EQ(identified, 10);
  return worst;
}

// The default keys of `humanoid walk` (the default compensation case, the identification's attitude the IMU's over
// the walk, the regressor through the gears' lag) with control.k_estimation on: 20 steps at 1 s/step on gears of
// 870 Nm/rad, believed 1000. Measured: the roll groups 1.6 and 1.0 % low, the pitch groups 5.2 and 4.6 % high (the
// modelled torques' bias; docs/guide/compensation.md's table). Bound: 6 %.
TEST(WalkKEstimation, TheDefaultKeysFindEachJointWithin6PercentIn20StepsAt1s) {
  const WalkRunParams p = walk_with(
      {"walk.steps=20", "walk.step_time=1.0", "plant.k_joint=870", "control.k_joint=1000", "control.k_estimation=on"});
  const WalkResult r = run_walk(p);
  ASSERT_FALSE(r.metrics.fell) << r.metrics.fall_text();
  expect_each_identified_within(p, r, 870.0, 0.06);
}

// control.k_estimation_torque measured: the servos' torque from their current less the rotors' inertia, the same
// walk. The modelled torques' bias gone, each group is found within 0.4 % (measured; at 3 s/step and k 1180, 1230
// within 0.7 %, docs/guide/compensation.md). Bound: 1.5 %.
TEST(WalkKEstimation, MeasuredTorquesFindEachGroupWithin1Point5PercentAt1s) {
  const WalkRunParams p = walk_with({"walk.steps=20", "walk.step_time=1.0", "plant.k_joint=870", "control.k_joint=1000",
                                     "control.k_estimation=on", "control.k_estimation_torque=measured"});
  const WalkResult r = run_walk(p);
  ASSERT_FALSE(r.metrics.fell) << r.metrics.fall_text();
  ::testing::Test::RecordProperty("worst", std::to_string(expect_each_identified_within(p, r, 870.0, 0.015)));
}

// control.k_estimation_per_joint: one 1/k per joint from the measured torques, no forgetting over the walk (the
// gears' stiffness is constant), the twin's soles believed (configs/calibrate-stiffness.yaml's values, against the
// ground's torque about each sole's centre). `keys` with the pace's and the gears'.
WalkRunParams per_joint_walk(std::vector<std::string> keys) {
  for (const char* key : {"control.k_joint=1000", "control.k_estimation=on", "control.k_estimation_torque=measured",
                          "control.k_estimation_per_joint=true", "control.k_estimation_memory=1e6",
                          "control.sole_stiffness_roll=25600", "control.sole_stiffness_pitch=56200"})
    keys.emplace_back(key);
  return walk_with(keys);
}

// 20 steps at 1 s/step on gears of 1230 Nm/rad, believed 1000. Measured: every joint within 4.3 % (the left hip
// pitch), relative std 0.3–1.7 %. Bound: 5 %, the issue's. Asking for it with the modelled torques is refused
// (exit 2): ill-posed.
TEST(WalkKEstimation, PerJointMeasuredTorquesFindEachJointWithin5PercentIn20StepsAt1s) {
  const WalkRunParams p = per_joint_walk({"walk.steps=20", "walk.step_time=1.0", "plant.k_joint=1230"});
  const WalkResult r = run_walk(p);
  ASSERT_FALSE(r.metrics.fell) << r.metrics.fall_text();
  ::testing::Test::RecordProperty("worst", std::to_string(expect_each_identified_within(p, r, 1230.0, 0.05)));
  EXPECT_THROW(walk_with({"control.k_estimation=on", "control.k_estimation_per_joint=true"}), ConfigError);
}

// 10 steps at 3 s/step on gears of 870 Nm/rad, believed 1000: the slow stance moves the ankle pitches' torques least.
// Measured: every joint within 4.4 % (the right ankle pitch), relative std 0.2–2.4 %. Bound: 5 %, the issue's.
TEST(WalkKEstimation, PerJointMeasuredTorquesFindEachJointWithin5PercentIn10StepsAt3s) {
  const WalkRunParams p = per_joint_walk({"walk.steps=10", "walk.step_time=3.0", "plant.k_joint=870"});
  const WalkResult r = run_walk(p);
  ASSERT_FALSE(r.metrics.fell) << r.metrics.fall_text();
  ::testing::Test::RecordProperty("worst", std::to_string(expect_each_identified_within(p, r, 870.0, 0.05)));
}

// control.k_estimation = calibrate (chain_stiffness_calibration.hpp) on the twin, as configs/calibrate-stiffness.yaml
// without the walk: 180 s in two passes, the gears' damping and the soles' stiffness believed as the twin's; the
// belief of k starts at 1000. (That the belief holds until the calibration ends: chain_stiffness_calibration_test.)
// `scale(side, joint in leg)` gives the twin's factor on 1250 Nm/rad.
constexpr double kSoleStiffnessRoll = 25600.0;   // configs/calibrate-stiffness.yaml [Nm/rad]
constexpr double kSoleStiffnessPitch = 56200.0;  // [Nm/rad]

WalkRunParams calibration_stance(double time) {
  WalkRunParams p;
  p.walk.steps = 0;
  p.walk.calibration.time = time;
  p.walk.start_time = time + 4.0;
  p.walk.end_time = 0.5;
  p.plant.k_joint = 1250.0;
  p.control.k_joint = 1000.0;
  p.control.k_estimation = compensation::KEstimation::kCalibrate;
  p.control.k_calibration_passes = 2;
  p.control.gear_damping = p.plant.gear_damping;
  p.control.sole_stiffness_roll = kSoleStiffnessRoll;
  p.control.sole_stiffness_pitch = kSoleStiffnessPitch;
  p.control.load_model = compensation::LoadModel::kMeasured;
  p.control.load_filter_time = 0.01;
  return p;
}

struct Calibrated {
  WalkResult result;
  humanoid::JointVector truth;  ///< the twin's k [Nm/rad]
};

template <class Scale>
Calibrated calibrate(Scale scale) {
  WalkRunParams p = calibration_stance(180.0);
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
// issue's target, each joint within 10 %. Measured: 5.0 % (the right ankle pitch), the hips and knees 1.1 %.
TEST(WalkKEstimation, TheCalibrationStanceFindsEachJointWithin10Percent) {
  expect_each_joint_within(calibrate([](int, int i) { return (i == 1 || i == 3) ? 1.2 : 0.8; }), 0.10, 0.10);
}

// The left leg scaled as the issue's, the right the reverse, so the two ankle rolls differ by 50 %: the
// hardest of the README's rows. Measured: 9.0 % (the right ankle roll, 1500 Nm/rad), the hips and knees 1.9 %.
// Bounds: 12 % and 5 %. Before the soles' tilt was taken out and the second pass: 16.8 %; the first motion
// design (soles' rolls 0.003 rad near a by-product of two other components) put the left ankle roll at its
// bound, 900 % off.
TEST(WalkKEstimation, TheCalibrationStanceSeparatesLeftAndRightAnkles) {
  const Calibrated c = calibrate([](int side, int i) {
    const double issue = (i == 1 || i == 3) ? 1.2 : 0.8;
    return side == 0 ? issue : 2.0 - issue;
  });
  expect_each_joint_within(c, 0.05, 0.12);
}

// The twin's soles tilt in their contacts (MuJoCo's soft contact) as control.sole_stiffness_* in
// configs/calibrate-stiffness.yaml say: over the calibration stance (uniform gears), the soles' relative
// tilt through the true link angles, fitted by least squares to the soles' tilts under the ground's torques about
// their centres, from the F/T sensors (sole_tilt, through the chain's regressor: a unit compliance about each axis
// in turn), plus a constant. Samples: both soles firm by their F/T sensors, as the calibration takes them. Measured
// here (40 s): 25.6 and 56.2 kNm/rad. Asserted: within 10 % of the config's.
TEST(WalkKEstimation, TheTwinsSolesTiltAsTheConfigSays) {
  WalkRunParams p = calibration_stance(40.0);
  const walking::RobotModel model = walk_controller_model(p);
  compensation::CompensationParams rigid_soles = p.control;  // (the regressor's y as the chain sees it)
  rigid_soles.sole_stiffness_roll = rigid_soles.sole_stiffness_pitch = 0.0;
  compensation::ChainStiffnessCalibration chain(model, rigid_soles, p.plant.control_period, 0.0, 1.0);
  compensation::CompensationParams unit_soles = p.control;  // (a sole's tilt per unit compliance: −M)
  unit_soles.sole_stiffness_roll = unit_soles.sole_stiffness_pitch = 1.0;
  // Normal equations of y = [h_roll h_pitch I] (1/k_roll, 1/k_pitch, y₀), y the relative tilt (roll, pitch).
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  Eigen::Vector4d b = Eigen::Vector4d::Zero();
  const double begin = p.walk.calibration.start + p.walk.calibration.ramp, end = p.walk.calibration.end() - 1.0;
  struct Observer final : loop::LoopObserver {
    std::function<void(const twin::HumanoidPlant&)> f;
    void observe(const loop::LoopStep& step) override { f(step.plant); }
  } observer;
  observer.f = [&](const twin::HumanoidPlant& plant) {
    const twin::GroundTruth g = plant.truth();
    if (g.t < begin || g.t > end) return;
    const humanoid::SensorReadings& s = plant.sensors();
    // Each axis's column: the soles' tilts with a unit compliance about that axis alone, through the chain's y.
    std::array<std::array<walking::Vector3d, 2>, 2> tilts;  // [axis][side]
    for (int side = 0; side < 2; ++side) {
      const walking::FootContact contact =
          compensation::sole_contact(model, s.ft[side], walking::Matrix3d::Identity(), side);
      if (!compensation::firm_support(model, contact, side, 0.05)) return;
      const walking::Vector3d unit = compensation::sole_tilt(contact, unit_soles);
      tilts[0][side] = walking::Vector3d(unit.x(), 0, 0);
      tilts[1][side] = walking::Vector3d(0, unit.y(), 0);
    }
    Eigen::Vector2d y, y_roll, y_pitch;
    chain.regressor(g.link_angle, {}, y);
    chain.regressor(g.link_angle, {}, tilts[0], y_roll);  // y − the roll column
    chain.regressor(g.link_angle, {}, tilts[1], y_pitch);
    for (int r = 0; r < 2; ++r) {
      const Eigen::Vector4d h(y[r] - y_roll[r], y[r] - y_pitch[r], r == 0, r == 1);
      A += h * h.transpose();
      b += h * y[r];
    }
  };
  run_walk(p, {}, [&](WalkLoop& w) { w.loop->attach(observer); });
  const Eigen::Vector4d x = A.ldlt().solve(b);
  ::testing::Test::RecordProperty("sole_stiffness_roll", std::to_string(1.0 / x[0]));
  ::testing::Test::RecordProperty("sole_stiffness_pitch", std::to_string(1.0 / x[1]));
  EXPECT_NEAR(1.0 / x[0], kSoleStiffnessRoll, 0.10 * kSoleStiffnessRoll);
  EXPECT_NEAR(1.0 / x[1], kSoleStiffnessPitch, 0.10 * kSoleStiffnessPitch);
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
