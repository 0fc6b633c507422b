#include "flexgait/compensation/deformation_compensator.hpp"

namespace flexgait::compensation {
namespace {

using humanoid::kJoints;
using humanoid::kLegJoints;
using humanoid::leg_first_joint;

/// Leg joints (left then right, kinematic order) ↔ the joint vector.
LegVector legs_of(const humanoid::JointVector& v) {
  LegVector out;
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < kLegJoints; ++i) out(side * kLegJoints + i) = v[leg_first_joint(side) + i];
  return out;
}
void set_legs(humanoid::JointVector& v, const LegVector& legs) {
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < kLegJoints; ++i) v[leg_first_joint(side) + i] = legs(side * kLegJoints + i);
}

}  // namespace

DeformationCompensator::DeformationCompensator(const walking::RobotModel& model, const CompensationParams& params)
    : model_(model), params_(params), stiffness_(params.stiffness()) {}

const humanoid::JointVector& DeformationCompensator::torque(const humanoid::JointVector& q, const walking::Matrix3d& R,
                                                            const SupportPlan& support) {
  split_by_plan(support);
  return torque_at(q, R, support);
}

const humanoid::JointVector& DeformationCompensator::torque_at(const humanoid::JointVector& q,
                                                               const walking::Matrix3d& R, const SupportPlan& support) {
  // The pelvis position does not change a gravity torque; only its attitude does.
  walking::forward_kinematics(model_, data_, walking::Pose{walking::Vector3d::Zero(), R}, q);
  if (params_.split == WeightSplit::kCom) plan_loads_ = com_loads(model_, data_, support.swinging);
  tau_ = gravity_torque(model_, data_, plan_loads_, params_.gravity);
  return tau_;
}

void DeformationCompensator::split_by_plan(const SupportPlan& support) {
  if (params_.split == WeightSplit::kZmpReference)
    plan_loads_ = support_loads(support.zmp_ref, support.soles, support.swinging, model_.sole_length, model_.sole_width);
}

const humanoid::JointVector& DeformationCompensator::input(const humanoid::JointVector& desired,
                                                           const walking::Matrix3d& pelvis_R,
                                                           const SupportPlan& support) {
  command_ = desired;
  if (!params_.input()) {
    input_torque_.fill(0.0);
    return command_;
  }
  input_torque_ = torque(desired, pelvis_R, support);
  for (int j = 0; j < kJoints; ++j) command_[j] += input_torque_[j] / stiffness_[j];  // eq. 9
  return command_;
}

const OutputEstimate& DeformationCompensator::output(const humanoid::JointVector& encoder,
                                                     const walking::Matrix3d& imu_R,
                                                     const SupportPlan& support) {
  split_by_plan(support);
  q_ = encoder;
  const double h = params_.fd_step;
  using LegMatrix = Eigen::Matrix<double, kLegDofs, kLegDofs>;
  auto leg_torque = [&](const LegVector& theta, LegVector& tau) {
    set_legs(q_, theta);
    tau = legs_of(torque_at(q_, imu_R, support));
  };
  // G = ∂τ_g/∂θ by forward differences. With the split about the reference ZMP the loads do not
  // depend on θ, so each leg's torque depends on its own joints only: G is block diagonal and one
  // evaluation perturbs joint i of both legs at once (6 evaluations, not 12). The COM split
  // couples the legs through μ: all 12 columns.
  const bool block_diagonal = params_.split == WeightSplit::kZmpReference;
  auto leg_jacobian = [&](const LegVector& theta, const LegVector& tau, LegMatrix& G) {
    G.setZero();
    const int evaluations = block_diagonal ? kLegJoints : kLegDofs;
    for (int j = 0; j < evaluations; ++j) {
      LegVector shifted = theta;
      shifted(j) += h;
      if (block_diagonal) shifted(j + kLegJoints) += h;
      set_legs(q_, shifted);
      const LegVector difference = (legs_of(torque_at(q_, imu_R, support)) - tau) / h;
      if (!block_diagonal) {
        G.col(j) = difference;
        continue;
      }
      G.block<kLegJoints, 1>(0, j) = difference.head<kLegJoints>();
      G.block<kLegJoints, 1>(kLegJoints, j + kLegJoints) = difference.tail<kLegJoints>();
    }
  };
  const LinkAngleEstimate<kLegDofs> e = solve_link_angles<kLegDofs>(legs_of(encoder), legs_of(stiffness_),
                                                                    leg_torque, leg_jacobian, params_.newton);
  estimate_.newton = estimate_.one_step = estimate_.conventional = encoder;  // the waist carries no τ_g
  set_legs(estimate_.newton, e.newton);
  set_legs(estimate_.one_step, e.one_step);
  set_legs(estimate_.conventional, e.conventional);
  estimate_.gravity_torque = torque_at(estimate_.newton, imu_R, support);
  estimate_.iterations = e.iterations;
  estimate_.residual = e.residual;
  estimate_.converged = e.converged;
  return estimate_;
}

}  // namespace flexgait::compensation
