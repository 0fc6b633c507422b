#pragma once
/// \file sensor_health.hpp
/// Sensor health (docs/guide/humanoid.md, "Sensors, faults and the attitude estimate"): every reading is checked each
/// control period before the
/// controller uses it. A reading is bad when
///  - nan:   a value is not finite;
///  - stale: its time stamp is older than health.max_age (a dropped or late sample);
///  - stuck: a live signal repeated the same bits for health.stuck_samples periods (noise and
///           motion make a working gyro, accelerometer, AHRS or F/T sensor change every sample);
///           an F/T sensor reading exactly zero (its unloaded value) while its foot swings is not
///           stuck: an unloaded massless foot reads exactly that, and a real F/T check likewise
///           judges a constant reading against the contact it expects (set_unloaded); nor for
///           health.hold_time after the planned landing (a landing a little late, or one that
///           touches and bounces off the floor first); then its count of repeats starts;
///           an encoder (quantised: it legitimately repeats while its motor rests) is stuck when
///           its reading has not changed while its motor's command moved by more than
///           health.encoder_stuck_motion since the reading last changed (the servo keeps the
///           motor within its tracking error of the command, so a working encoder must move).
/// A bad value is replaced by the signal's last good one (held) — a bad encoder by its motor's
/// command when the commands are known (set_command), since the motor follows it — or, before the signal has given
/// any good value, by its nominal value at rest (set_nominal: the start pose's encoders, a level
/// IMU at rest, unloaded F/T sensors), so that no bad value ever leaves the check, from the first
/// sample on; a signal bad for longer than
/// health.hold_time has failed (latched), which the controller escalates to a safe stop.
/// Pure and allocation-free: readings and time in, cleaned readings and flags out.
#include <array>
#include <cstdint>
#include <limits>

#include "flexgait/core/record.hpp"
#include "flexgait/robot/sensor_ids.hpp"
#include "flexgait/robot/sensors.hpp"

namespace flexgait::walking {

struct HealthParams {
  double max_age = 0.01;   ///< a reading older than this is stale [s]
  double hold_time = 0.3;  ///< longest a last good value stands in for a bad reading [s]
  int stuck_samples = 10;  ///< identical consecutive readings that make a live sensor stuck (0: not checked)
  double encoder_stuck_motion = 0.02;  ///< command motion with an unchanged encoder that makes it stuck [rad]
  double fade_time = 0.5;  ///< after a failure, the loops fed by that sensor fade out with this time constant [s]
  bool safe_stop = true;   ///< a failed sensor ends the walk (safe stop); off: hold and fade only

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("health.max_age", s.max_age,
      {.unit = "s", .doc = "a sensor reading older than this is stale", .bounds = closed(0, 10)});
    v("health.hold_time", s.hold_time,
      {.unit = "s",
       .doc = "longest the last good value stands in for a bad reading; then the sensor has failed",
       .bounds = closed(0, 1000)});
    v("health.stuck_samples", s.stuck_samples,
      {.doc =
           "identical consecutive readings that make a gyro, accelerometer, AHRS or F/T sensor stuck (0: not checked)",
       .bounds = closed(0, 100000)});
    v("health.encoder_stuck_motion", s.encoder_stuck_motion,
      {.unit = "rad",
       .doc = "an encoder whose reading has not changed while its motor's command moved this far is stuck (0: not "
              "checked); above the servo's largest tracking error",
       .bounds = closed(0, 10)});
    v("health.fade_time", s.fade_time,
      {.unit = "s",
       .doc = "after a failure the balance loops fed by that sensor fade out with this time constant",
       .bounds = left_open(0, 100)});
    v("health.safe_stop", s.safe_stop, {.doc = "a failed sensor ends the walk at the next double support (safe stop)"});
  }
};

enum class SignalFault : std::uint8_t { kOk, kNan, kStale, kStuck };
constexpr std::array<EnumName<SignalFault>, 4> enum_names(SignalFault) {
  return {{{SignalFault::kOk, "ok"},
           {SignalFault::kNan, "nan"},
           {SignalFault::kStale, "stale"},
           {SignalFault::kStuck, "stuck"}}};
}

/// One signal of up to kMaxValues values.
class SignalMonitor {
 public:
  static constexpr int kMaxValues = 6;
  /// Checks the reading `values` (n values, measured at `stamp`) at time t [s], period T [s], and
  /// overwrites `values` with the last good ones when it is bad. Returns the reading's fault.
  /// `frozen`: the caller's own evidence that the signal is stuck (an encoder that did not move
  /// with its command); `fallback` (n values, or null): what a bad reading is replaced by instead
  /// of the last good values.
  SignalFault check(const HealthParams& p, double t, double T, double stamp, double* values, int n, bool detect_stuck,
                    bool frozen = false, const double* fallback = nullptr);

  /// The value a bad reading is replaced by until the signal gives a good one (n values).
  void set_nominal(const double* values, int n);

  /// Starts the count of repeated readings again (a repeat that is not evidence of a stuck signal).
  void forget_repeats() { repeats_ = 0; }

  SignalFault fault() const { return fault_; }  ///< of the last check
  bool bad() const { return fault_ != SignalFault::kOk; }
  bool failed() const { return failed_; }        ///< bad for longer than hold_time once (latched)
  int episodes() const { return episodes_; }     ///< times it turned bad
  double bad_time() const { return bad_time_; }  ///< total time bad [s]

 private:
  std::array<double, kMaxValues> good_{}, previous_{};  ///< good_: the last good values, or the nominal ones
  bool has_previous_ = false;
  int repeats_ = 0;       ///< consecutive readings equal to the one before
  double bad_since_ = 0;  ///< [s]
  SignalFault fault_ = SignalFault::kOk;
  bool failed_ = false;
  int episodes_ = 0;
  double bad_time_ = 0;
};

/// The health of all the robot's sensors (humanoid::SensorId order; the encoders are one sensor
/// of kJoints signals).
class SensorHealth {
 public:
  SensorHealth(const HealthParams& params, double period) : params_(params), period_(period) {
    set_nominal(humanoid::SensorReadings{});
  }

  /// The readings that stand in for bad ones before a sensor has given a good reading (the
  /// robot at rest in its start pose); without it, zeros (and the identity quaternion).
  void set_nominal(const humanoid::SensorReadings& nominal);
  /// The motor commands sent after the last check [rad] (the encoders' stuck test and fallback).
  void set_command(const humanoid::JointVector& command) {
    if (!has_command_) command_anchor_ = command;  // (motion counts from the first command on)
    command_ = command;
    has_command_ = true;
  }
  /// Which feet are in the air (the plan's swing): their F/T sensors may read exactly zero (a
  /// massless foot carries no load at all), which is then no sign of a stuck sensor.
  void set_unloaded(const std::array<bool, 2>& unloaded) { unloaded_ = unloaded; }
  /// Checks every reading of `s` at time t [s]; clean() then holds them with bad values replaced.
  void check(const humanoid::SensorReadings& s, double t);
  const humanoid::SensorReadings& clean() const { return clean_; }

  bool bad(int sensor) const;           ///< this period
  bool failed(int sensor) const;        ///< once bad beyond hold_time (latched)
  SignalFault fault(int sensor) const;  ///< this period (the first bad signal's, encoders)
  int episodes(int sensor) const;       ///< times it turned bad (encoders: over all joints)
  double bad_time(int sensor) const;    ///< total time bad [s] (encoders: any joint)
  /// Bit i set when sensor i is bad this period.
  unsigned flags() const;
  const HealthParams& params() const { return params_; }

 private:
  HealthParams params_;
  double period_;
  std::array<SignalMonitor, humanoid::kSensors - 1> monitor_{};  ///< all but the encoders
  std::array<SignalMonitor, humanoid::kJoints> encoder_{};
  std::array<bool, 2> unloaded_{};  ///< the feet in the air (set_unloaded)
  /// The last check in swing [s] (−∞ before the first swing: no landing's exemption yet).
  std::array<double, 2> swing_end_{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  humanoid::JointVector command_{};  ///< the last commands sent [rad]
  bool has_command_ = false;
  humanoid::JointVector encoder_previous_{};  ///< each encoder's last raw reading [rad]
  humanoid::JointVector command_anchor_{};    ///< the command when that reading last changed [rad]
  bool has_encoder_previous_ = false;
  int encoder_episodes_ = 0;
  double encoder_bad_time_ = 0;
  bool encoder_bad_ = false;
  humanoid::SensorReadings clean_;
};

}  // namespace flexgait::walking
