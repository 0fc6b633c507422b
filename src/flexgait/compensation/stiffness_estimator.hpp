#pragma once
/// \file stiffness_estimator.hpp
/// Online identification of the gears' stiffness while walking (docs/guide/compensation.md, control.k_estimation).
///
/// The model (docs/theory/humanoid.md, "The actuator deformation model"): θ_link = θ_enc − τ/k. A stance
/// foot flat on the ground fixes the foot's tilt; the IMU gives the pelvis attitude; the encoders
/// give the chain between them. The foot's tilt seen through the encoders, R_obs = R_imu · R_foot(θ_enc),
/// differs from the flat foot by the chain's deflections: to first order the rotation
///     ω = Σ_i a_i τ_i c_i,   c_i = 1/k_i,  a_i the joint axis (world)
/// of which the horizontal components are observed (ω_x = −R_obs(1,2), ω_y = R_obs(0,2); the
/// foot's yaw is not known). Two measurements per stance foot, against the leg's joints; the yaw joints'
/// deflections (axis z) are not seen and keep the belief. By default one c per joint group and leg, roll (axis
/// mostly x) and pitch (axis mostly y): deflections about parallel axes (hip pitch, knee, ankle pitch; hip roll, ankle
/// roll) enter only as their torque-weighted sum, walking moves the parallel joints' modelled torques nearly in
/// proportion, and the model's few-percent torque errors, multiplied by that near-collinearity, leave the joints apart
/// ill-determined (docs/guide/compensation.md, "Per joint: the servos' measured torques"). With each servo's torque
/// measured (control.k_estimation_torque measured: the motor current's torque less the rotor's inertia J_m θ̈_m,
/// measured_gear_torque.hpp) the torques' own variation over a walk separates them: one c per joint
/// (control.k_estimation_per_joint).
///
/// Each leg's c is estimated by RLS with forgetting (forgetting_rls.hpp), the regressor of a parameter
/// h_p = Σ_{i∈p} (a_i)_xy τ_i (a group's joints, or one joint), τ through the gears' lag (DeflectionLag, at
/// lag_stiffness, with control.gear_damping); the sole's tilt in its contact under the ground's torque about its
/// centre, from its F/T sensor (sole_tilt, control.sole_stiffness_*), is taken out of ω. A sample is used
/// only when the foot is in firm support by its F/T sensor (normal force ≥ a quarter of the weight,
/// the centre of pressure within the middle 60 % of the sole's length and width) and |H| ≥
/// control.k_estimation_min_torque. Bad data (a NaN, or an F/T reading older than 50 ms, or the
/// controller's sensor check flagging a sensor) keeps the last estimate and is counted.
/// The estimate stays within [0.1, 10] × the belief (so k > 0 always). A parameter is confident when
/// it is inside those bounds and its relative standard deviation sqrt(P_pp)/c_p ≤ control.k_estimation_confidence (P
/// the RLS covariance with prior (c₀)² and measurement variance control.k_estimation_noise²); from then on stiffness()
/// gives 1/c_p for its joints (the last confident value if confidence lapses). The pelvis attitude the chain starts
/// from: the controller's estimate (control.k_estimation_attitude_time = 0), or the IMU's turn pulled towards that
/// estimate with time constant t_a, so the estimate's errors at the gait's frequencies — correlated with the
/// deflections, the dominant error of the identification — are filtered out:
///     R ← exp([e]× min(1, T/t_a)) R exp([Δθ − b̂ T]×),  e the rotation vector of R_imu Rᵀ,
/// Δθ the IMU's delta angle, its turn since the last reading integrated at its own rate (humanoid::Imu): one gyro
/// sample per period aliases the rate's ripple at the control frequency — the servos' steps — into a drift, on the
/// twin 0.14 mrad/s in pitch while walking, which the pitch joints take for deflection. The
/// default t_a = 1000 s: the IMU's over a walk (the controller's Mahony attitude drifts ~0.02 rad in pitch over a
/// 20 s walk, which the pitch groups, their regressor nearly constant, take for deflection).
/// It trusts the gyro over t_a: a gyro bias b tilts it by ≈ b t_a. So a real robot's gyro is calibrated first
/// (control.k_estimation_gyro_rest = t_r > 0) by the static alignment of an inertial unit: standing still in the
/// start stance over t_r, until the COM starts to move (walk.preview_time before the first step), the gyro's
/// turn less the pelvis's turn seen through the legs (both soles flat and still; encoders − τ/k) over t_r is its
/// bias b̂, removed from every later reading (Δθ − b̂ T above), and the attitude starts from the accelerometer's
/// up u = Rᵀ e_z at the window's end (the controller's yaw; the minimal turn of the controller's estimate that
/// makes Rᵀ e_z = u). No sample is taken before. Left: the bias's walk
/// since then, σ_w √t, tilting the attitude by ≈ σ_w t^{3/2}/√3 (t ≪ t_a), and the accelerometer's bias a_b:
/// ≈ a_b/g. A constant tilt error matters: the pitch groups' regressor is nearly constant in a walk.
/// Allocation-free after construction; free of the simulator.
#include <algorithm>
#include <array>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/compensation/forgetting_rls.hpp"
#include "flexgait/walking/foot_wrench.hpp"

namespace flexgait::compensation {

/// The identification's bad-data rule (also chain_stiffness_calibration.hpp): every encoder, torque and F/T
/// value finite and both F/T readings at most 50 ms old at t [s].
bool identification_inputs_ok(double t, const humanoid::JointVector& encoder, const humanoid::JointVector& torque,
                              const std::array<humanoid::ForceTorque, 2>& ft);

/// A sole in firm support by its F/T sensor: normal force ≥ min_share × the robot's weight and the centre of
/// pressure on the sole shrunk to 60 % about its centre (a rectangle: the middle 60 % of its length and width). \param
/// sole_R the sole's planned attitude.
bool firm_support(const walking::RobotModel& model, const humanoid::ForceTorque& ft, const walking::Matrix3d& sole_R,
                  int side, double min_share);
/// The same test on the sole's contact (sole_contact).
bool firm_support(const walking::RobotModel& model, const walking::FootContact& contact, int side, double min_share);

/// What a sole's F/T sensor says about its contact, the centre of pressure and the ground's torque about the sole's
/// centre (walking::foot_contact with the model's sensor-to-sole lever). \param sole_R the sole's attitude (world).
walking::FootContact sole_contact(const walking::RobotModel& model, const humanoid::ForceTorque& ft,
                                  const walking::Matrix3d& sole_R, int side);

/// The modelled torque as the gears' deflection sees it (both identifications). The deflection lags the load: with
/// control.gear_damping d the gear is a Kelvin–Voigt element, k δ + d δ̇ = τ, so δ = τ / (k (1 + (d/k) s))
/// (docs/theory/humanoid.md, "The actuator deformation model"); the modelled torque already lags the load by the F/T
/// low-pass (control.load_filter_time t_f), so the regressor's torque lags it by the rest, d/k − t_f (time
/// constants of first-order lags add at the gait's low frequencies), backward Euler over the period; a measured
/// torque (control.k_estimation_torque) lags by d/k. k is the best known at the time (the calibration: what the
/// compensators use; walking: StiffnessEstimator::lag_stiffness). A filter in time: it runs every period with good
/// data, whether or not a sample is taken; it starts from the first torque.
class DeflectionLag {
 public:
  void update(const humanoid::JointVector& torque, const humanoid::JointVector& stiffness,
              const CompensationParams& params, double period) {
    const double filter_time = params.k_estimation_torque == KTorque::kMeasured ? 0.0 : params.load_filter_time;
    for (int j = 0; j < humanoid::kJoints; ++j) {
      const double lag = std::max(0.0, params.gear_damping / stiffness[j] - filter_time);
      const double a = started_ ? period / (period + lag) : 1.0;
      torque_[j] += a * (torque[j] - torque_[j]);
    }
    started_ = true;
  }
  const humanoid::JointVector& torque() const { return torque_; }  ///< [Nm]

 private:
  humanoid::JointVector torque_{};
  bool started_ = false;
};

/// The sole's tilt in its contact about the sole's x and y axes (sole frame; z 0) [rad]: the foot pad and the floor
/// contact turn the sole against the ground's torque about the sole's centre M (sole_contact), θ = −M / k_sole
/// (control.sole_stiffness_roll, _pitch; 0: rigid). Not the ankle's torque, which adds the ground force's moment
/// about the ankle: the vertical force times the sole centre's offset from the ankle's axes (the builtin's 14 mm
/// outward: 8 Nm of ankle roll in single support with the centre of pressure at the sole's centre) and the
/// horizontal force times the ankle's height; neither tilts the sole.
inline walking::Vector3d sole_tilt(const walking::FootContact& contact, const CompensationParams& p) {
  const auto compliance = [](double k) { return k > 0 ? 1.0 / k : 0.0; };
  return {-contact.torque.x() * compliance(p.sole_stiffness_roll),
          -contact.torque.y() * compliance(p.sole_stiffness_pitch), 0.0};
}

/// A joint whose axis (body frame) is mostly vertical, a yaw joint: its deflection barely tilts a sole, so neither
/// identification sees it (it keeps the belief).
inline bool yaw_axis(const walking::Vector3d& axis) {
  const walking::Vector3d a = axis.cwiseAbs();
  return a.z() >= a.x() && a.z() >= a.y();
}

class StiffnessEstimator {
 public:
  /// Per leg: up to one 1/k per leg joint (modelled torques: the roll group's at 0, the pitch group's at 1; measured:
  /// each joint's at its place in the leg), then the stance's tilt offset (x, y). A parameter not estimated has a
  /// zero prior variance and stays at zero.
  static constexpr int kParams = humanoid::kLegJoints;
  static constexpr int kStates = kParams + 2;
  enum Group { kRoll = 0, kPitch = 1 };

  /// \param rest_end when the robot leaves its start stance (the first step begins) [s]: the end of the gyro's
  /// calibration window (control.k_estimation_gyro_rest).
  StiffnessEstimator(const walking::RobotModel& model, const CompensationParams& params, double period,
                     double rest_end = 0.0);

  /// One control period. \param t now [s] (the F/T stamps' staleness); \param imu_R the controller's pelvis
  /// attitude (world); \param imu the IMU's readings (its delta angle [rad], and its accelerometer [m/s²] for
  /// the calibration at rest; pelvis frame); \param torque the modelled
  /// or measured gear torque of every joint [Nm]; \param sensors_ok false when the controller's sensor check
  /// flags a sensor this period. Returns how many feet gave a sample.
  int update(double t, const humanoid::JointVector& encoder, const walking::Matrix3d& imu_R, const humanoid::Imu& imu,
             const humanoid::JointVector& torque, const std::array<humanoid::ForceTorque, 2>& ft,
             const SupportPlan& support, bool sensors_ok);

  /// The raw estimate of each joint's stiffness, 1/c of its parameter (the belief for the yaw joints
  /// and the waist) [Nm/rad].
  const humanoid::JointVector& estimate() const { return estimate_; }
  /// What the compensators use: the estimate of the confident parameters, the belief elsewhere.
  const humanoid::JointVector& stiffness() const { return stiffness_; }
  /// The joint's stiffness is estimated (a leg's roll or pitch joint).
  bool identified(int joint) const { return param_[joint] >= 0; }
  /// The joint's parameter has been confident (its estimate goes to the compensators).
  bool confident(int joint) const;
  /// A joint's relative standard deviation sqrt(P_pp)/c_p, its parameter's (the joints of a group share one 1/k; 0
  /// for a joint not identified).
  double relative_std(int joint) const;
  long samples() const { return samples_; }    ///< foot samples used
  long bad_data() const { return bad_data_; }  ///< periods skipped for bad data
  /// The gyro bias found at rest (pelvis frame) [rad/s]; zero before or without the calibration.
  const walking::Vector3d& gyro_bias() const { return gyro_bias_; }

 private:
  double relative_std(int side, int param) const;
  /// The parameter is held at a bound of [0.1, 10] × the belief: the data pushed it out of the plausible range (a
  /// regressor with no information, a wrong attitude), so its estimate is the bound, not a finding; never confident.
  bool on_bound(int side, int param) const;
  /// Each of the leg's parameters beyond its bound onto it, the correlated states with it (a projection).
  void hold_within_bounds(int side);
  void publish(int side);
  /// The stiffness the regressor's lag d/k is taken at: a joint's estimate once its relative std is at most 20 %
  /// (the lag then within 20 % of the gear's; the belief's may be further off: 13 % at 870 Nm/rad believed 1000,
  /// and the samples it lags stay in the fit), else what the compensators use.
  humanoid::JointVector lag_stiffness() const;
  void follow_attitude(const walking::Matrix3d& imu_R, const walking::Vector3d& delta_angle);
  /// control.k_estimation_gyro_rest: sums the gyro, the accelerometer and the legs' turn over the rest window;
  /// at its end, the static alignment (the bias, the attitude). False while it is still to come (no samples then).
  bool calibrate_at_rest(double t, const walking::Matrix3d& imu_R, const walking::Vector3d& delta_angle,
                         const walking::Vector3d& accel, const humanoid::JointVector& encoder,
                         const humanoid::JointVector& torque);
  /// The mean of the two soles' attitudes in the pelvis frame, through the link angles θ_enc − τ/k (the belief).
  walking::Matrix3d soles_in_pelvis(const humanoid::JointVector& encoder, const humanoid::JointVector& torque);

  walking::RobotModel model_;
  CompensationParams params_;
  double noise_variance_;
  double period_;  ///< [s]
  humanoid::JointVector belief_, estimate_, stiffness_;
  std::array<int, humanoid::kJoints> param_{};  ///< each joint's parameter in its leg's RLS; −1: not identified
  std::array<std::array<double, kParams>, 2> c_min_{}, c_max_{};
  std::array<ForgettingRls<kStates>, 2> rls_;
  DeflectionLag lag_;                 ///< the regressor's torque: the modelled torque through the deflection's lag
  std::array<bool, 2> new_stance_{};  ///< the foot has swung since its last sample (the offset starts anew)
  walking::Matrix3d attitude_ = walking::Matrix3d::Identity();  ///< the identification's pelvis attitude (world)
  bool attitude_started_ = false;
  double rest_end_;  ///< [s]
  bool calibrated_;
  walking::Vector3d gyro_bias_ = walking::Vector3d::Zero();  ///< [rad/s]
  /// Over the rest window, s = t − its end [s]: n, Σs, Σs², ΣΔθ (the IMU's turn from the first reading to the last),
  /// Σu, Σ s u (u the accelerometer's unit up), the soles' attitude in the pelvis frame first and last.
  struct RestSums {
    double n = 0, t = 0, tt = 0;
    walking::Vector3d turn = walking::Vector3d::Zero(), up = walking::Vector3d::Zero(),
                      t_up = walking::Vector3d::Zero();
    walking::Matrix3d soles_first = walking::Matrix3d::Identity();  ///< soles_in_pelvis at the window's first sample
    humanoid::JointVector encoder_last{}, torque_last{};            ///< its last sample's (soles_in_pelvis at the end)
  } rest_;
  std::array<std::array<bool, kParams>, 2> confident_{};
  walking::RobotModelData data_;
  long samples_ = 0, bad_data_ = 0;
};

}  // namespace flexgait::compensation
