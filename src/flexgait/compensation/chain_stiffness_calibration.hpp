#pragma once
/// \file chain_stiffness_calibration.hpp
/// Each leg joint's gear stiffness from a calibration in the start stance (docs/guide/compensation.md,
/// control.k_estimation = calibrate; the motion: walking/calibration_motion.hpp).
///
/// With both soles flat on one floor, the legs close a chain: sole → left leg → pelvis → right leg →
/// sole. Through the link angles θ = θ_enc − τ c (c = 1/k, spec "The actuator deformation model"),
/// the right sole's attitude in the left sole's frame is a constant R₀ (the floor's), so through the
/// encoders
///     y = log(R_L(θ_enc)ᵀ R_R(θ_enc)) = y₀ + Σ_j s_j J_l⁻¹(y) R_Lᵀ a_j τ_j c_j + O(δ²),
/// a_j joint j's axis (pelvis frame), s_j = −1 on the left leg and +1 on the right, J_l⁻¹ SO(3)'s
/// inverse left Jacobian (rotation.hpp). Its roll and pitch rows are used; the relative yaw is not
/// (the soles twist in their contacts: 0.5 mrad rms on the twin, against 0.03–0.1 mrad in roll and
/// pitch). Neither the IMU nor an attitude estimate enters: the pelvis's attitude cancels.
///
/// Unknowns: c_j of every leg joint whose axis is mostly horizontal (roll, pitch: ten on the builtin
/// robot; the yaw joints' deflections barely tilt a sole and keep the belief) and y₀'s roll and pitch
/// (the floor under the two soles need not be level between them). Why they separate (walking does
/// not, docs/guide/compensation.md, "Stiffness identified while walking"): the two legs' torques change differently as
/// the weight moves between them,
/// and the calibration motion moves the parallel joints' torques (hip pitch, knee, ankle pitch; hip and
/// ankle roll) in different ratios. Least squares over the window with prior c₀ = 1/belief (100 % relative
/// std), y₀ ~ N(0, (0.05 rad)²), observation noise control.k_estimation_noise, no forgetting (one batch:
/// the slowest component's period is 13 s), in information form (information_least_squares.hpp). A sample is taken
/// within the calibration window, both soles planned in support and firm by their F/T sensors (normal force ≥ 5 % of
/// the weight, the centre of pressure in the sole's middle 60 %); bad data (stiffness_estimator.hpp's rule, or the
/// controller's sensor check) is skipped and counted. The estimate stays within [0.1, 10] × the belief. The
/// compensators keep the belief until the calibration ends, then take each joint's estimate whose relative std is ≤
/// control.k_estimation_confidence. (Fed back while it runs, the estimate changes the modelled torque
/// it is fitted to, sample by sample: on the twin the worst joint then ended 11 % off, against 6.4 %
/// held; docs/guide/compensation.md.)
///
/// Three things the chain sees besides the gears (docs/guide/compensation.md, "Stiffness identified while walking"),
/// each a belief:
/// - the soles tilt in their contacts (a pad, a soft floor: on the twin 25.6 kNm/rad in roll, 56.2 kNm/rad in
///   pitch in this stance) against the ground's torque about each sole's centre, which the F/T sensors read
///   (sole_tilt): in the stance that torque moves with the ankle's, so the tilt is nearly in series with the
///   ankle's gear, not separable from it. control.sole_stiffness_* takes the tilt out of y (0: rigid soles);
/// - the gears' lag: control.gear_damping d delays the deflection by d/k behind the torque;
/// - the modelled torque depends on the stiffness (the output compensator's estimated pose, the lag d/k): with
///   control.k_calibration_passes > 1 the window is split, each pass fitted afresh with the torques modelled at
///   the previous pass's estimate (the compensators take it at the pass's end; samples resume kSettleTime later).
/// Allocation-free after construction; free of the simulator.
#include <array>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/compensation/information_least_squares.hpp"
#include "flexgait/compensation/stiffness_estimator.hpp"

namespace flexgait::compensation {

class ChainStiffnessCalibration {
 public:
  static constexpr int kMaxJoints = 2 * humanoid::kLegJoints;  ///< identified joints at most
  static constexpr int kStates = kMaxJoints + 2;               ///< their c, then y₀'s roll and pitch

  /// \param begin, end the calibration window [s] (walking::CalibrationMotion's start and end()).
  ChainStiffnessCalibration(const walking::RobotModel& model, const CompensationParams& params, double period,
                            double begin, double end);

  /// One control period. \param t now [s]; \param torque the modelled gear torque of every joint [Nm];
  /// \param sensors_ok false when the controller's sensor check flags a sensor. Returns 1 when it took a sample.
  int update(double t, const humanoid::JointVector& encoder, const humanoid::JointVector& torque,
             const std::array<humanoid::ForceTorque, 2>& ft, const SupportPlan& support, bool sensors_ok);

  /// The roll and pitch rows of y's regressor on the states at the encoders θ_enc (the model above) and
  /// y itself: y ≈ H x. For the tests (finite differences) and the update.
  Eigen::Matrix<double, 2, kStates> regressor(const humanoid::JointVector& encoder, const humanoid::JointVector& torque,
                                              Eigen::Vector2d& y);
  /// The same with the soles' tilts in their contacts (sole_tilt: each in its sole's frame, left, right) taken out
  /// of y: y ≈ H x + J_l⁻¹(y) R_Lᵀ (R_R θ_R − R_L θ_L) through the encoders.
  Eigen::Matrix<double, 2, kStates> regressor(const humanoid::JointVector& encoder, const humanoid::JointVector& torque,
                                              const std::array<walking::Vector3d, 2>& sole_tilts, Eigen::Vector2d& y);

  const humanoid::JointVector& estimate() const {
    return estimate_;
  }  ///< 1/c (the belief where not identified) [Nm/rad]
  /// What the compensators use: the belief, after the calibration the confident estimates [Nm/rad].
  const humanoid::JointVector& stiffness() const { return stiffness_; }
  bool identified(int joint) const { return state_[joint] >= 0; }
  int state(int joint) const { return state_[joint]; }  ///< a joint's column in the regressor; −1: not identified
  /// Relative standard deviation sqrt(P_jj)/c_j of an identified joint (0 elsewhere).
  double relative_std(int joint) const;
  long samples() const { return samples_; }    ///< samples used
  long bad_data() const { return bad_data_; }  ///< periods skipped for bad data

 private:
  walking::RobotModel model_;
  CompensationParams params_;
  double period_;  ///< [s]
  double noise_variance_;
  double begin_, end_;  ///< [s]
  DeflectionLag lag_;   ///< the modelled torque through the deflection's lag
  humanoid::JointVector belief_, estimate_, stiffness_;
  std::array<int, humanoid::kJoints> state_{};  ///< a joint's state index, −1: not identified
  std::array<double, kStates> c_min_{}, c_max_{};
  InformationLeastSquares<kStates> fit_;
  walking::RobotModelData data_;
  bool published_ = false;   ///< the calibration is over and stiffness_ holds its result
  int pass_ = 0;             ///< the pass being fitted (control.k_calibration_passes)
  double settle_until_ = 0;  ///< no samples before this, after a pass published [s]

  void start_fit();          ///< the fit afresh, its prior 1/stiffness_ (100 % relative std)
  void publish();            ///< stiffness_ takes each confident estimate
  int pass(double t) const;  ///< the pass time t falls in (clamped to the window's)
  long samples_ = 0, bad_data_ = 0;
};

}  // namespace flexgait::compensation
