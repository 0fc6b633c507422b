// The sensor health check on synthetic readings: each fault kind (NaN, stale, stuck) is detected
// and flagged, the last good value is held, a fault longer than the hold time is a latched
// failure, a short one is not; encoders repeat legitimately; checking allocates nothing.
#include "flexgait/walking/sensor_health.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "../support/count_allocations.hpp"

using flexgait::testing::g_allocations;

namespace flexgait::walking {
namespace {

constexpr double kT = 0.004;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

/// Live readings at period k: every value moves (as noise and motion make them), fresh stamps.
humanoid::SensorReadings live(int k) {
  humanoid::SensorReadings s;
  const double t = k * kT, w = 1e-3 * std::sin(0.1 * k);
  s.t = t;
  for (int j = 0; j < humanoid::kJoints; ++j) s.encoder[j] = 0.1 * j;  // quantised: constant at rest
  s.encoder_stamp.fill(t);
  for (auto& ft : s.ft) {
    ft.force = {w, -w, -250 + w};
    ft.torque = {w, 2 * w, -w};
    ft.stamp = t;
  }
  s.imu.gyro = {w, -w, 0.5 * w};
  s.imu.accel = {w, w, 9.81 + w};
  s.imu.quat = {1, w, 0, 0};
  s.imu.gyro_stamp = s.imu.accel_stamp = s.imu.quat_stamp = t;
  return s;
}

struct Runner {
  SensorHealth health{HealthParams{}, kT};
  unsigned seen = 0;  ///< flags over the run
  /// Checks live readings for k in [from, to), `fault` altering them.
  template <class Fault>
  void go(int from, int to, Fault fault) {
    for (int k = from; k < to; ++k) {
      humanoid::SensorReadings s = live(k);
      fault(s, k);
      health.check(s, k * kT);
      seen |= health.flags();
    }
  }
};

TEST(SensorHealth, HealthyReadingsAreNeverFlagged) {
  Runner r;
  r.go(0, 5000, [](humanoid::SensorReadings&, int) {});
  EXPECT_EQ(r.seen, 0U);
  for (int i = 0; i < humanoid::kSensors; ++i) {
    EXPECT_EQ(r.health.episodes(i), 0);
    EXPECT_FALSE(r.health.failed(i));
  }
}

TEST(SensorHealth, NanIsFlaggedAndTheLastGoodValueHeld) {
  Runner r;
  r.go(0, 100, [](humanoid::SensorReadings&, int) {});
  const double last_good = live(99).encoder[humanoid::kLeftKnee];
  // NaN on one encoder for 0.05 s (12 periods): flagged at once, held, not a failure.
  r.go(100, 112, [&](humanoid::SensorReadings& s, int) {
    s.encoder[humanoid::kLeftKnee] = kNan;
    EXPECT_EQ(r.health.clean().encoder[humanoid::kLeftKnee], r.health.clean().encoder[humanoid::kLeftKnee]);
  });
  EXPECT_TRUE(r.health.bad(humanoid::kEncoder));
  EXPECT_EQ(r.health.fault(humanoid::kEncoder), SignalFault::kNan);
  EXPECT_EQ(r.health.clean().encoder[humanoid::kLeftKnee], last_good);
  r.go(112, 200, [](humanoid::SensorReadings&, int) {});
  EXPECT_FALSE(r.health.bad(humanoid::kEncoder));
  EXPECT_FALSE(r.health.failed(humanoid::kEncoder));
  EXPECT_EQ(r.health.episodes(humanoid::kEncoder), 1);
  EXPECT_NEAR(r.health.bad_time(humanoid::kEncoder), 12 * kT, 1e-12);
}

TEST(SensorHealth, ADropoutIsStaleOnceOlderThanMaxAge) {
  // A dropped F/T sensor repeats its last sample and stamp: stale once the stamp is older than
  // max_age (0.01 s: the third period), held at the last good value, clear when samples return.
  Runner r;
  r.go(0, 100, [](humanoid::SensorReadings&, int) {});
  const humanoid::SensorReadings frozen = live(99);
  int first_flag = -1;
  r.go(100, 150, [&](humanoid::SensorReadings& s, int k) {  // 0.2 s
    s.ft[0] = frozen.ft[0];
    if (first_flag < 0 && r.health.bad(humanoid::kFtLeft)) first_flag = k;
  });
  EXPECT_EQ(first_flag, 103);  // flag read after the check of k = 102: age 0.012 s > 0.01 s
  EXPECT_EQ(r.health.fault(humanoid::kFtLeft), SignalFault::kStale);
  EXPECT_EQ(r.health.clean().ft[0].force, frozen.ft[0].force);
  EXPECT_FALSE(r.health.bad(humanoid::kFtRight));
  r.go(150, 200, [](humanoid::SensorReadings&, int) {});
  EXPECT_FALSE(r.health.bad(humanoid::kFtLeft));
  EXPECT_FALSE(r.health.failed(humanoid::kFtLeft));  // 0.19 s bad < hold_time 0.3 s
  EXPECT_EQ(r.health.episodes(humanoid::kFtLeft), 1);
}

TEST(SensorHealth, AStuckGyroIsFlaggedAfterStuckSamples) {
  // Frozen values with fresh stamps: stuck when stuck_samples (10) readings are identical.
  Runner r;
  r.go(0, 100, [](humanoid::SensorReadings&, int) {});
  const auto frozen = live(99).imu.gyro;
  int first_flag = -1;
  r.go(100, 125, [&](humanoid::SensorReadings& s, int k) {  // 0.1 s
    s.imu.gyro = frozen;
    if (first_flag < 0 && r.health.bad(humanoid::kGyro)) first_flag = k;
  });
  // Readings 99..108 are the same ten: flagged at the check of k = 108.
  EXPECT_EQ(first_flag, 109);
  EXPECT_EQ(r.health.fault(humanoid::kGyro), SignalFault::kStuck);
  r.go(125, 150, [](humanoid::SensorReadings&, int) {});
  EXPECT_FALSE(r.health.bad(humanoid::kGyro));
  EXPECT_FALSE(r.health.failed(humanoid::kGyro));
}

// A massless foot in swing: its F/T reads exactly zero, repeated, for the whole swing (0.4 s, more
// than stuck_samples and hold_time) and is never flagged, nor after the planned landing (a late
// landing), for up to hold_time (0.3 s = 75 periods); the same zero after that is stuck
// stuck_samples (10) readings later. A landing that touches (a nonzero reading) and bounces off the
// floor again has the same hold_time; a frozen nonzero reading in swing counts at once.
TEST(SensorHealth, AnUnloadedFootReadingExactlyZeroInSwingIsNotStuck) {
  Runner r;
  r.go(0, 100, [](humanoid::SensorReadings&, int) {});
  const auto zero = [](humanoid::SensorReadings& s, int) {
    s.ft[0].force = {0, 0, -0.0};  // (−0 is the same unloaded value)
    s.ft[0].torque = {0, 0, 0};
  };
  r.health.set_unloaded({true, false});
  r.go(100, 200, zero);
  EXPECT_EQ(r.seen, 0U);
  r.health.set_unloaded({false, false});  // planned landing at k = 200; the foot still in the air
  r.go(200, 270, zero);
  EXPECT_EQ(r.seen, 0U);
  int first_flag = -1;
  r.go(270, 300, [&](humanoid::SensorReadings& s, int k) {
    zero(s, k);
    if (first_flag < 0 && r.health.bad(humanoid::kFtLeft)) first_flag = k;
  });
  // The last exempt check is k = 274 (t − 0.796 s ≤ 0.3 s, to rounding 273 or 274), then ten repeats.
  EXPECT_GE(first_flag, 283);
  EXPECT_LE(first_flag, 285);
  EXPECT_EQ(r.health.fault(humanoid::kFtLeft), SignalFault::kStuck);
  // Touched (loaded readings), then in the air again (a bounce) or frozen at zero: the same exemption
  // from the planned landing, then stuck ten readings later.
  Runner landed;
  landed.health.set_unloaded({true, false});
  landed.go(0, 100, zero);
  landed.health.set_unloaded({false, false});
  landed.go(100, 110, [](humanoid::SensorReadings&, int) {});
  first_flag = -1;
  landed.go(110, 200, [&](humanoid::SensorReadings& s, int k) {
    zero(s, k);
    if (first_flag < 0 && landed.health.bad(humanoid::kFtLeft)) first_flag = k;
  });
  // The last exempt check is k = 174 (t − 0.396 s ≤ 0.3 s, to rounding 173 or 174), then ten repeats.
  EXPECT_GE(first_flag, 183);
  EXPECT_LE(first_flag, 185);
  // A frozen nonzero reading while the foot swings is stuck.
  Runner frozen;
  frozen.go(0, 100, [](humanoid::SensorReadings&, int) {});
  frozen.health.set_unloaded({true, true});
  const auto held = live(99).ft[1];
  frozen.go(100, 120, [&](humanoid::SensorReadings& s, int) {
    s.ft[1].force = held.force;
    s.ft[1].torque = held.torque;
  });
  EXPECT_EQ(frozen.health.fault(humanoid::kFtRight), SignalFault::kStuck);
}

TEST(SensorHealth, LatencyBeyondMaxAgeIsStale) {
  Runner r;
  r.go(0, 100, [](humanoid::SensorReadings&, int) {});
  r.go(100, 150, [](humanoid::SensorReadings& s, int k) { s.imu.accel_stamp = (k - 5) * kT; });  // 0.02 s late
  EXPECT_EQ(r.health.fault(humanoid::kAccel), SignalFault::kStale);
  r.go(150, 200, [](humanoid::SensorReadings& s, int k) { s.imu.accel_stamp = (k - 2) * kT; });  // 0.008 s: tolerated
  EXPECT_FALSE(r.health.bad(humanoid::kAccel));
}

TEST(SensorHealth, BadBeyondTheHoldTimeIsALatchedFailure) {
  Runner r;
  r.go(0, 100, [](humanoid::SensorReadings&, int) {});
  const humanoid::SensorReadings frozen = live(99);
  r.go(100, 100 + 74, [&](humanoid::SensorReadings& s, int) { s.ft[1] = frozen.ft[1]; });
  EXPECT_FALSE(r.health.failed(humanoid::kFtRight));  // bad from k = 103: 0.28 s so far
  r.go(174, 200, [&](humanoid::SensorReadings& s, int) { s.ft[1] = frozen.ft[1]; });
  EXPECT_TRUE(r.health.failed(humanoid::kFtRight));
  r.go(200, 300, [](humanoid::SensorReadings&, int) {});
  EXPECT_FALSE(r.health.bad(humanoid::kFtRight));
  EXPECT_TRUE(r.health.failed(humanoid::kFtRight));  // latched
}

TEST(SensorHealth, EncodersMayRepeat) {
  // Quantised encoders read the same step for long at rest: never "stuck".
  Runner r;
  r.go(0, 1000, [](humanoid::SensorReadings&, int) {});
  EXPECT_FALSE(r.health.bad(humanoid::kEncoder));
}

TEST(SensorHealth, AnEncoderThatDoesNotFollowItsMovingCommandIsStuckAndReadAsTheCommand) {
  // Joint 3's command ramps at 0.45 rad/s (1.8 mrad a period) from k = 0; its encoder follows it
  // (quantised to 1e-5 rad) until k = 100, then freezes. Stuck once the command has moved more
  // than encoder_stuck_motion (0.02 rad) from the command when the reading last changed; the
  // clean reading is then the command.
  Runner r;
  const double rate = 0.45;
  humanoid::JointVector command{};
  int first_stuck = -1;
  for (int k = 0; k < 200; ++k) {
    humanoid::SensorReadings s = live(k);
    const int moving = std::min(k, 100);
    s.encoder[3] = std::round(rate * moving * kT / 1e-5) * 1e-5;
    r.health.check(s, k * kT);
    if (first_stuck < 0 && r.health.fault(humanoid::kEncoder) == SignalFault::kStuck) first_stuck = k;
    if (first_stuck >= 0) {
      ASSERT_EQ(r.health.clean().encoder[3], command[3]) << "k = " << k;
      ASSERT_EQ(r.health.clean().encoder[2], s.encoder[2]) << "the other joints as read";
    }
    command[3] = rate * k * kT;  // sent after the update of period k
    r.health.set_command(command);
  }
  // The reading last changed at k = 100, when the command sent after period 99 was 0.1782 rad;
  // the check at k sees the command of period k − 1: 0.0018 (k − 1) − 0.1782 > 0.02 first at
  // k = 112 (0.0216; at k = 111 0.0198).
  EXPECT_EQ(first_stuck, 112);
  EXPECT_EQ(r.health.episodes(humanoid::kEncoder), 1);
}

TEST(SensorHealth, AnEncoderAtRestWithItsCommandAtRestIsNotStuck) {
  // Quantised readings repeat for 1000 periods while the command dithers by ±5 mrad (a balance
  // loop's corrections), well inside encoder_stuck_motion: never stuck.
  Runner r;
  humanoid::JointVector command{};
  for (int k = 0; k < 1000; ++k) {
    r.health.check(live(k), k * kT);
    ASSERT_FALSE(r.health.bad(humanoid::kEncoder)) << "k = " << k;
    for (int j = 0; j < humanoid::kJoints; ++j) command[j] = 0.1 * j + 0.005 * std::sin(0.05 * k);
    r.health.set_command(command);
  }
}

TEST(SensorHealth, ABadFirstSampleReadsAsTheNominalRestValue) {
  // No last good value exists at the first sample: a NaN there is replaced by the nominal
  // reading (set_nominal), never passed on; every sensor.
  SensorHealth h{HealthParams{}, kT};
  humanoid::SensorReadings nominal;
  nominal.imu.accel = {0, 0, 9.81};
  for (int j = 0; j < humanoid::kJoints; ++j) nominal.encoder[j] = 0.01 * j;
  h.set_nominal(nominal);
  humanoid::SensorReadings s = live(0);
  s.imu.gyro.fill(kNan);
  s.imu.accel.fill(kNan);
  s.imu.quat.fill(kNan);
  s.ft[0].force.fill(kNan);
  s.ft[1].torque.fill(kNan);
  s.encoder.fill(kNan);
  h.check(s, 0.0);
  const humanoid::SensorReadings& c = h.clean();
  EXPECT_EQ(c.imu.gyro, nominal.imu.gyro);
  EXPECT_EQ(c.imu.accel, nominal.imu.accel);
  EXPECT_EQ(c.imu.quat, nominal.imu.quat);
  EXPECT_EQ(c.ft[0].force, nominal.ft[0].force);
  EXPECT_EQ(c.ft[1].torque, nominal.ft[1].torque);
  EXPECT_EQ(c.encoder, nominal.encoder);
  for (int i = 0; i < humanoid::kSensors; ++i) EXPECT_TRUE(h.bad(i)) << humanoid::kSensorNames[i];
}

TEST(SensorHealth, CheckAllocatesNothing) {
  SensorHealth h{HealthParams{}, kT};
  humanoid::SensorReadings s = live(0);
  const long before = g_allocations.load();
  for (int k = 0; k < 1000; ++k) {
    s.t = k * kT;
    s.ft[0].force[0] = k % 7 == 0 ? kNan : 1.0 * k;
    h.check(s, k * kT);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
}

}  // namespace
}  // namespace flexgait::walking
