// The walk under sensor faults: 10 steps at 1 s/step survive a
// 0.2 s dropout of one F/T sensor, a gyro stuck for 0.1 s and NaN readings of one encoder for
// 0.05 s — no fall, each fault flagged in summary.json and log.csv; a permanent F/T failure is a
// safe stop, not a fall. A walk without faults flags nothing; noise and faults are deterministic.
#include <gtest/gtest.h>

#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/experiments/walk_output.hpp"

namespace flexgait::experiments {
namespace {

using twin::FaultKind;

WalkRunParams ten_steps() {
  WalkRunParams p;
  p.walk.steps = 10;
  p.walk.step_time = 1.0;
  return p;
}

void set_fault(WalkRunParams& p, int sensor, FaultKind kind, double start, double duration) {
  p.plant.faults.sensor[sensor] = {kind, start, duration, 0.0};
}

/// Logged samples flagging `sensor`.
int flagged_samples(const WalkResult& r, int sensor) {
  int n = 0;
  for (const auto& w : r.log) n += (w.sensor_faults >> sensor) & 1U;
  return n;
}

/// The walk survived the fault: all steps, no fall, no safe stop, the fault flagged.
void expect_survived(const WalkResult& r, int sensor) {
  const WalkMetrics& m = r.metrics;
  EXPECT_FALSE(m.fell) << m.fall_text() << " at " << m.fall_time << " s";
  EXPECT_EQ(m.steps_completed, 10);
  EXPECT_FALSE(m.safe_stop) << m.safe_stop_text();
  EXPECT_FALSE(m.safe_stop_reason.has_value());
  EXPECT_EQ(m.mujoco_warnings, 0);
  EXPECT_EQ(m.sensor_fault_episodes, 1);
  ASSERT_EQ(m.sensor_faults.size(), 1U);
  EXPECT_EQ(m.sensor_faults[0].rfind(std::string(humanoid::kSensorNames[sensor]) + ":", 0), 0U) << m.sensor_faults[0];
  EXPECT_GT(flagged_samples(r, sensor), 0);
}

TEST(WalkSensorFaults, NoFaultsNothingFlagged) {
  const WalkResult r = run_walk(ten_steps());
  EXPECT_FALSE(r.metrics.fell);
  EXPECT_EQ(r.metrics.sensor_fault_episodes, 0);
  EXPECT_TRUE(r.metrics.sensor_faults.empty());
  EXPECT_FALSE(r.metrics.safe_stop);
  // The estimator against the twin's true pelvis attitude (measured 0.014 rad rms, 0.019 rad
  // max at 1 s/step): the pelvis rocks with ~1 m/s² that the plan does not hold; 0.03 rad is
  // 1.5× the measured maximum.
  EXPECT_LT(r.metrics.attitude_error_max, 0.03);
}

TEST(WalkSensorFaults, SurvivesAFtDropout) {
  WalkRunParams p = ten_steps();
  set_fault(p, humanoid::kFtLeft, FaultKind::kDropout, 3.4, 0.2);  // across the landing of step 1 at 3.5 s
  const WalkResult r = run_walk(p);
  expect_survived(r, humanoid::kFtLeft);
  // Stale from max_age after the dropout began to its end: 0.2 s − 0.01 s, within a period.
  EXPECT_NEAR(r.metrics.sensor_fault_time, 0.2 - p.health.max_age, 0.0041);
}

TEST(WalkSensorFaults, SurvivesAStuckGyro) {
  WalkRunParams p = ten_steps();
  set_fault(p, humanoid::kGyro, FaultKind::kStuck, 4.8, 0.1);  // mid-swing of step 3
  const WalkResult r = run_walk(p);
  expect_survived(r, humanoid::kGyro);
  // Flagged once stuck_samples readings repeat (the last good and 9 stuck), until the fault ends.
  const double T = p.plant.control_period;
  EXPECT_NEAR(r.metrics.sensor_fault_time, 0.1 - (p.health.stuck_samples - 2) * T, 1.01 * T);
}

TEST(WalkSensorFaults, SurvivesNanEncoderReadings) {
  WalkRunParams p = ten_steps();
  p.plant.faults.encoder_joint = humanoid::kLeftHipRoll;  // the output compensator reads it
  set_fault(p, humanoid::kEncoder, FaultKind::kNan, 5.8, 0.05);
  const WalkResult r = run_walk(p);
  expect_survived(r, humanoid::kEncoder);
  EXPECT_NEAR(r.metrics.sensor_fault_time, 0.05, 0.0041);
  for (const auto& w : r.log) ASSERT_TRUE(std::isfinite(w.encoder[humanoid::kLeftHipRoll])) << "held, t = " << w.t;
  EXPECT_TRUE(std::isfinite(r.metrics.estimate_error_rms));
}

TEST(WalkSensorFaults, PermanentFtFailureIsASafeStop) {
  WalkRunParams p = ten_steps();
  set_fault(p, humanoid::kFtRight, FaultKind::kNan, 4.3, 1e9);
  const WalkResult r = run_walk(p);
  const WalkMetrics& m = r.metrics;
  EXPECT_FALSE(m.fell) << m.fall_text() << " at " << m.fall_time << " s";
  EXPECT_EQ(m.mujoco_warnings, 0);
  ASSERT_TRUE(m.safe_stop);
  EXPECT_NEAR(m.safe_stop_time, 4.3 + p.health.hold_time, 0.0081);
  ASSERT_TRUE(m.safe_stop_reason.has_value());
  EXPECT_EQ(m.safe_stop_reason->sensor, humanoid::kFtRight);
  EXPECT_EQ(m.safe_stop_reason->fault, walking::SignalFault::kNan);
  // At 4.6 s step 3 (4.5–5.5 s) is in double support (lift-off at 4.7 s): it is dropped, so three
  // steps were taken; the robot then stands to the planned end of the walk.
  EXPECT_EQ(m.steps_completed, 3);
  EXPECT_NEAR(m.simulated_time, r.plan.duration, 0.01);
  EXPECT_TRUE(r.log.back().safe_stop);
}

TEST(WalkSensorFaults, ABadFirstSampleOfAnySensorIsHeldAtItsRestValue) {
  // A NaN on the very first sample (no last good value yet) reads as the start pose at rest: the
  // twin never sees a NaN command, and one bad sample is one episode, not a failure.
  for (const int sensor : {humanoid::kGyro, humanoid::kAccel, humanoid::kAhrs, humanoid::kFtLeft, humanoid::kEncoder}) {
    WalkRunParams p = ten_steps();
    p.walk.steps = 2;
    p.estimator.source = sensor == humanoid::kAhrs ? walking::AttitudeSource::kAhrs : p.estimator.source;
    set_fault(p, sensor, FaultKind::kNan, 0.0, 0.001);
    const WalkResult r = run_walk(p);
    const WalkMetrics& m = r.metrics;
    EXPECT_FALSE(m.failure) << humanoid::kSensorNames[sensor] << ": " << m.failure_text();
    EXPECT_EQ(m.outcome(), "walked") << humanoid::kSensorNames[sensor] << ": " << m.fall_text();
    EXPECT_EQ(m.sensor_fault_episodes, 1) << humanoid::kSensorNames[sensor];
  }
}

TEST(WalkSensorFaults, AStuckEncoderIsDetectedAndTheOutputCompensatorReadsItsCommand) {
  // The left knee's encoder freezes at 2.4 s (mid-walk) for good. Its command keeps moving, so
  // the health check flags it stuck; the clean reading is the command, and the output
  // compensator's estimate stays on the link. With health.safe_stop (default) the walk stops
  // safely; without, it walks on.
  WalkRunParams p = ten_steps();
  p.plant.faults.encoder_joint = humanoid::kLeftKnee;
  set_fault(p, humanoid::kEncoder, FaultKind::kStuck, 2.4, 1e9);
  const WalkResult stopped = run_walk(p);
  EXPECT_EQ(stopped.metrics.outcome(), "safe_stop") << stopped.metrics.fall_text();
  ASSERT_TRUE(stopped.metrics.safe_stop_reason.has_value());
  EXPECT_EQ(stopped.metrics.safe_stop_reason->sensor, humanoid::kEncoder);
  EXPECT_EQ(stopped.metrics.safe_stop_reason->fault, walking::SignalFault::kStuck);
  p.health.safe_stop = false;
  const WalkResult walked = run_walk(p);
  const WalkMetrics& m = walked.metrics;
  EXPECT_EQ(m.outcome(), "walked") << m.fall_text();
  EXPECT_GE(m.sensor_fault_episodes, 1);
  // Without the fallback the frozen reading made the estimate error 110 % of the deflection; the
  // command stands in for the motor within the servo's tracking error.
  EXPECT_LT(m.estimate_error_share_of_deflection(), 0.6);
}

TEST(WalkSensorFaults, NoisyFaultyWalksAreDeterministic) {
  WalkRunParams p = ten_steps();
  p.walk.steps = 2;
  p.plant.gyro_noise = 0.01;
  p.plant.accel_noise = 0.1;
  p.plant.encoder_noise = 1e-4;
  p.plant.imu.gyro_bias = 0.002;
  p.plant.imu.gyro_bias_walk = 1e-4;
  p.plant.imu.ahrs_noise = 0.01;
  set_fault(p, humanoid::kAccel, FaultKind::kLatency, 2.0, 0.5);
  p.plant.faults.sensor[humanoid::kAccel].delay = 0.02;
  const WalkResult a = run_walk(p), b = run_walk(p);
  EXPECT_FALSE(a.metrics.fell);
  EXPECT_EQ(a.metrics.sensor_fault_episodes, 1);  // the late accelerometer, stale
  EXPECT_EQ(walk_log_csv(a), walk_log_csv(b));
  EXPECT_EQ(walk_summary_json(a), walk_summary_json(b));
}

}  // namespace
}  // namespace flexgait::experiments
