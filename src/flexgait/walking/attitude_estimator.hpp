#pragma once
/// \file attitude_estimator.hpp
/// The pelvis attitude from the IMU's gyro and accelerometer: Mahony's explicit complementary
/// filter with gyro bias estimation (R. Mahony, T. Hamel, J.-M. Pflimlin, "Nonlinear
/// complementary filters on the special orthogonal group", IEEE TAC 53(5), 2008, eqs. (32a–c)):
///
///     v      = (a − R̂ᵀ a_m) / |a − R̂ᵀ a_m|     measured "up" in the pelvis frame (accelerometer a,
///                                               a_m the planned pelvis acceleration, world)
///     v̂      = R̂ᵀ e_z                           estimated "up"
///     ω_mes  = v × v̂                            (32c, one vector direction)
///     dR̂/dt  = R̂ [ω_y − b̂ + k_P ω_mes]×         (32a, ω_y the gyro)
///     db̂/dt  = −k_I ω_mes                        (32b)
///
/// integrated once per control period T with the exact exponential of the body rate. Yaw is not
/// observable from gravity: it is the gyro's integral (the controller does not use it).
///
/// Small-error dynamics (roll or pitch error θ = θ̂ − θ, bias error b̃ = b − b̂):
/// θ̇ = b̃ − k_P θ, b̃̇ = −k_I θ, so θ̈ + k_P θ̇ + k_I θ = 0 — poles s = (−k_P ± √(k_P² − 4 k_I))/2.
/// A constant gyro bias is rejected (steady-state error 0; transient peak about b/k_P); a
/// horizontal acceleration the plan does not predict tilts the estimate by a/g through the
/// low-pass k_P/(s + k_P). The twin's pelvis rocks on its compliant legs with accelerations of
/// ~1 m/s² near 0.5–1 Hz that the plan does not hold, so the defaults trust the gyro: k_P = 0.1
/// rad/s (a/g attenuated ~30× at 0.5 Hz) and k_I = 0.002 rad/s² (poles −0.028 and −0.072 rad/s:
/// the bias is learnt over about a minute).
///
/// Start (levelling) and alignment: the filter starts from the mean accelerometer reading over a
/// steady window of level_time — every reading within 5 % of g in magnitude and within
/// level_tolerance of the window's mean direction — (tilt from gravity, yaw 0): the coarse
/// levelling of an inertial unit at rest. The twin is dropped onto its elastic gears at the
/// start and pitches at up to 2 rad/s for the first 0.1 s; a single first reading taken then was
/// 0.26 rad off in pitch and the balance loops acted on it. Until the window is found the filter
/// has no attitude (the controller holds the body upright); if none is found within align_time
/// of the first reading, the mean of every reading since then (within [0.5 g, 1.5 g]) starts it
/// — a body that rocks in place has a zero mean acceleration, whereas one reading of the twin
/// rocking at ~4 Hz under a strong sway damping (balance.ankle_gyro_gain 0.15) was 0.06 rad off —
/// and, that wait having been the averaging, without the alignment below. For align_time after
/// a steady start the filter corrects with the higher gain align_kp (time constant 1/align_kp)
/// and does not learn the bias, then switches to k_P and k_I. The alignment also ends, for good,
/// at the first reading whose planned horizontal acceleration a_m (the plan's COM acceleration)
/// exceeds align_accel: at align_kp it would take the gap between the planned and the real
/// acceleration for tilt within 0.2 s (measured: an alignment over the first step left 0.06 rad
/// of error that k_P then kept for the whole walk). The robot should stand for level_time +
/// align_time (walk.start_time is longer by default).
/// Readings whose magnitude is outside [0.5 g, 1.5 g] after compensation are not used (impacts).
/// Allocation-free; no simulator types.
#include "flexgait/core/record.hpp"
#include "flexgait/robot/robot_params.hpp"
#include "flexgait/walking/rotation.hpp"

namespace flexgait::walking {

/// Which attitude the controller uses (estimator.source).
enum class AttitudeSource { kMahony, kAhrs, kTilt };
constexpr std::array<EnumName<AttitudeSource>, 3> enum_names(AttitudeSource) {
  return {{{AttitudeSource::kMahony, "mahony"}, {AttitudeSource::kAhrs, "ahrs"}, {AttitudeSource::kTilt, "tilt"}}};
}

struct EstimatorParams {
  AttitudeSource source = AttitudeSource::kMahony;  ///< Mahony filter, or the IMU's AHRS output
  double kp = 0.1;                                  ///< k_P: accelerometer correction gain [rad/s]
  double ki = 0.002;                                ///< k_I: gyro bias integral gain [rad/s^2]
  double align_time = 1.0;  ///< alignment after the start: gain align_kp, no bias integration [s]
  double align_kp = 5.0;    ///< k_P while aligning [rad/s]
  /// The alignment ends early once the planned horizontal acceleration exceeds this [m/s^2]:
  /// once the plan moves at all. The compliant twin does not follow the plan's acceleration
  /// while the weight shifts before the first step: over 1.2–1.3 s of configs/walk-robotis.yaml
  /// the plan's COM accelerates +0.17 m/s² sideways and the pelvis accelerates −0.11 (the
  /// accelerometer's −0.08 less gravity's share through the true roll); at align_kp that gap is
  /// tilt within 0.2 s (the estimate was 0.015 rad off when the alignment ended at 1.25 s, and
  /// k_P kept most of it for the walk). 0.01 ends the default walk's alignment at 0.49 s: attitude
  /// error rms 0.0086 → 0.0028 rad at 1 s/step and 0.0054 → 0.0044 at 3 s/step (both
  /// compensators, dynamic loads, f = 0.5, lag). The earlier 0.2 did not cut that alignment.
  double align_accel = 0.01;
  /// Levelling: length of the steady accelerometer window that starts the filter [s]. At least
  /// one period of the standing twin's sway, so that half a swing does not pass for rest: with
  /// balance.ankle_gyro_gain 0.15 it sways at 3.8 Hz (0.26 s) and a 0.1 s window on one rough
  /// floor (configs/walk-rough.yaml, seed 13) started 0.03–0.04 rad off, which the alignment
  /// had corrected until it ended with the plan's first motion. 0.3: over that floor set (seeds
  /// 1–48) 5 fell and the attitude error's median was 0.0146 rad; 0.1 (with align_accel 0.01):
  /// 8 and 0.0157; the earlier 0.1 with align_accel 0.2: 5 and 0.0173. Flat walks: unchanged to
  /// 1e-4 rad.
  double level_time = 0.3;
  double level_tolerance = 0.02;   ///< levelling: a steady reading's largest angle to the window's mean [rad]
  bool accel_compensation = true;  ///< subtract the planned COM acceleration from the accelerometer
  double gravity = humanoid::kDefaultGravity;  ///< [m/s^2] (the walking controller sets its robot model's)
  // The kinematic–inertial tilt observer (source tilt; tilt_observer.hpp (T3)).
  double tilt_alpha = 50.0;  ///< α: velocity correction [1/s]
  /// β: tilt correction from the velocity error [1/s]. The encoders miss the gears' deflection rate
  /// (the body rocks ~0.02 rad at 0.5 Hz on them), which the velocity error carries into the tilt:
  /// measured at 1 s/step, attitude error rms 0.043 rad at β = 5, 0.0117 at 1, 0.0064 at 0.2,
  /// 0.0088 at 0.05 (the Mahony filter: 0.0127).
  double tilt_beta = 0.2;
  double tilt_gamma = 15.0;  ///< γ: pull of the unit tilt toward the corrected one [1/s]

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("estimator.source", s.source,
      {.doc = "pelvis attitude: mahony (filter on gyro and accelerometer), ahrs (the IMU's orientation output) or tilt "
              "(kinematic-inertial observer: gyro, accelerometer and the stance legs' kinematics; Benallegue 2020)"});
    v("estimator.kp", s.kp,
      {.unit = "rad/s", .doc = "Mahony filter: accelerometer correction gain k_P", .bounds = closed(0, 100)});
    v("estimator.ki", s.ki,
      {.unit = "rad/s^2", .doc = "Mahony filter: gyro bias integral gain k_I", .bounds = closed(0, 100)});
    v("estimator.align_time", s.align_time,
      {.unit = "s",
       .doc = "Mahony filter: alignment time after the start (gain estimator.align_kp, no bias integration)",
       .bounds = closed(0, 100)});
    v("estimator.align_kp", s.align_kp,
      {.unit = "rad/s", .doc = "Mahony filter: k_P while aligning", .bounds = closed(0, 100)});
    v("estimator.align_accel", s.align_accel,
      {.unit = "m/s^2",
       .doc = "Mahony filter: the alignment ends early once the planned horizontal COM acceleration exceeds this",
       .bounds = closed(0, 100)});
    v("estimator.level_time", s.level_time,
      {.unit = "s",
       .doc = "Mahony filter: start from the mean accelerometer over a steady window this long (0: the first reading "
              "near 1 g)",
       .bounds = closed(0, 10)});
    v("estimator.level_tolerance", s.level_tolerance,
      {.unit = "rad",
       .doc = "Mahony filter: a steady reading's largest angle to the levelling window's mean direction",
       .bounds = closed(0, 1)});
    v("estimator.accel_compensation", s.accel_compensation,
      {.doc = "Mahony filter: subtract the planned COM acceleration from the accelerometer"});
    v("estimator.tilt_alpha", s.tilt_alpha,
      {.unit = "1/s", .doc = "tilt observer: velocity correction gain", .bounds = closed(0, 1000)});
    v("estimator.tilt_beta", s.tilt_beta,
      {.unit = "1/s", .doc = "tilt observer: tilt correction from the velocity error", .bounds = closed(0, 1000)});
    v("estimator.tilt_gamma", s.tilt_gamma,
      {.unit = "1/s",
       .doc = "tilt observer: pull of the unit tilt toward the corrected one",
       .bounds = closed(0, 1000)});
  }
};

class AttitudeEstimator {
 public:
  explicit AttitudeEstimator(const EstimatorParams& params) : params_(params) {}

  /// One period T [s]: gyro ω_y [rad/s] (pelvis frame); accelerometer a [m/s^2] (pelvis frame)
  /// or nullptr when it is unavailable (then gyro integration only); a_m the planned pelvis
  /// acceleration (world) [m/s^2]. The result is in attitude(), bias().
  void update(const Vector3d& gyro, const Vector3d* accel, const Vector3d& planned_accel, double T);
  /// Starts again (the next steady window initialises the attitude).
  void reset();

  const Matrix3d& attitude() const { return R_; }  ///< R̂: pelvis to world
  const Vector3d& bias() const { return bias_; }   ///< b̂ [rad/s]
  bool initialised() const { return initialised_; }

 private:
  EstimatorParams params_;
  Matrix3d R_ = Matrix3d::Identity();
  Vector3d bias_ = Vector3d::Zero();
  bool initialised_ = false;
  double time_ = 0;  ///< since the initialisation, or align_time from when the alignment ended early [s]
  // Levelling (before the initialisation).
  Vector3d level_sum_ = Vector3d::Zero();  ///< sum of the window's readings [m/s^2]
  int level_count_ = 0;                    ///< readings in the window
  double waiting_ = 0;                     ///< since the first accelerometer reading [s]
  Vector3d wait_sum_ = Vector3d::Zero();   ///< sum of the readings since then [m/s^2]

  /// Takes one reading a (already gated to [0.5 g, 1.5 g]) into the levelling; initialises the
  /// attitude once the window is steady (or the wait timed out: from the mean of a − planned_accel).
  void level(const Vector3d& a, const Vector3d& planned_accel, double T);
};

}  // namespace flexgait::walking
