#include "flexgait/walking/sensor_health.hpp"

#include <cmath>
#include <cstring>

namespace flexgait::walking {

using humanoid::kSensors;

SignalFault SignalMonitor::check(const HealthParams& p, double t, double T, double stamp, double* values, int n,
                                 bool detect_stuck, bool frozen, const double* fallback) {
  bool finite = true;
  for (int i = 0; i < n; ++i) finite = finite && std::isfinite(values[i]);
  // Bitwise repeat of the reading before (NaN never repeats: it is caught as nan first).
  const bool repeat =
      has_previous_ && std::memcmp(values, previous_.data(), sizeof(double) * static_cast<std::size_t>(n)) == 0;
  repeats_ = repeat ? repeats_ + 1 : 0;
  std::memcpy(previous_.data(), values, sizeof(double) * static_cast<std::size_t>(n));
  has_previous_ = true;

  SignalFault f = SignalFault::kOk;
  if (!finite)
    f = SignalFault::kNan;
  else if (!(t - stamp <= p.max_age))
    f = SignalFault::kStale;
  else if (frozen || (detect_stuck && p.stuck_samples > 0 && repeats_ + 1 >= p.stuck_samples))
    f = SignalFault::kStuck;

  if (f == SignalFault::kOk) {
    std::memcpy(good_.data(), values, sizeof(double) * static_cast<std::size_t>(n));
  } else {
    if (fault_ == SignalFault::kOk) {
      ++episodes_;
      bad_since_ = t;
    }
    bad_time_ += T;
    if (t - bad_since_ > p.hold_time) failed_ = true;  // bad beyond the hold time: failed
    std::memcpy(values, fallback != nullptr ? fallback : good_.data(), sizeof(double) * static_cast<std::size_t>(n));
  }
  fault_ = f;
  return f;
}

void SignalMonitor::set_nominal(const double* values, int n) {
  std::memcpy(good_.data(), values, sizeof(double) * static_cast<std::size_t>(n));
}

void SensorHealth::set_nominal(const humanoid::SensorReadings& r) {
  for (int side = 0; side < 2; ++side) {
    std::array<double, 6> v{};
    for (int i = 0; i < 3; ++i) {
      v[i] = r.ft[side].force[i];
      v[3 + i] = r.ft[side].torque[i];
    }
    monitor_[side].set_nominal(v.data(), 6);
  }
  monitor_[humanoid::kGyro].set_nominal(r.imu.gyro.data(), 3);
  monitor_[humanoid::kAccel].set_nominal(r.imu.accel.data(), 3);
  monitor_[humanoid::kAhrs].set_nominal(r.imu.quat.data(), 4);
  for (int j = 0; j < humanoid::kJoints; ++j) encoder_[j].set_nominal(&r.encoder[j], 1);
}

void SensorHealth::check(const humanoid::SensorReadings& s, double t) {
  clean_ = s;
  const HealthParams& p = params_;
  for (int side = 0; side < 2; ++side) {
    std::array<double, 6> v{};
    for (int i = 0; i < 3; ++i) {
      v[i] = s.ft[side].force[i];
      v[3 + i] = s.ft[side].torque[i];
    }
    // An unloaded foot's sensor reads its unloaded value, zero, exactly when the foot is massless:
    // not stuck while the foot swings, nor for health.hold_time after the planned landing (a landing
    // a little late, or one that touches and bounces off the floor before it bears the load); then
    // the count of repeats starts.
    const auto i_side = static_cast<std::size_t>(side);
    bool zero = true;
    for (const double x : v) zero = zero && x == 0.0;
    if (unloaded_[i_side]) swing_end_[i_side] = t;
    const bool unloaded_value = zero && t - swing_end_[i_side] <= p.hold_time;
    monitor_[side].check(p, t, period_, s.ft[side].stamp, v.data(), 6, !unloaded_value);
    if (unloaded_value) monitor_[side].forget_repeats();
    for (int i = 0; i < 3; ++i) {
      clean_.ft[side].force[i] = v[i];
      clean_.ft[side].torque[i] = v[3 + i];
    }
  }
  monitor_[humanoid::kGyro].check(p, t, period_, s.imu.gyro_stamp, clean_.imu.gyro.data(), 3, true);
  monitor_[humanoid::kAccel].check(p, t, period_, s.imu.accel_stamp, clean_.imu.accel.data(), 3, true);
  monitor_[humanoid::kAhrs].check(p, t, period_, s.imu.quat_stamp, clean_.imu.quat.data(), 4, true);
  bool any = false;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    // (bitwise: a NaN never repeats, and moves the anchor)
    const double raw = s.encoder[j];
    const bool repeat = has_encoder_previous_ && std::memcmp(&raw, &encoder_previous_[j], sizeof raw) == 0;
    if (!repeat) command_anchor_[j] = command_[j];
    encoder_previous_[j] = raw;
    // (stuck until the reading changes again, wherever the command goes meanwhile)
    const bool frozen = has_command_ && repeat && p.encoder_stuck_motion > 0 &&
                        (encoder_[j].fault() == SignalFault::kStuck ||
                         std::abs(command_[j] - command_anchor_[j]) > p.encoder_stuck_motion);
    const double* fallback = has_command_ ? &command_[j] : nullptr;
    any = encoder_[j].check(p, t, period_, s.encoder_stamp[j], &clean_.encoder[j], 1, false, frozen, fallback) !=
              SignalFault::kOk ||
          any;
  }
  has_encoder_previous_ = true;
  if (any && !encoder_bad_) ++encoder_episodes_;
  if (any) encoder_bad_time_ += period_;
  encoder_bad_ = any;
}

bool SensorHealth::bad(int sensor) const {
  return sensor == humanoid::kEncoder ? encoder_bad_ : monitor_[sensor].bad();
}

bool SensorHealth::failed(int sensor) const {
  if (sensor != humanoid::kEncoder) return monitor_[sensor].failed();
  for (const auto& e : encoder_)
    if (e.failed()) return true;
  return false;
}

SignalFault SensorHealth::fault(int sensor) const {
  if (sensor != humanoid::kEncoder) return monitor_[sensor].fault();
  for (const auto& e : encoder_)
    if (e.bad()) return e.fault();
  return SignalFault::kOk;
}

int SensorHealth::episodes(int sensor) const {
  return sensor == humanoid::kEncoder ? encoder_episodes_ : monitor_[sensor].episodes();
}

double SensorHealth::bad_time(int sensor) const {
  return sensor == humanoid::kEncoder ? encoder_bad_time_ : monitor_[sensor].bad_time();
}

unsigned SensorHealth::flags() const {
  unsigned out = 0;
  for (int i = 0; i < kSensors; ++i)
    if (bad(i)) out |= 1U << i;
  return out;
}

}  // namespace flexgait::walking
