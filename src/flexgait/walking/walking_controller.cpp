#include "flexgait/walking/walking_controller.hpp"

#include "flexgait/robot/convex_hull.hpp"
#include "flexgait/walking/foot_wrench.hpp"
#include "flexgait/walking/stance_load.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace flexgait::walking {
namespace {

/// Step adjustment replans when a landing moves by this much [m] (fewer rewrites of the reference).
constexpr double kReplanDistance = 0.005;
/// Step adjustment ends at this share of the swing (later, the swing foot's path would turn too sharply).
constexpr double kLastAdjustment = 0.75;
/// An adjusted step's swing foot loaded past this share of its swing (the arc's apex, footstep_plan.cpp)
/// has landed early (S3); before it, a loaded swing foot scuffs the floor on its way up.
constexpr double kEarlyLandingPhase = 0.5;
constexpr double kCaptureSettle =
    0.5;  ///< after a capture step the ZMP moves from the landed foot to the feet's middle in this [s]
/// Once the stance leg could not carry the load alone, the capture step's foot lifts after the
/// load has been within its joints' limit this long [s]: three periods, a few of the contact's
/// (plant.contact_time_constant 5 ms) and the servos' (30 Hz) time constants, over which the
/// vertical load rings during a push.
constexpr double kCaptureLiftHold = 0.012;
/// kCaptureLiftHold in control periods (whole ones, at least the time).
int capture_lift_hold_periods(double period) {
  return static_cast<int>(std::ceil(kCaptureLiftHold / period - 1e-9));
}
/// The planned motion's COM Jacobian is taken again every this many periods (0.1 s at 4 ms).

/// Each component clamped to [−limit, limit].
Eigen::Vector2d clamp_abs(const Eigen::Vector2d& v, double limit) {
  return v.cwiseMax(-limit).cwiseMin(limit);
}

/// The point of the box of half-extents `half` (along and across `yaw`) about `centre` nearest `x` [m].
Eigen::Vector2d nearest_in_box(const Eigen::Vector2d& centre, double yaw, const Eigen::Vector2d& half,
                               const Eigen::Vector2d& x) {
  const Eigen::Rotation2Dd heading(yaw);
  return centre + heading * (heading.inverse() * (x - centre)).cwiseMax(-half).cwiseMin(half);
}

/// Where p projects on the segment right → left, as the left foot's share in [0, 1] (½ for coincident feet).
double left_share(const Eigen::Vector2d& left, const Eigen::Vector2d& right, const Eigen::Vector2d& p) {
  const Eigen::Vector2d span = left - right;
  return span.squaredNorm() > 1e-12 ? std::clamp((p - right).dot(span) / span.squaredNorm(), 0.0, 1.0) : 0.5;
}

/// The estimator's parameters with the robot model's gravity.
EstimatorParams with_gravity(EstimatorParams estimator, double gravity) {
  estimator.gravity = gravity;
  return estimator;
}

}  // namespace

using humanoid::leg_first_joint;

WalkingController::WalkingController(const humanoid::RobotParams& robot, const WalkParams& walk,
                                     const BalanceParams& balance, double period, const EstimatorParams& estimator,
                                     const HealthParams& health)
    : WalkingController(make_robot_model(robot), walk, balance, period, estimator, health) {}

WalkingController::WalkingController(const RobotModel& model, const WalkParams& walk, const BalanceParams& balance,
                                     double period, const EstimatorParams& estimator, const HealthParams& health)
    : walk_(walk),
      balance_(balance),
      period_(period),
      model_(model),
      landing_(LandingGains{balance.landing_admittance, balance.landing_window, balance.landing_tilt_limit}),
      dcm_(DcmGains{balance.dcm_kp, balance.dcm_ki, balance.dcm_integral_limit}),
      estimator_params_(with_gravity(estimator, model.gravity)),
      estimator_(estimator_params_),
      tilt_(TiltObserverGains{estimator.tilt_alpha, estimator.tilt_beta, estimator.tilt_gamma, model.gravity}),
      health_(health, period) {
  if (!(period > 0)) throw std::invalid_argument("WalkingController: the period must be positive");
  plan_ = plan_footsteps(walk_);
  plan_.steps.reserve(plan_.steps.size() + 1);  // room for a recovery step (adjust_steps)
  // The initial standing pose: COM over the middle of the feet, pelvis level at its height.
  const FeetTarget feet = feet_target(plan_, walk_.swing_height, 0.0);
  pelvis_.p = Vector3d(0, 0, walk_.pelvis_height);
  solve_pose(zmp_reference(plan_, 0.0), feet.sole, Matrix3d::Identity(), 20, true);
  initial_pose_ = desired_;
  // What a sensor that is bad from its first sample reads as: the robot at rest in this pose,
  // level (specific force +g up), the F/T sensors unloaded (no ZMP from them).
  humanoid::SensorReadings rest;
  rest.encoder = initial_pose_;
  rest.imu.accel = {0, 0, model_.gravity};
  health_.set_nominal(rest);
  const double com_height = center_of_mass(model_, data_).z();
  gains_ = preview_gains(period_, com_height, model_.gravity, walk_.preview_time, walk_.preview_q, walk_.preview_r);
  // The reference over the whole plan and one horizon beyond (held at its final value).
  const auto samples = static_cast<std::size_t>(std::ceil(plan_.duration / period_)) + gains_.G_p.size() + 2;
  ref_x_.resize(samples);
  ref_y_.resize(samples);
  for (std::size_t k = 0; k < samples; ++k) {
    const Eigen::Vector2d p = planned_zmp(static_cast<double>(k) * period_);
    ref_x_[k] = p.x();
    ref_y_[k] = p.y();
  }
  const Eigen::Vector2d p0 = zmp_reference(plan_, 0.0);
  zmp_filtered_ = {p0, p0};
  for (int axis = 0; axis < 2; ++axis) cart_[axis].x = Eigen::Vector3d(p0(axis), 0, 0);
}

Eigen::Vector2d WalkingController::planned_zmp(double t) const {
  // (the stiffness calibration moves the COM through the ZMP reference)
  const CalibrationOffset c = calibration_offset(walk_.calibration, t);
  return zmp_reference(plan_, t) + Eigen::Vector2d(c.com_x, c.com_y);
}

void WalkingController::solve_pose(const Eigen::Vector2d& com, const std::array<Pose, 2>& soles,
                                   const Matrix3d& pelvis_R, int iterations, bool kinematics) {
  pelvis_.R = pelvis_R;
  solve_com_pose(model_, data_, com, soles, pelvis_, desired_, status_.ik, iterations, kinematics);
}

void WalkingController::measure_zmp(const humanoid::SensorReadings& s) {
  const double m_foot = model_.bodies[model_.foot[0]].mass;
  double fz_total = 0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  for (int side = 0; side < 2; ++side) {
    const Pose& sole = status_.sole[side];
    const FootContact c = foot_contact(s.ft[side], sole.R, model_.leg[side].ankle_to_sole, m_foot, model_.gravity,
                                       model_.ft_to_sole[side].head<2>());  // about the sole centre, sole.p
    foot_contact_[side] = c;
    status_.contact[side] = c.normal_force > balance_.contact_force;
    status_.foot_force[side] = c.normal_force;
    if (c.normal_force <= 1.0) continue;
    const Vector3d world = sole.p + sole.R * Vector3d(c.cop.x(), c.cop.y(), 0);
    moment += c.normal_force * world.head<2>();
    fz_total += c.normal_force;
    // Foot torque compliance: δ̇ = τ / D (the return term is applied in update).
    if (balance_.enabled && balance_.mode == BalanceMode::kPd && ft_live_ && status_.contact[side])
      foot_rotation_[side] += period_ * (c.torque / balance_.ankle_damping);
  }
  status_.zmp_valid = fz_total > balance_.contact_force;
  if (status_.zmp_valid) status_.zmp_measured = moment / fz_total;
}

Eigen::Vector2d WalkingController::load_split_point() const {
  // pd: the ZMP reference. dcm: the stabiliser's command while the robot stands where it began (a
  // plan without steps: the load split is its main lateral authority); once the plan steps
  // (walking, or a capture step) the reference, and the command's difference from it goes to the
  // soles' centres of pressure (dcm_balance). Measured (docs/guide/humanoid.md): split by the command while
  // walking, the load shifts and the COM estimate, anchored at the soles by their loads, feed each
  // other — after a capture step the loads switch between the staggered feet at 12 Hz (true ZMP
  // 0.036 m rms), and the largest lateral push walking at 1 s/step is 7.0–41.4 N s against
  // 10.2–42.2 by the reference.
  const bool dcm = balance_.enabled && balance_.mode == BalanceMode::kDcm;
  // (S3): from an adjusted step's early landing until the next step lifts, the command (the
  // reference would hold the load on the old stance foot while the DCM runs over the new one).
  if (dcm && early_landing_step_ >= 0 && early_landing_step_ >= status_.step - 1 &&
      (early_landing_step_ == status_.step ||
       (status_.step < static_cast<int>(plan_.steps.size()) &&
        status_.t + period_ < plan_.steps[static_cast<std::size_t>(status_.step)].t_lift)))
    return status_.zmp_command;
  return dcm && plan_.steps.empty() && !capture_.active ? status_.zmp_command : status_.zmp_ref;
}

void WalkingController::update_foot_lift(const FeetTarget& feet, const Eigen::Vector2d& zmp) {
  // Foot force control: the load each foot should carry follows the ZMP reference between the
  // sole centres (all of it on the stance foot in single support); a foot carrying more than its
  // share is raised, ż = (f − f_d) / D_z − z / T_z (a swing foot landing early gives way).
  const double share_left = left_share(feet.sole[0].p.head<2>(), feet.sole[1].p.head<2>(), zmp);
  const double load = std::max(0.0, status_.foot_force[0]) + std::max(0.0, status_.foot_force[1]);
  for (int side = 0; side < 2; ++side) {
    const double desired = (side == 0 ? share_left : 1.0 - share_left) * load;
    double& z = foot_lift_[side];
    // With an F/T reading held, only the return term acts.
    const double force_term =
        ft_live_ ? (std::max(0.0, status_.foot_force[side]) - desired) / balance_.foot_force_damping : 0.0;
    z += period_ * (force_term - z / balance_.foot_return_time);
    if (!balance_.enabled) z = 0;
    z = std::clamp(z, -balance_.foot_lift_limit, balance_.foot_lift_limit);
  }
  status_.foot_lift = foot_lift_;
}

Eigen::Vector2d WalkingController::zmp_feedback() {
  // ZMP feedback: the gear deflections move the real COM away from the plan by centimetres; shift
  // the commanded COM until the measured ZMP follows the reference (PI, clamped, anti-windup).
  if (!balance_.enabled || balance_.mode != BalanceMode::kPd) return Eigen::Vector2d::Zero();
  if (ft_failed_) zmp_integral_ *= 1.0 - period_ / (health_.params().fade_time + period_);  // fades out
  if (!status_.zmp_valid || !ft_live_) return zmp_integral_;                                // held
  // The measured ZMP carries −(z/g) c̈ (it leads the COM with the opposite sign at high
  // frequency): filter it twice (first order, balance.zmp_filter_time each) before use.
  const double a = period_ / (balance_.zmp_filter_time + period_);
  for (int stage = 0; stage < 2; ++stage)
    zmp_filtered_[stage] += a * ((stage == 0 ? status_.zmp_measured : zmp_filtered_[0]) - zmp_filtered_[stage]);
  const Eigen::Vector2d error = status_.zmp_ref - zmp_filtered_[1];
  zmp_integral_ = clamp_abs(zmp_integral_ + period_ * balance_.zmp_ki * error, balance_.zmp_limit);
  return clamp_abs(zmp_integral_ + balance_.zmp_kp * error, balance_.zmp_limit);
}

void WalkingController::dcm_balance(const humanoid::SensorReadings& s, const FeetTarget& feet, double yaw) {
  // The COM by kinematics: the encoders' pose under the estimated pelvis attitude, placed so that
  // the loaded soles sit where the plan put them (their offsets weighted by the F/T loads).
  const Pose pelvis{Vector3d::Zero(), rpy_to_matrix(status_.imu_roll, status_.imu_pitch, yaw)};
  forward_kinematics(model_, estimate_data_, pelvis, s.encoder);
  Vector3d anchor = Vector3d::Zero();
  double weight = 0;
  for (int side = 0; side < 2; ++side) {
    if (feet.swinging[side]) continue;
    const double w = std::max(foot_contact_[side].normal_force, 1.0);
    anchor += w * (feet.sole[side].p - sole_pose(model_, estimate_data_, side).p);
    weight += w;
  }
  if (weight > 0) anchor /= weight;  // (a plan never swings both feet)
  const Eigen::Vector2d kinematic = (center_of_mass(model_, estimate_data_) + anchor).head<2>();
  if (balance_.com_bias_time > 0 && status_.zmp_valid && ft_live_)
    com_bias_ += period_ / (balance_.com_bias_time + period_) * (status_.zmp_measured - kinematic - com_bias_);
  const Eigen::Vector2d com = kinematic + com_bias_;
  if (com_estimated_) {
    const double a = period_ / (balance_.com_velocity_filter_time + period_);
    com_velocity_ += a * ((com - status_.com_estimate) / period_ - com_velocity_);
  }
  com_estimated_ = true;
  status_.com_estimate = com;
  const double omega = std::sqrt(model_.gravity / gains_.com_height);
  status_.dcm = dcm_of(com, com_velocity_, omega);
  status_.dcm_ref =
      dcm_of(Eigen::Vector2d(cart_[0].x(0), cart_[1].x(0)), Eigen::Vector2d(cart_[0].x(1), cart_[1].x(1)), omega);
  const Eigen::Vector2d p = dcm_.zmp_command(status_.dcm, status_.dcm_ref, status_.zmp_ref, omega, period_, !ft_live_);
  status_.zmp_command = p;
  // Distribution: the load shares follow load_split_point() along the line between the soles
  // (update_foot_lift); what is off it goes under each loaded sole as its centre of pressure.
  const Eigen::Vector2d left = feet.sole[0].p.head<2>(), right = feet.sole[1].p.head<2>();
  Eigen::Vector2d base = feet.swinging[0] ? right : left;
  if (!feet.swinging[0] && !feet.swinging[1])
    base = right + left_share(left, right, load_split_point()) * (left - right);
  for (int side = 0; side < 2; ++side) {
    if (feet.swinging[side] || !status_.contact[side] || !ft_live_) continue;
    const Matrix3d& R = feet.sole[side].R;
    const Vector3d off = R.transpose() * Vector3d(p.x() - base.x(), p.y() - base.y(), 0);
    const Eigen::Vector2d cop = nearest_point(model_.sole_polygon[side], off.head<2>());
    const double fz = foot_contact_[side].normal_force;
    const Eigen::Vector2d torque_wanted(cop.y() * fz, -cop.x() * fz);  // ground torque about the sole centre
    foot_rotation_[side] += period_ * balance_.cop_admittance * ft_fade_ * (foot_contact_[side].torque - torque_wanted);
  }
}

void WalkingController::check_sensors(const humanoid::SensorReadings& raw, double t, std::size_t k) {
  using namespace humanoid;
  health_.set_unloaded(status_.swinging);  // (the plan's swing at t, set by the last update)
  health_.check(raw, t);
  const SensorReadings& s = health_.clean();
  // (source tilt: the Mahony filter runs beside the tilt observer, which starts from its levelling)
  const bool mahony = estimator_params_.source != AttitudeSource::kAhrs;
  // The sensors this controller uses; the first of them to fail stops the walk.
  const std::array<bool, kSensors> used = {true, true, true, mahony, !mahony, true};
  for (int i = 0; i < kSensors; ++i) {
    if (!used[i] || !health_.failed(i)) continue;
    ft_failed_ = ft_failed_ || i == kFtLeft || i == kFtRight;
    imu_failed_ = imu_failed_ || i == kGyro || i == kAccel || i == kAhrs;
    if (!safe_stop_.active && health_.params().safe_stop) {
      safe_stop_.sensor = static_cast<SensorId>(i);
      safe_stop_.fault = health_.fault(i);
      begin_safe_stop(t, k);
    }
  }
  status_.sensor_flags = health_.flags();
  status_.safe_stop = safe_stop_.active;
  ft_live_ = !health_.bad(kFtLeft) && !health_.bad(kFtRight);
  gyro_live_ = !health_.bad(kGyro);
  const double fade = 1.0 - period_ / (health_.params().fade_time + period_);
  if (ft_failed_) ft_fade_ *= fade;
  if (imu_failed_) imu_fade_ *= fade;

  // The attitude: the Mahony filter holds while the gyro is bad and runs on the gyro alone while
  // the accelerometer is; the AHRS output is held by the health check.
  if (mahony) {
    if (gyro_live_) {
      const Vector3d gyro(s.imu.gyro[0], s.imu.gyro[1], s.imu.gyro[2]);
      const Vector3d accel(s.imu.accel[0], s.imu.accel[1], s.imu.accel[2]);
      const Vector3d planned(cart_[0].x(2), cart_[1].x(2), 0.0);  // the COM's acceleration now
      estimator_.update(gyro, health_.bad(kAccel) ? nullptr : &accel, planned, period_);
      if (estimator_params_.source == AttitudeSource::kTilt)
        update_tilt(s, gyro, health_.bad(kAccel) ? nullptr : &accel);
    }
    attitude_ = estimator_.attitude();
    if (tilt_.started()) {
      const Eigen::Vector2d roll_pitch = roll_pitch_of_tilt(tilt_.tilt());
      attitude_ = rpy_to_matrix(roll_pitch(0), roll_pitch(1), yaw_of(attitude_));  // (yaw: the gyro's)
    }
  } else {
    bool finite = true;
    for (double q : s.imu.quat) finite = finite && std::isfinite(q);
    if (finite) attitude_ = quat_to_matrix(s.imu.quat.data());  // else: never a good one yet, keep
  }
}

void WalkingController::update_tilt(const humanoid::SensorReadings& s, const Vector3d& gyro, const Vector3d* accel) {
  // (T2): each loaded sole centre, placed in the pelvis (IMU) frame by the encoders, is an anchor
  // at rest; their velocities are averaged with the F/T loads as weights.
  forward_kinematics(model_, tilt_data_, Pose{}, s.encoder);
  const Vector3d omega = gyro - estimator_.bias();
  Vector3d y_v = Vector3d::Zero();
  double weight = 0;
  for (int side = 0; side < 2; ++side) {
    const Vector3d p = sole_pose(model_, tilt_data_, side).p;
    const double f = foot_contact_[side].normal_force;
    if (anchors_known_ && f > balance_.contact_force) {
      y_v -= f * (omega.cross(p) + (p - anchor_[side]) / period_);
      weight += f;
    }
    anchor_[side] = p;
  }
  anchors_known_ = true;
  if (!estimator_.initialised()) return;
  if (weight > 0) y_v /= weight;
  const Vector3d up = estimator_.attitude().transpose() * Vector3d::UnitZ();
  if (!tilt_.started()) {
    tilt_.reset(weight > 0 ? y_v : Vector3d::Zero(), up);  // from the Mahony filter's levelling
    return;
  }
  // Without the accelerometer: the specific force of a body at rest along the tilt.
  const Vector3d y_a = accel != nullptr ? *accel : Vector3d(estimator_params_.gravity * tilt_.tilt());
  tilt_.update(weight > 0 ? y_v : tilt_.velocity(), y_a, omega, period_);
}

void WalkingController::begin_safe_stop(double t, std::size_t k) {
  safe_stop_.active = true;
  safe_stop_.t = t;
  const FeetTarget feet = feet_target(plan_, walk_.swing_height, t + period_);
  const auto n = static_cast<int>(plan_.steps.size());
  // Where the ZMP reference starts blending to the middle of the feet, and from which value.
  std::size_t keep = plan_.steps.size();
  double t_blend = t;
  Eigen::Vector2d from(ref_x_[k], ref_y_[k]);
  if (feet.step >= n) {  // the walk has ended: nothing to cut
    safe_stop_.steps_kept = n;
    return;
  }
  if (feet.step < 0) {
    keep = 0;
  } else if (t + period_ >= plan_.steps[feet.step].t_lift) {  // swinging: finish this step
    const Step& st = plan_.steps[feet.step];
    keep = static_cast<std::size_t>(feet.step) + 1;
    t_blend = st.t_land;
    from = Eigen::Vector2d(st.stance.x, st.stance.y);
  } else {  // double support: the step is not taken
    keep = static_cast<std::size_t>(feet.step);
  }
  plan_.steps.resize(keep);  // shrinks: no allocation
  if (keep > 0) {
    const Step& last = plan_.steps.back();
    plan_.final[last.swing] = last.to;
    plan_.final[1 - last.swing] = last.stance;
  } else {
    plan_.final = plan_.initial;
  }
  const double blend_time = std::max(walk_.dsp_ratio * walk_.step_time, 0.2 * walk_.step_time);
  plan_.t_settle = std::max(t_blend, t) + blend_time;
  safe_stop_.steps_kept = static_cast<int>(keep);
  const Eigen::Vector2d mid(0.5 * (plan_.final[0].x + plan_.final[1].x), 0.5 * (plan_.final[0].y + plan_.final[1].y));
  for (std::size_t i = k; i < ref_x_.size(); ++i) {
    const double ti = static_cast<double>(i) * period_;
    if (ti < t_blend) continue;  // over the stance foot until the swing foot lands, as planned
    const Eigen::Vector2d p = from + quintic_blend((ti - t_blend) / blend_time) * (mid - from);
    ref_x_[i] = p.x();
    ref_y_[i] = p.y();
  }
}

void WalkingController::begin_capture_transfer(double t, std::size_t k, int swing, double omega) {
  // (C0) Both feet stay down while the stance leg could not carry the load alone: the centre of
  // pressure at the point of the feet's box (2 cm inside its edges) nearest the DCM, the COM
  // falling about it as the linear inverted pendulum from its estimated state. (Measured, docs/guide/humanoid.md:
  // lifting at once, 40 ms into a 0.1 s backward chest push, the stance knee needed 150–160 N m;
  // its 100 N m servo gave way, the knee bent 0.12 rad, the pelvis sank 2.6 cm and pitched back
  // 0.25 rad, the swing foot touched down 4.7 cm short; with a 150 N m servo the step recovered
  // 1.51 of the capture-point bound backward against 1.12.)
  const std::array<Footprint, 2>& f = plan_.initial;
  const Eigen::Vector2d mid(0.5 * (f[0].x + f[1].x), 0.5 * (f[0].y + f[1].y));
  const double width = std::hypot(f[0].x - f[1].x, f[0].y - f[1].y);
  const Eigen::Vector2d half(0.5 * model_.sole_length - kCaptureMargin,
                             0.5 * (model_.sole_width + width) - kCaptureMargin);
  const Eigen::Vector2d p = capture_sole_[0].rectangle && capture_sole_[1].rectangle
                                ? nearest_in_box(mid, f[1 - swing].yaw, half, status_.dcm)
                                : nearest_in_capture_soles(status_.dcm);
  for (int a = 0; a < 2; ++a) {
    const double c = status_.com_estimate(a);
    cart_[a].x = Vector3d(c, com_velocity_(a), omega * omega * (c - p(a)));
    cart_[a].error_sum = 0;
  }
  capture_ = {true, true, swing, t, p, capture_lift_hold_periods(period_) - 1};
  for (std::size_t i = k; i < ref_x_.size(); ++i) {
    ref_x_[i] = p.x();
    ref_y_[i] = p.y();
  }
}

bool WalkingController::capture_lift_due(double t) {
  if (!(balance_.capture_torque_limit > 0) || !ft_live_) return true;
  if (t - capture_.t_begin >= balance_.recovery_step_time) return true;
  // (L1): the ground force on both soles (F/T, estimated attitude) through the capture step's
  // centre of pressure on the stance sole (C1), carried by the stance leg alone. Its size is
  // the robot's weight: the vertical load rings with the contact while a push acts (measured
  // 350–1030 N, even airborne, against 560 N), its line — the push's trace — is what changes.
  const int stance = 1 - capture_.swing;
  Vector3d force = Vector3d::Zero();
  for (int side = 0; side < 2; ++side) force += sole_pose(model_, estimate_data_, side).R * foot_contact_[side].force;
  bool feasible = force.z() > balance_.contact_force;
  if (feasible) {
    const Footprint& f = plan_.initial[stance];
    const Eigen::Vector2d p = capture_cop(stance, status_.dcm);
    const Vector3d point = sole_pose(model_, estimate_data_, stance).p + Vector3d(p.x() - f.x, p.y() - f.y, 0);
    const LegTorque tau = stance_joint_torques(model_, estimate_data_, stance,
                                               force * (model_.total_mass * model_.gravity / force.z()), point);
    for (int i = 0; i < humanoid::kLegJoints; ++i) {
      const double own = balance_.capture_joint_torque_limit[humanoid::leg_first_joint(stance) + i];
      feasible = feasible && std::abs(tau(i)) <= (own > 0 ? own : balance_.capture_torque_limit);
    }
  }
  // Within the limit at once: lift now; once beyond it, lift after kCaptureLiftHold within it.
  capture_.feasible_periods = feasible ? capture_.feasible_periods + 1 : 0;
  return capture_.feasible_periods >= capture_lift_hold_periods(period_);
}

Eigen::Vector2d WalkingController::capture_cop(int stance, const Eigen::Vector2d& xi) const {
  const Footprint& f = plan_.initial[stance];
  const Eigen::Rotation2Dd heading(f.yaw);
  const Eigen::Vector2d centre(f.x, f.y);
  return centre + heading * nearest_point(capture_sole_[stance], heading.inverse() * (xi - centre));
}

Eigen::Vector2d WalkingController::nearest_in_capture_soles(const Eigen::Vector2d& xi) {
  std::size_t n = 0;
  for (int side = 0; side < 2; ++side) {
    const Footprint& f = plan_.initial[side];
    const Eigen::Rotation2Dd heading(f.yaw);
    for (const Eigen::Vector2d& c : capture_sole_[side].corners)
      transfer_points_[n++] = Eigen::Vector2d(f.x, f.y) + heading * c;
  }
  const std::size_t k = humanoid::convex_hull_into(transfer_points_.data(), n, transfer_hull_.data());
  return nearest_point(transfer_hull_.data(), k, xi);
}

void WalkingController::begin_capture_step(double t, std::size_t k, double omega, double T, double settle,
                                           const StepLimits& limits) {
  // (C1) the centre of pressure goes at once to the stance sole's point nearest the DCM, 2 cm
  // inside its edges; (C2) the COM falls about it as the linear inverted pendulum from its
  // reference state (the estimated one when (C0) lifts at once), so the DCM reference is ξ₀
  // diverging from p, ξ(τ) = p + (ξ₀ − p) e^{ωτ}; (C3) the swing foot lifts now and lands at ξ(T),
  // within reach.
  // (Moving the landing with the measured DCM during the swing, as walking steps do, recovered
  // less: 0.89–0.93 of the capture-point bound against 1.09–0.99 at T = 0.3–0.35 s.)
  const int swing = capture_.swing;
  const Footprint& stance = plan_.initial[1 - swing];
  const Eigen::Vector2d xi0 =
      dcm_of(Eigen::Vector2d(cart_[0].x(0), cart_[1].x(0)), Eigen::Vector2d(cart_[0].x(1), cart_[1].x(1)), omega);
  const Eigen::Vector2d centre(stance.x, stance.y), p = capture_cop(1 - swing, xi0);
  for (int a = 0; a < 2; ++a) cart_[a].x(2) = omega * omega * (cart_[a].x(0) - p(a));
  capture_.transfer = false;
  capture_.p = p;
  Step st;
  st.swing = swing;
  st.t_begin = capture_.t_begin;
  st.t_lift = t + period_;
  st.t_land = t + T;
  st.from = plan_.initial[swing];
  st.stance = stance;
  st.to = adjusted_landing(Footprint{p.x(), p.y(), stance.yaw, stance.z}, stance, swing, xi0 - p, omega, T, limits);
  st.to.yaw = st.from.yaw;
  st.to.z = st.from.z;
  status_.step_shift = Eigen::Vector2d(st.to.x - st.from.x, st.to.y - st.from.y);
  plan_.steps.push_back(st);  // reserved at construction: no allocation
  plan_.final[swing] = st.to;
  plan_.final[1 - swing] = stance;
  plan_.t_settle = st.t_land + settle;
  // The ZMP reference: p until the landing, then from the landed foot to the middle of the feet.
  const Eigen::Vector2d landed(st.to.x, st.to.y), mid = 0.5 * (landed + centre);
  for (std::size_t i = k; i < ref_x_.size(); ++i) {
    const double ti = static_cast<double>(i) * period_;
    const double b = quintic_blend(std::clamp((ti - st.t_land) / settle, 0.0, 1.0));
    const Eigen::Vector2d r = ti < st.t_land ? p : Eigen::Vector2d(landed + b * (mid - landed));
    ref_x_[i] = r.x();
    ref_y_[i] = r.y();
  }
}

void WalkingController::propagate_capture(double t) {
  // The linear inverted pendulum about p over one period, exactly: y = c − p,
  // (y, ẏ) ← (y cosh ωT + ẏ/ω sinh ωT, y ω sinh ωT + ẏ cosh ωT), c̈ = ω² y (its ZMP stays p).
  const double omega = std::sqrt(model_.gravity / gains_.com_height);
  const double ch = std::cosh(omega * period_), sh = std::sinh(omega * period_);
  for (int a = 0; a < 2; ++a) {
    Vector3d& x = cart_[a].x;
    const double y = x(0) - capture_.p(a), v = x(1);
    const double y1 = y * ch + v / omega * sh;
    x = Vector3d(capture_.p(a) + y1, y * omega * sh + v * ch, omega * omega * y1);
  }
  // Landed (the capture step is the plan's only step): the preview controller takes over.
  if (!capture_.transfer && t + period_ >= plan_.steps.back().t_land - 0.5 * period_) {
    capture_.active = false;
    for (CartTable& c : cart_) c.error_sum = 0;
  }
}

void WalkingController::adjust_steps(double t, std::size_t k, const FeetTarget& feet) {
  const double omega = std::sqrt(model_.gravity / gains_.com_height);
  const StepLimits limits{balance_.step_adjustment_limit, balance_.step_reach, model_.sole_width + 0.02};
  if (capture_.active) {  // a capture step's landing is set when its foot lifts
    if (capture_.transfer && capture_lift_due(t))
      begin_capture_step(t, k, omega, balance_.recovery_step_time, kCaptureSettle, limits);
    return;
  }
  const Eigen::Vector2d e = status_.dcm - status_.dcm_ref;
  const Eigen::Vector2d half(0.5 * model_.sole_length, 0.5 * model_.sole_width);
  const auto n = static_cast<int>(plan_.steps.size());
  if (feet.step >= 0 && feet.step < n) {
    // Walking (or the recovery step): from the step's double support to three quarters of its
    // swing, the landing is the planned one moved by (S2) for the error now.
    Step& s = plan_.steps[static_cast<std::size_t>(feet.step)];
    const double u0 = std::clamp((t + period_ - s.t_lift) / (s.t_land - s.t_lift), 0.0, 1.0);  // swing phase
    if (adjusted_step_ != feet.step) {
      adjusted_step_ = feet.step;
      planned_landing_ = s.to;
      step_adjusted_ = false;
    }
    if (early_landing_step_ == feet.step) return;  // landed (S3): the landing stays where the foot is
    Footprint to = planned_landing_;
    if (balance_.early_landing && step_adjusted_ && u0 > kEarlyLandingPhase && u0 < 1 && status_.contact[s.swing]) {
      // (S3) The swing foot meets the floor before its touchdown (the push rolls the robot toward
      // it): the step has landed, where the foot is by the encoders under the estimated attitude
      // (dcm_balance's kinematics) from the stance sole.
      early_landing_step_ = feet.step;
      const Vector3d at = feet.sole[1 - s.swing].p + sole_pose(model_, estimate_data_, s.swing).p -
                          sole_pose(model_, estimate_data_, 1 - s.swing).p;
      to.x = at.x();
      to.y = at.y();
    } else {
      if (u0 > kLastAdjustment) return;
      const Eigen::Vector2d beyond = dcm_error_beyond_sole(e, s.stance, half);
      if (beyond.squaredNorm() > 0) {
        step_adjusted_ = true;
        to = adjusted_landing(planned_landing_, s.stance, s.swing, beyond, omega, s.t_land - t, limits);
      }
    }
    const Eigen::Vector2d d(to.x - s.to.x, to.y - s.to.y);
    if (d.norm() < kReplanDistance) return;
    status_.step_shift = Eigen::Vector2d(to.x - planned_landing_.x, to.y - planned_landing_.y);
    if (u0 > 0) {
      // Mid-swing: the swing foot stays where it is, p0 = from + b0 (to − from), and goes on to the
      // new landing: from' = (p0 − b0 to') / (1 − b0), so that from' + b (to' − from') = p0 at b0.
      const double b0 = quintic_blend(u0);
      const Eigen::Vector2d from(s.from.x, s.from.y), old_to(s.to.x, s.to.y);
      const Eigen::Vector2d p0 = from + b0 * (old_to - from), new_from = (p0 - b0 * (old_to + d)) / (1 - b0);
      s.from.x = new_from.x();
      s.from.y = new_from.y();
    }
    // The footprints placed from this landing on move with it.
    auto move = [&](Footprint& f) { f.x += d.x(), f.y += d.y(); };
    for (int j = feet.step; j < n; ++j) {
      Step& sj = plan_.steps[static_cast<std::size_t>(j)];
      move(sj.to);
      if (j == feet.step) continue;
      move(sj.stance);
      if (j >= feet.step + 2) move(sj.from);
    }
    move(plan_.final[s.swing]);
    if (feet.step + 1 < n) move(plan_.final[1 - s.swing]);
  } else if (n == 0 && !recovery_step_) {
    // Standing: the support polygon of both feet (the box around them along their heading).
    const std::array<Footprint, 2>& f = plan_.initial;
    const Footprint mid{0.5 * (f[0].x + f[1].x), 0.5 * (f[0].y + f[1].y), f[0].yaw};
    const double width = std::hypot(f[0].x - f[1].x, f[0].y - f[1].y);
    const Eigen::Vector2d beyond = dcm_error_beyond_sole(e, mid, Eigen::Vector2d(half.x(), half.y() + 0.5 * width));
    if (beyond.squaredNorm() == 0) return;
    const double T = balance_.recovery_step_time;
    const double settle = kCaptureSettle;
    // The ZMP reference must hold the transfer, the step and its settling (with the preview horizon).
    if (static_cast<std::size_t>(std::ceil((t + 2 * T + settle) / period_)) + gains_.G_p.size() + 1 >= ref_x_.size())
      return;
    recovery_step_ = true;
    // The foot on the side the error leaves by steps; straight ahead or back, the less loaded one.
    const int swing = std::abs(beyond.y()) > 1e-3
                          ? (beyond.y() > 0 ? 0 : 1)
                          : (foot_contact_[0].normal_force < foot_contact_[1].normal_force ? 0 : 1);
    begin_capture_transfer(t, k, swing, omega);
    if (capture_lift_due(t)) begin_capture_step(t, k, omega, T, settle, limits);
    return;
  } else {
    return;
  }
  // The preview controller replans: the ZMP reference of the new plan from now on.
  for (std::size_t i = k; i < ref_x_.size(); ++i) {
    const Eigen::Vector2d p = planned_zmp(static_cast<double>(i) * period_);
    ref_x_[i] = p.x();
    ref_y_[i] = p.y();
  }
}

const humanoid::JointVector& WalkingController::update(const humanoid::SensorReadings& raw, double t) {
  status_.t = t;
  const auto last = ref_x_.size() - gains_.G_p.size() - 1;
  const auto k = std::min(static_cast<std::size_t>(std::max(0.0, std::round(t / period_))), last);
  check_sensors(raw, t, k);
  const humanoid::SensorReadings& s = health_.clean();
  status_.zmp_ref = Eigen::Vector2d(ref_x_[k], ref_y_[k]);
  if (capture_.active) {
    propagate_capture(t);
  } else {
    preview_step(gains_, cart_[0], &ref_x_[k]);
    preview_step(gains_, cart_[1], &ref_y_[k]);
  }
  status_.com_ref = Eigen::Vector2d(cart_[0].x(0), cart_[1].x(0));

  const FeetTarget feet = feet_target(plan_, walk_.swing_height, t + period_);
  const CalibrationOffset calibration = calibration_offset(walk_.calibration, t + period_);
  pelvis_.p.z() = walk_.pelvis_height + feet.floor_z + calibration.pelvis_z;  // (floor_z = 0 unless know_floor)
  status_.step = feet.step;
  status_.sole = feet.sole;
  status_.swinging = feet.swinging;

  // Balance: foot torques (and the measured ZMP), foot forces, pelvis attitude, ZMP feedback.
  status_.imu_roll = roll_of(attitude_);
  status_.imu_pitch = pitch_of(attitude_);
  measure_zmp(s);
  for (int side = 0; side < 2; ++side)
    landing_.update(side, t, period_, feet.swinging[side] || !balance_.enabled, status_.contact[side],
                    foot_contact_[side].torque, ft_live_);
  // Pelvis heading: the mean of the feet's headings (as unit vectors, so no wrap at ±π).
  const double yaw = heading_of(feet.sole);
  const bool dcm = balance_.enabled && balance_.mode == BalanceMode::kDcm;
  if (dcm) dcm_balance(s, feet, yaw);
  // (from walk.start_time on: the COM estimate settles while the robot first stands)
  if (dcm && balance_.step_adjustment && !safe_stop_.active && t >= walk_.start_time) adjust_steps(t, k, feet);
  for (int side = 0; side < 2; ++side) {
    if (!dcm) foot_rotation_[side] -= period_ / balance_.ankle_return_time * foot_rotation_[side];
    if (!balance_.enabled || feet.swinging[side]) foot_rotation_[side].setZero();
    foot_rotation_[side] = clamp_abs(foot_rotation_[side], balance_.ankle_limit);
  }
  status_.foot_rotation = foot_rotation_;
  update_foot_lift(feet, load_split_point());
  double d_roll = 0, d_pitch = 0;
  if (balance_.enabled) {
    d_roll = std::clamp(-(balance_.imu_kp * status_.imu_roll + balance_.imu_kd * s.imu.gyro[0]), -balance_.imu_limit,
                        balance_.imu_limit);
    d_pitch = std::clamp(-(balance_.imu_kp * status_.imu_pitch + balance_.imu_kd * s.imu.gyro[1]), -balance_.imu_limit,
                         balance_.imu_limit);
  }
  d_roll *= imu_fade_;
  d_pitch *= imu_fade_;
  status_.roll_correction = d_roll;
  status_.pitch_correction = d_pitch;
  status_.com_shift = zmp_feedback();

  std::array<Pose, 2> soles = feet.sole;
  // Sway damping: the whole body rocks on its compliant legs (a ~0.5 Hz mode, spec "Physics");
  // rotating the stance soles' commands with the IMU rate leans the body against the motion.
  // The rate is low-passed (balance.gyro_filter_time): unfiltered, the loop through the stiff
  // servos chatters at high frequency in double support.
  if (gyro_live_)  // held while the gyro is bad
    gyro_filtered_ += period_ / (balance_.gyro_filter_time + period_) *
                      (Eigen::Vector2d(s.imu.gyro[0], s.imu.gyro[1]) - gyro_filtered_);
  const Eigen::Vector2d sway = balance_.enabled ? Eigen::Vector2d(imu_fade_ * balance_.ankle_gyro_gain * gyro_filtered_)
                                                : Eigen::Vector2d::Zero();
  for (int side = 0; side < 2; ++side) {
    Eigen::Vector2d r =
        clamp_abs(foot_rotation_[side] + (feet.swinging[side] ? Eigen::Vector2d::Zero() : sway), balance_.ankle_limit);
    if (balance_.landing_admittance > 0) r += landing_.tilt(side);  // (landing_adaptation.hpp)
    r.x() += calibration.sole_roll[side];
    soles[side].R = soles[side].R * rot_y(r(1)) * rot_x(r(0));
    soles[side].p.z() += foot_lift_[side];
  }
  const Matrix3d pelvis_command = rpy_to_matrix(d_roll, d_pitch + calibration.pelvis_pitch, yaw);
  if (capture_.active) {
    // The capture step's swing foot is aimed from the pelvis as the IMU finds it: its target turns
    // about the pelvis by R_command R_estimatedᵀ, so the leg's command puts the foot at its world
    // target. (A chest push pitches the torso 0.1–0.2 rad during the step; aimed from the commanded
    // pelvis, the foot then lands 0.1 m behind its target: measured, 0.045 m against 0.17 m.)
    const Matrix3d C = pelvis_command * rpy_to_matrix(status_.imu_roll, status_.imu_pitch, yaw).transpose();
    for (int side = 0; side < 2; ++side) {
      if (!feet.swinging[side]) continue;
      soles[side].p = pelvis_.p + C * (soles[side].p - pelvis_.p);
      soles[side].R = C * soles[side].R;
    }
  }
  solve_pose(status_.com_ref + status_.com_shift, soles, pelvis_command, 2);
  status_.pelvis = pelvis_;
  const PlannedMotion last_motion = status_.motion;  // (the plan pose's guess below)
  status_.motion.valid = false;
  if (plan_motion_) {
    // The plan's own motion at the commanded pose's time (planned_motion.hpp): the balance's
    // corrections as constants.
    PlanPoseInputs in;
    in.model = &model_;
    in.plan = &plan_;
    in.swing_height = walk_.swing_height;
    in.pelvis_height = walk_.pelvis_height + calibration.pelvis_z;
    in.cart = {cart_[0].x, cart_[1].x};
    in.com_offset = status_.com_shift;
    in.tilt = rot_y(d_pitch + calibration.pelvis_pitch) * rot_x(d_roll);
    // From the last period's plan pose carried forward (carried_pelvis), else the commanded pose, the Jacobian by
    // differences there.
    const bool carried = last_motion.valid;
    Pose guess = pelvis_;
    if (carried)
      guess.p = carried_pelvis(last_motion, period_, Eigen::Vector2d(cart_[0].x(0), cart_[1].x(0)) + in.com_offset,
                               rot_z(yaw) * in.tilt, motion_jacobian_inverse_);
    status_.motion = planned_motion(in, t + period_, guess, motion_data_, motion_jacobian_inverse_, !carried);
  }
  status_.desired = desired_;
  return desired_;
}

}  // namespace flexgait::walking
