#include "flexgait/compensation/deformation_compensator.hpp"

#include <algorithm>
#include <cmath>

namespace flexgait::compensation {
namespace {

using humanoid::kJoints;
using humanoid::kLegJoints;
using humanoid::leg_first_joint;

const walking::PlannedMotion kAtRest{};  ///< the motion of the measured load model: none

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

DeformationCompensator::DeformationCompensator(const walking::RobotModel& model, const CompensationParams& params,
                                               double period)
    : model_(model),
      params_(params),
      period_(period),
      filter_gain_(params.load_filter_time > 0 ? 1.0 - std::exp(-period / params.load_filter_time) : 1.0),
      stiffness_(params.stiffness()),
      talos_{{TalosHipRoll(params.talos_cutoff, params.talos_limit, period),
              TalosHipRoll(params.talos_cutoff, params.talos_limit, period)}} {}

void DeformationCompensator::sense(const std::array<humanoid::ForceTorque, 2>& ft) {
  for (int side = 0; side < 2; ++side) {
    const walking::Vector3d f(ft[side].force.data()), m(ft[side].torque.data());
    ft_usable_[side] = f.allFinite() && m.allFinite();
    if (!ft_usable_[side]) continue;  // a failed sensor: the plan's split for this foot (torque_at)
    walking::Wrench& w = ft_[side];
    const double a = sensed_ ? filter_gain_ : 1.0;
    w.force += a * (f - w.force);
    w.moment += a * (m - w.moment);
  }
  sensed_ = true;
}

const humanoid::JointVector& DeformationCompensator::torque(const humanoid::JointVector& q, const walking::Matrix3d& R,
                                                            const SupportPlan& support) {
  split_by_plan(support);
  return torque_at(q, R, support);
}

const humanoid::JointVector& DeformationCompensator::torque_at(const humanoid::JointVector& q,
                                                               const walking::Matrix3d& R, const SupportPlan& support,
                                                               int first) {
  // The pelvis position does not change a gravity torque; only its attitude does.
  walking::forward_kinematics(model_, data_, walking::Pose{walking::Vector3d::Zero(), R}, q, first);
  if (params_.load_model == LoadModel::kGravity) {
    if (params_.split == WeightSplit::kCom) plan_loads_ = com_loads(model_, data_, support.swinging);
    tau_ = gravity_torque(model_, data_, plan_loads_, params_.gravity);
    return tau_;
  }
  // Each foot's F/T wrench (foot frame) turned into the world by this pose's foot frame.
  if (params_.split == WeightSplit::kCom && planned_cop_) plan_loads_ = com_loads(model_, data_, support.swinging);
  // control.plan_horizontal_force f > 0: the input side's ground wrench is the plan's own (plan_ground_wrench).
  const bool whole_body = planned_cop_ && params_.load_model == LoadModel::kDynamic && support.motion.valid &&
                          params_.plan_horizontal_force > 0 && plan_ground_wrench(support);
  for (int side = 0; side < 2; ++side) {
    const walking::Pose& foot = data_.frame[model_.foot[side]];
    // A stance foot's wrench is read; a swinging foot is the model's (its reading, a few tens of
    // newtons, disagrees with the foot's weight and planned motion by up to 40 N in the 1 s walk,
    // which moved the swing hip pitch's torque by 25 Nm).
    feet_.given[side] = sensed_ && !support.swinging[side];
    feet_.wrench[side] = {foot.R * ft_[side].force, foot.R * ft_[side].moment};
    // The output side reads a stance foot's F/T; while its reading is not finite, the foot carries the plan's
    // split below, as the gravity form assumes.
    if (!planned_cop_ && (!feet_.given[side] || ft_usable_[side])) continue;
    const walking::Pose sole = walking::sole_pose(model_, data_, side);
    const walking::Vector3d cop =
        sole.p + sole.R * walking::Vector3d(plan_loads_.cop[side].x(), plan_loads_.cop[side].y(), 0);
    if (whole_body) {
      // The foot's own Newton–Euler less its share of the plan's ground wrench: the force at its centre of
      // pressure (its horizontal part times f), the free moment about the vertical shared alike.
      walking::Vector3d ground = plan_loads_.share[side] * plan_ground_.force;
      ground.head<2>() *= params_.plan_horizontal_force;
      const walking::Vector3d free(0, 0, plan_loads_.share[side] * plan_ground_.moment.z());
      feet_.given[side] = true;
      feet_.wrench[side] = {foot_need_[side].force - ground,
                            foot_need_[side].moment - (cop - foot.p).cross(ground) - free};
      continue;
    }
    // The input side (a feed-forward): the plan's ground force, the weight shared as the split
    // says, at the split's centres of pressure. Not the F/T reading: fed into the commands it
    // closes a loop of gain ≈ 1 through the gears (a flat foot's ankle torque is k times the
    // command's change; in double support the feet's loads follow the legs' lengths), and the 1 s
    // walk falls. Nor M (g + a) with a the commanded pelvis's acceleration: that doubles the
    // 1 s walk's peak roll error. With control.plan_horizontal_force f > 0 the plan's
    // own ground wrench above.
    const auto& b = model_.bodies[static_cast<std::size_t>(model_.foot[side])];
    const walking::Vector3d weight(0, 0, -b.mass * model_.gravity);
    const double load = plan_loads_.share[side] * model_.total_mass;
    const walking::Vector3d ground(0, 0, load * model_.gravity);
    feet_.given[side] = true;
    feet_.wrench[side] = {-ground - weight, -(cop - foot.p).cross(ground) - (foot.R * b.com).cross(weight)};
  }
  const walking::PlannedMotion& m = params_.load_model == LoadModel::kDynamic ? support.motion : kAtRest;
  if (whole_body)  // plan_ground_wrench's forward pass was this pose's and motion's
    walking::inverse_dynamics_with_feet(model_, data_, dynamics_, feet_);
  else
    walking::inverse_dynamics(model_, data_, m.pelvis, m.velocity, m.acceleration, dynamics_, feet_, 1.0, first);
  tau_ = dynamics_.tau;
  tau_[humanoid::kWaistYaw] = 0.0;  // the waist carries no modelled load (as in the gravity form)
  return tau_;
}

bool DeformationCompensator::plan_ground_wrench(const SupportPlan& support) {
  // The whole body's Newton–Euler of the planned motion with no foot loaded: (f₀, n₀) at the pelvis is the wrench
  // the world must supply, i.e. the ground's (Featherstone 2008, §5.3; Sardain and Bessonnet 2004: its zero-moment
  // point is the plan's ZMP). Each foot's own need is kept for its given wrench.
  walking::inverse_dynamics(model_, data_, support.motion.pelvis, support.motion.velocity, support.motion.acceleration,
                            dynamics_);
  for (int side = 0; side < 2; ++side) foot_need_[side] = dynamics_.joint_wrench[model_.foot[side]];
  const walking::Vector3d f = dynamics_.joint_wrench[0].force;
  if (!(f.z() > 0)) return false;  // no push on the ground (a plan in free fall): the weight's split instead
  // Its centre of pressure p on the stance sole's plane: the moment about p has no horizontal part.
  const int anchor = support.swinging[0] ? 1 : 0;
  const walking::Pose sole = walking::sole_pose(model_, data_, anchor);
  const walking::Vector3d n = dynamics_.joint_wrench[0].moment + data_.frame[0].p.cross(f);  // about the origin
  const double z = sole.p.z();
  const walking::Vector3d p((z * f.x() - n.y()) / f.z(), (n.x() + z * f.y()) / f.z(), z);
  plan_ground_ = {f, n - p.cross(f)};
  // The same point in the world through the plan's sole, the split about it.
  const walking::Vector3d world =
      support.soles[anchor].p + support.soles[anchor].R * (sole.R.transpose() * (p - sole.p));
  plan_loads_ = support_loads(world.head<2>(), support.soles, support.swinging, model_.sole_polygon);
  return true;
}

void DeformationCompensator::split_by_plan(const SupportPlan& support) {
  if (params_.split == WeightSplit::kZmpReference)
    plan_loads_ = support_loads(support.zmp_ref, support.soles, support.swinging, model_.sole_polygon);
}

const humanoid::JointVector& DeformationCompensator::input(const humanoid::JointVector& desired,
                                                           const walking::Matrix3d& pelvis_R,
                                                           const SupportPlan& support) {
  command_ = desired;
  if (params_.mode == CompensationMode::kRobotis || params_.mode == CompensationMode::kTalos) {
    apply_baseline(desired, pelvis_R, support);
    return command_;
  }
  if (!params_.input()) {
    input_torque_.fill(0.0);
    return command_;
  }
  planned_cop_ = true;
  input_torque_ = torque(desired, pelvis_R, support);
  planned_cop_ = false;
  if (params_.gear_damping > 0) {
    // The Kelvin–Voigt lag of the deflection (from the static one in the first period).
    for (int j = 0; j < kJoints; ++j) {
      const double a = input_lagged_ ? lag_weight(j) : 1.0;
      input_deflection_[j] = a * input_torque_[j] / stiffness_[j] + (1 - a) * input_deflection_[j];
      command_[j] += input_deflection_[j];
    }
    input_lagged_ = true;
    return command_;
  }
  for (int j = 0; j < kJoints; ++j) command_[j] += input_torque_[j] / stiffness_[j];  // eq. 9
  return command_;
}

void DeformationCompensator::apply_baseline(const humanoid::JointVector& desired, const walking::Matrix3d& pelvis_R,
                                            const SupportPlan& support) {
  // Both read the modelled hip roll torque: TALOS its size, ROBOTIS only its sign (the direction
  // of the stance hip roll's sag, which its fixed feed-forward opposes: θ_cmd − θ_d has the sign of
  // τ, eq. 9).
  const bool talos = params_.mode == CompensationMode::kTalos;
  input_torque_ = torque(desired, pelvis_R, support);
  for (int side = 0; side < 2; ++side) {
    const int hip_roll = leg_first_joint(side) + 1;
    if (talos) {
      const double tau = support.swinging[side] ? 0.0 : input_torque_[hip_roll];
      command_[hip_roll] += talos_[side].update(tau, stiffness_[hip_roll]);
    } else if (!support.swinging[side] && support.swinging[1 - side]) {
      const double against_sag = input_torque_[hip_roll] >= 0 ? 1.0 : -1.0;
      command_[hip_roll] += robotis_hip_roll(support.single_support_phase, params_.robotis_hip_roll, against_sag);
    }
  }
}

double DeformationCompensator::lag_weight(int j) const {
  return params_.gear_damping > 0 ? period_ / (period_ + params_.gear_damping / stiffness_[j]) : 1.0;
}

const OutputEstimate& DeformationCompensator::output(const humanoid::JointVector& encoder,
                                                     const walking::Matrix3d& imu_R, const SupportPlan& support) {
  split_by_plan(support);
  q_ = encoder;
  const double h = params_.fd_step;
  using LegMatrix = Eigen::Matrix<double, kLegDofs, kLegDofs>;
  // The first evaluation (at the encoders) is whole; the others change the legs' angles alone.
  int first = 0;
  auto leg_torque = [&](const LegVector& theta, LegVector& tau) {
    set_legs(q_, theta);
    tau = legs_of(torque_at(q_, imu_R, support, first));
    first = walking::kFirstLegBody;
  };
  // G = ∂τ_g/∂θ. Each leg's torque depends on its own joints only unless the loads depend on the pose:
  // G is block diagonal, each block the analytic derivative at the pose of the last torque evaluation
  // (gravity_torque_derivative, walking::inverse_dynamics_derivative). The gravity loads split about the
  // pose's COM couple the legs through μ and the centres of pressure: forward differences, all 12 columns. So does a
  // stance foot whose F/T reading failed (its load the plan's split at the sole's centre of pressure, which moves
  // with the pose, where the analytic derivative holds a read wrench fixed in the foot).
  const bool ft_failed = params_.load_model != LoadModel::kGravity && sensed_ &&
                         ((!ft_usable_[0] && !support.swinging[0]) || (!ft_usable_[1] && !support.swinging[1]));
  const bool coupled = (params_.split == WeightSplit::kCom && params_.load_model == LoadModel::kGravity) || ft_failed;
  auto leg_jacobian = [&](const LegVector& theta, const LegVector& tau, LegMatrix& G) {
    G.setZero();
    if (coupled) {
      for (int j = 0; j < kLegDofs; ++j) {
        LegVector shifted = theta;
        shifted(j) += h;
        set_legs(q_, shifted);
        G.col(j) = (legs_of(torque_at(q_, imu_R, support, first)) - tau) / h;
      }
      return;
    }
    if (legs_of(q_) != theta) {  // data_ and dynamics_ must hold this pose
      set_legs(q_, theta);
      torque_at(q_, imu_R, support, first);
    }
    for (int side = 0; side < 2; ++side) {
      const int o = side * kLegJoints;
      if (params_.load_model == LoadModel::kGravity) {
        G.block<kLegJoints, kLegJoints>(o, o) =
            gravity_torque_derivative(model_, data_, plan_loads_, params_.gravity, side);
        continue;
      }
      G.block<kLegJoints, kLegJoints>(o, o) =
          walking::inverse_dynamics_derivative(model_, data_, dynamics_, feet_, side);
    }
  };
  // control.gear_damping: eq. 11 with the Kelvin–Voigt lag, k/a and θ_enc − (1 − a) δ_{n−1}.
  const bool lagged = params_.gear_damping > 0 && output_lagged_;
  LegVector observed = legs_of(encoder), stiffness = legs_of(stiffness_);
  if (lagged) {
    const LegVector& previous = deflection_[0];
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < kLegJoints; ++i) {
        const int r = side * kLegJoints + i;
        const double a = lag_weight(leg_first_joint(side) + i);
        observed(r) -= (1 - a) * previous(r);
        stiffness(r) /= a;
      }
  }
  // A new support or coupling changes G's form: the factorisation and the deflections' history start again. A new
  // stiffness (k estimation, the lag's k/a) leaves both: Newton's residual holds the new K, so the chord converges to
  // the same root, and a factor gone stale (a step cutting the residual less than kKeptChordContraction) is formed
  // again.
  if (kept_swinging_ != support.swinging || kept_coupled_ != coupled) {
    kept_.forget();
    extrapolable_ = 0;
  }
  kept_swinging_ = support.swinging;
  kept_coupled_ = coupled;
  // Newton's start: θ_enc less the deflection extrapolated from the last three periods by the parabola through
  // them, δ ≈ 3δ₁ − 3δ₂ + δ₃ (its error ~ δ⃛ T³; θ_enc itself is off by the whole deflection, ~1e-2 rad); from the
  // last two or one while there are fewer since the factorisation was formed.
  const LegVector encoder_legs = legs_of(encoder);
  LegVector start = encoder_legs;
  if (extrapolable_ == 1) start -= deflection_[0];
  if (extrapolable_ == 2) start -= 2 * deflection_[0] - deflection_[1];
  if (extrapolable_ == 3) start -= 3 * (deflection_[0] - deflection_[1]) + deflection_[2];
  const LinkAngleEstimate<kLegDofs> e =
      solve_link_angles<kLegDofs>(observed, stiffness, leg_torque, leg_jacobian, params_.newton, !coupled, &kept_,
                                  forms_, extrapolable_ > 0 ? &start : nullptr);
  deflection_[2] = deflection_[1];
  deflection_[1] = deflection_[0];
  deflection_[0] = encoder_legs - e.newton;
  output_lagged_ = true;
  if (e.converged) {
    extrapolable_ = std::min(extrapolable_ + 1, 3);
  } else {
    kept_.forget();
    extrapolable_ = 0;
  }
  estimate_.newton = estimate_.one_step = estimate_.per_joint = estimate_.conventional = encoder;  // the waist: no τ_g
  set_legs(estimate_.newton, e.newton);
  set_legs(estimate_.one_step, e.one_step);
  set_legs(estimate_.per_joint, e.per_joint);
  set_legs(estimate_.conventional, e.conventional);
  // τ_g(θ̂) as the solve left it (the waist carries no modelled load).
  estimate_.gravity_torque.fill(0.0);
  set_legs(estimate_.gravity_torque, e.torque);
  estimate_.iterations = e.iterations;
  estimate_.residual = e.residual;
  estimate_.converged = e.converged;
  estimate_.predicted = e.predicted;
  return estimate_;
}

}  // namespace flexgait::compensation
