#pragma once
/// \file sensor_faults.hpp
/// How the twin's sensors fail (docs/guide/humanoid.md, "Sensors, faults and the attitude estimate"): a fault schedule
/// per sensor, and the model of
/// a real IMU (gyro and accelerometer with bias and bias drift; an AHRS orientation output with
/// its own error). The plant applies these to its readings; a controller only sees the result.
///
/// A fault acts on one sensor (`channel`) from `start` for `duration` seconds:
///  - dropout: no new sample arrives; the reading and its time stamp stay at the last sample
///    delivered (what a bus driver shows when packets are lost);
///  - stuck:   the values freeze at the last sample delivered, the time stamp keeps advancing
///    (a sensor that reports fresh but frozen data);
///  - nan:     the values are NaN, the time stamp advances;
///  - latency: each sample arrives `delay` seconds late (reading and stamp of t − delay).
/// Outside [start, start + duration) the sensor is healthy. A duration at least the walk's length
/// makes the fault permanent.
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/robot/joints.hpp"
#include "flexgait/robot/sensor_ids.hpp"

namespace flexgait::twin {

enum class FaultKind { kNone, kDropout, kStuck, kNan, kLatency };
constexpr std::array<EnumName<FaultKind>, 5> enum_names(FaultKind) {
  return {{{FaultKind::kNone, "none"},
           {FaultKind::kDropout, "dropout"},
           {FaultKind::kStuck, "stuck"},
           {FaultKind::kNan, "nan"},
           {FaultKind::kLatency, "latency"}}};
}

/// One sensor's fault.
struct FaultSpec {
  FaultKind kind = FaultKind::kNone;
  double start = 0;     ///< [s]
  double duration = 0;  ///< [s]; at least the walk's length: permanent
  double delay = 0;     ///< latency only: how late each sample arrives [s]

  bool active(double t) const { return kind != FaultKind::kNone && t >= start && t - start < duration; }
};

/// The fault schedule of the twin: one fault per sensor (keys plant.faults.<sensor>.*).
struct SensorFaults {
  std::array<FaultSpec, humanoid::kSensors> sensor{};
  humanoid::Joint encoder_joint = humanoid::kLeftKnee;  ///< the joint whose encoder the encoder fault hits

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    for (int i = 0; i < humanoid::kSensors; ++i) {
      const std::string key = "plant.faults." + std::string(humanoid::kSensorNames[i]);
      auto& f = s.sensor[i];
      v(key + ".kind", f.kind, {.doc = "fault of this sensor: none, dropout, stuck, nan or latency"});
      v(key + ".start", f.start, {.unit = "s", .doc = "when the fault begins", .bounds = closed(0, 1e6)});
      v(key + ".duration", f.duration,
        {.unit = "s", .doc = "how long it lasts (at least the walk's length: permanent)", .bounds = closed(0, 1e9)});
      v(key + ".delay", f.delay, {.unit = "s", .doc = "latency: how late each sample arrives", .bounds = closed(0, 1)});
    }
    v("plant.faults.encoder.joint", s.encoder_joint, {.doc = "the joint whose encoder the encoder fault hits"});
  }
};

/// The IMU's error model beyond white noise (plant.noise.gyro, plant.noise.accel): a constant
/// bias on each axis and a bias random walk, b(t + T) = b(t) + σ_w √T n, n ~ N(0, 1) per axis
/// and control period T; the AHRS orientation output is the true orientation turned by a small
/// random rotation of std `ahrs_noise` about each axis.
struct ImuModel {
  double gyro_bias = 0;        ///< on each axis [rad/s]
  double gyro_bias_walk = 0;   ///< σ_w [rad/s/√s]
  double accel_bias = 0;       ///< on each axis [m/s^2]
  double accel_bias_walk = 0;  ///< σ_w [m/s^2/√s]
  double ahrs_noise = 0;       ///< std of the AHRS orientation error about each axis [rad]

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("plant.imu.gyro_bias", s.gyro_bias,
      {.unit = "rad/s", .doc = "gyro bias on each axis", .bounds = closed(-10, 10)});
    v("plant.imu.gyro_bias_walk", s.gyro_bias_walk,
      {.unit = "rad/s/sqrt(s)", .doc = "gyro bias random walk (drift) density", .bounds = closed(0, 10)});
    v("plant.imu.accel_bias", s.accel_bias,
      {.unit = "m/s^2", .doc = "accelerometer bias on each axis", .bounds = closed(-100, 100)});
    v("plant.imu.accel_bias_walk", s.accel_bias_walk,
      {.unit = "m/s^2/sqrt(s)", .doc = "accelerometer bias random walk (drift) density", .bounds = closed(0, 100)});
    v("plant.imu.ahrs_noise", s.ahrs_noise,
      {.unit = "rad", .doc = "std of the AHRS orientation output's error about each axis", .bounds = closed(0, 1)});
  }
};

/// Applies one FaultSpec to a stream of samples of N values (allocates only at construction).
template <std::size_t N>
class FaultChannel {
 public:
  using Values = std::array<double, N>;
  FaultChannel() = default;  ///< no fault
  /// \param period the interval between samples [s] (sizes the latency buffer)
  FaultChannel(const FaultSpec& spec, double period) : spec_(spec) {
    if (spec_.kind == FaultKind::kLatency) history_.resize(static_cast<std::size_t>(spec_.delay / period) + 3);
  }

  /// Turns the sample (values, stamp) taken at time t into what the sensor delivers.
  void apply(double t, Values& values, double& stamp) {
    if (!history_.empty()) {
      history_[head_] = {values, stamp};
      head_ = (head_ + 1) % history_.size();
      filled_ = std::min(filled_ + 1, history_.size());
    }
    if (!spec_.active(t)) {
      delivered_ = {values, stamp};
      return;
    }
    switch (spec_.kind) {
      case FaultKind::kDropout:
        values = delivered_.values;
        stamp = delivered_.stamp;
        return;
      case FaultKind::kStuck:
        values = delivered_.values;
        delivered_.stamp = stamp;
        return;
      case FaultKind::kNan:
        values.fill(std::numeric_limits<double>::quiet_NaN());
        delivered_ = {values, stamp};
        return;
      case FaultKind::kLatency:
        // The newest sample at least `delay` old (the oldest held when none is).
        for (std::size_t back = 1; back <= filled_; ++back) {
          const Sample& s = history_[(head_ + history_.size() - back) % history_.size()];
          if (s.stamp <= t - spec_.delay + 1e-12 || back == filled_) {
            values = s.values;
            stamp = s.stamp;
            break;
          }
        }
        delivered_ = {values, stamp};
        return;
      case FaultKind::kNone:
        return;
    }
  }

 private:
  struct Sample {
    Values values{};
    double stamp = 0;
  };
  FaultSpec spec_;
  Sample delivered_;
  std::vector<Sample> history_;  ///< ring buffer of the last samples (latency only)
  std::size_t head_ = 0, filled_ = 0;
};

}  // namespace flexgait::twin
