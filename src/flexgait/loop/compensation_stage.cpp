#include "flexgait/loop/compensation_stage.hpp"

#include "flexgait/walking/leg_kinematics.hpp"
#include "flexgait/walking/rotation.hpp"

namespace flexgait::loop {

CompensationStage::CompensationStage(const walking::RobotModel& model, const compensation::CompensationParams& params,
                                     double period, const StiffnessWindows& windows)
    : compensator_(model, params, period) {
  if (params.k_estimation == compensation::KEstimation::kOn) {
    estimator_.emplace(model, params, period, windows.rest_end);
    if (params.k_estimation_torque == compensation::KTorque::kMeasured)
      measured_torque_.emplace(params.rotor_inertia, period);
  }
  if (params.k_estimation == compensation::KEstimation::kCalibrate)
    calibration_.emplace(model, params, period, windows.calibration_begin, windows.calibration_end);
}

humanoid::SensorReadings CompensationStage::feedback(const humanoid::SensorReadings& raw) const {
  humanoid::SensorReadings readings = raw;
  if (compensator_.params().compensated_feedback)
    for (int j = 0; j < humanoid::kJoints; ++j) readings.encoder[j] += deflection_estimate_[j];
  return readings;
}

const humanoid::JointVector& CompensationStage::command(const humanoid::JointVector& desired,
                                                        const ControlContext& context, double t) {
  const compensation::CompensationParams& params = compensator_.params();
  const compensation::SupportPlan& support = context.support;
  sensors_ = context.sensors;
  if (params.compensated_feedback)
    for (int j = 0; j < humanoid::kJoints; ++j) sensors_.encoder[j] -= deflection_estimate_[j];
  if (params.load_model != compensation::LoadModel::kGravity) compensator_.sense(sensors_.ft);
  command_ = compensator_.input(desired, support.pelvis.R, support);
  estimate_ = params.output() ? &compensator_.output(sensors_.encoder, context.attitude, support) : nullptr;
  if (estimate_ && params.compensated_feedback)
    for (int j = 0; j < humanoid::kJoints; ++j) deflection_estimate_[j] = estimate_->newton[j] - sensors_.encoder[j];
  if (estimator_ || calibration_) {
    // The torque the output compensator solved with, or the servos' measured one (docs/guide/compensation.md,
    // "Stiffness identified while walking").
    const humanoid::JointVector& tau = measured_torque_
                                           ? measured_torque_->update(sensors_.motor_torque, sensors_.encoder)
                                       : estimate_ ? estimate_->gravity_torque
                                                   : compensator_.torque(sensors_.encoder, context.attitude, support);
    if (estimator_) {
      estimator_->update(t, sensors_.encoder, context.attitude, sensors_.imu, tau, sensors_.ft, support,
                         context.sensors_good);
      compensator_.set_stiffness(estimator_->stiffness());
    } else {
      calibration_->update(t, sensors_.encoder, tau, sensors_.ft, support, context.sensors_good);
      compensator_.set_stiffness(calibration_->stiffness());
    }
  }
  return command_;
}

std::optional<humanoid::JointVector> CompensationStage::k_estimate() const {
  if (estimator_) return estimator_->estimate();
  if (calibration_) return calibration_->estimate();
  return std::nullopt;
}

std::optional<humanoid::JointVector> CompensationStage::k_relative_std() const {
  if (!estimator_ && !calibration_) return std::nullopt;
  humanoid::JointVector s{};
  for (int j = 0; j < humanoid::kJoints; ++j)
    s[j] = estimator_ ? estimator_->relative_std(j) : calibration_->relative_std(j);
  return s;
}

bool CompensationStage::k_identified(int joint) const {
  if (estimator_) return estimator_->identified(joint);
  if (calibration_) return calibration_->identified(joint);
  return false;
}

ControlContext CompensationStage::standing_context(const walking::RobotModel& model,
                                                   const humanoid::SensorReadings& sensors) {
  ControlContext c;
  c.sensors = sensors;
  c.attitude = walking::quat_to_matrix(sensors.imu.quat.data());
  c.support.pelvis.R = c.attitude;
  Eigen::Vector2d middle = Eigen::Vector2d::Zero();
  for (int side = 0; side < 2; ++side) {
    walking::LegAngles a{};
    for (int i = 0; i < humanoid::kLegJoints; ++i) a[i] = sensors.encoder[humanoid::leg_first_joint(side) + i];
    const walking::Pose local = walking::leg_forward_kinematics(model.leg[side], a);
    c.support.soles[side] = {c.attitude * local.p, c.attitude * local.R};
    middle += 0.5 * c.support.soles[side].p.head<2>();
  }
  c.support.zmp_ref = middle;
  return c;
}

}  // namespace flexgait::loop
