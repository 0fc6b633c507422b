#pragma once
/// \file compensation_stage.hpp
/// The actuator deformation compensators as a stage around any controller (the thesis's Fig. 2:
/// input compensator → robot → encoders → output compensator; docs/theory/humanoid.md, "The
/// deformation model"), with the stiffness identification that feeds them
/// (docs/guide/compensation.md, "Stiffness identification"):
///  - on the readings: control.compensated_feedback adds the output compensator's last deflection
///    estimate θ̂ − θ_enc to the encoders the controller reads (the gears move little in a period);
///  - on the command: eqs. 8–9 (or a field baseline) turn the controller's desired angles into the
///    motor commands; eqs. 10–13 estimate the real joint angles from the encoders;
///  - control.k_estimation on / calibrate: the gears' stiffness identified online, handed to the
///    compensators.
/// With control.compensation off the command passes unchanged.
#include <optional>

#include "flexgait/compensation/chain_stiffness_calibration.hpp"
#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/compensation/measured_gear_torque.hpp"
#include "flexgait/compensation/stiffness_estimator.hpp"
#include "flexgait/loop/controller.hpp"
#include "flexgait/walking/robot_model.hpp"

namespace flexgait::loop {

/// When the robot stands still for the stiffness identification [s].
struct StiffnessWindows {
  double rest_end = 0;                                ///< the start stance ends (the gyro's rest: StiffnessEstimator)
  double calibration_begin = 0, calibration_end = 0;  ///< the calibration motion (ChainStiffnessCalibration)
};

class CompensationStage {
 public:
  /// \param model the controller's belief of the robot; \param period control period T [s]
  CompensationStage(const walking::RobotModel& model, const compensation::CompensationParams& params, double period,
                    const StiffnessWindows& windows = {});

  /// The readings the controller is given (control.compensated_feedback: encoders + θ̂ − θ_enc).
  humanoid::SensorReadings feedback(const humanoid::SensorReadings& raw) const;
  /// The motor commands for the controller's `desired` angles [rad]; runs the output compensator
  /// and the stiffness identification on this period's readings as `context` holds them.
  const humanoid::JointVector& command(const humanoid::JointVector& desired, const ControlContext& context, double t);

  /// The readings of the last command() as the controller used them, with the encoders' own values.
  const humanoid::SensorReadings& sensors() const { return sensors_; }
  /// The output compensator's estimate of the last command() (nullptr when it does not run).
  const compensation::OutputEstimate* estimate() const { return estimate_; }
  /// τ_g of the input compensator at the last desired pose [Nm].
  const humanoid::JointVector& input_torque() const { return compensator_.input_torque(); }
  const compensation::CompensationParams& params() const { return compensator_.params(); }
  /// The output estimate's one-step and per-joint forms formed each period (DeformationCompensator::estimate_forms).
  void estimate_forms(bool on) { compensator_.estimate_forms(on); }
  /// control.k_estimation on or calibrate: each joint's stiffness estimate [Nm/rad]; empty when off.
  std::optional<humanoid::JointVector> k_estimate() const;
  /// control.k_estimation on or calibrate: each joint's relative standard deviation sqrt(P)/c (the compensators use a
  /// joint's estimate once it is at most control.k_estimation_confidence); 0 where not identified; empty when off.
  std::optional<humanoid::JointVector> k_relative_std() const;
  /// The joints the identification identifies (false for all when off).
  bool k_identified(int joint) const;

  /// The context of a controller that reports none: both feet down where the encoders put them
  /// (leg forward kinematics from a pelvis at the origin), the pelvis attitude from the IMU's AHRS
  /// output, the reference ZMP between the soles, the robot at rest.
  static ControlContext standing_context(const walking::RobotModel& model, const humanoid::SensorReadings& sensors);

 private:
  compensation::DeformationCompensator compensator_;
  std::optional<compensation::StiffnessEstimator> estimator_;           ///< control.k_estimation on
  std::optional<compensation::MeasuredGearTorque> measured_torque_;     ///< control.k_estimation_torque measured
  std::optional<compensation::ChainStiffnessCalibration> calibration_;  ///< control.k_estimation calibrate
  humanoid::JointVector deflection_estimate_{};  ///< θ̂ − θ_enc of the last period (compensated_feedback)
  humanoid::JointVector command_{};
  humanoid::SensorReadings sensors_;
  const compensation::OutputEstimate* estimate_ = nullptr;
};

}  // namespace flexgait::loop
