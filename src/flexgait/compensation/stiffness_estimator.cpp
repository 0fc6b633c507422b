#include "flexgait/compensation/stiffness_estimator.hpp"

#include <algorithm>
#include <cmath>

#include "flexgait/walking/foot_wrench.hpp"

namespace flexgait::compensation {

namespace {
constexpr double kStaleAge = 0.05;         // an F/T reading older than this is stale [s]
constexpr double kFirmWeightShare = 0.25;  // firm support: normal force ≥ this × the weight
constexpr double kFirmCopShare = 0.3;  // ... and the CoP on the sole shrunk about its centre to 2 × this (a rectangle:
                                       // |x| ≤ this × length, |y| ≤ this × width)
constexpr double kBoundFactor = 10.0;  // c ∈ [c₀/10, 10 c₀]
constexpr double kOffsetStd = 0.05;    // prior std of a stance's tilt offset (stance_offset) [rad]
// The regressor's lag d/k takes a joint's estimate once its relative std is at most this (lag_stiffness) [-].
constexpr double kLagStd = 0.2;
}  // namespace

bool identification_inputs_ok(double t, const humanoid::JointVector& encoder, const humanoid::JointVector& torque,
                              const std::array<humanoid::ForceTorque, 2>& ft) {
  bool finite = true;
  for (int j = 0; j < humanoid::kJoints; ++j) finite = finite && std::isfinite(encoder[j]) && std::isfinite(torque[j]);
  for (int side = 0; side < 2; ++side)
    for (int a = 0; a < 3; ++a)
      finite = finite && std::isfinite(ft[side].force[a]) && std::isfinite(ft[side].torque[a]);
  return finite && t - ft[0].stamp <= kStaleAge && t - ft[1].stamp <= kStaleAge;
}

walking::FootContact sole_contact(const walking::RobotModel& model, const humanoid::ForceTorque& ft,
                                  const walking::Matrix3d& sole_R, int side) {
  return walking::foot_contact(ft, sole_R, model.leg[side].ankle_to_sole,
                               model.bodies[static_cast<std::size_t>(model.foot[side])].mass, model.gravity,
                               model.ft_to_sole[side].head<2>());
}

bool firm_support(const walking::RobotModel& model, const walking::FootContact& contact, int side, double min_share) {
  return contact.normal_force >= min_share * model.total_mass * model.gravity &&
         walking::contains_scaled(model.sole_polygon[static_cast<std::size_t>(side)], contact.cop, kFirmCopShare);
}

bool firm_support(const walking::RobotModel& model, const humanoid::ForceTorque& ft, const walking::Matrix3d& sole_R,
                  int side, double min_share) {
  return firm_support(model, sole_contact(model, ft, sole_R, side), side, min_share);
}

StiffnessEstimator::StiffnessEstimator(const walking::RobotModel& model, const CompensationParams& params,
                                       double period, double rest_end)
    : model_(model),
      params_(params),
      noise_variance_(params.k_estimation_noise * params.k_estimation_noise),
      period_(period),
      belief_(params.stiffness()),
      estimate_(belief_),
      stiffness_(belief_),
      rest_end_(rest_end),
      calibrated_(params.k_estimation_gyro_rest <= 0) {
  param_.fill(-1);
  const bool per_joint = params.k_estimation_per_joint;
  const double lambda = std::exp(-period / params.k_estimation_memory);
  for (int side = 0; side < 2; ++side) {
    // A joint's parameter: its own (control.k_estimation_per_joint), or its group's by its axis, mostly x (roll) or y
    // (pitch); z (yaw) is not observed.
    for (const auto& body : model_.bodies) {
      const int j = body.joint;
      if (!humanoid::in_leg(j, side)) continue;
      if (yaw_axis(body.axis)) continue;
      const walking::Vector3d a = body.axis.cwiseAbs();
      param_[j] = per_joint ? j - humanoid::leg_first_joint(side) : (a.x() >= a.y() ? kRoll : kPitch);
    }
    ForgettingRls<kStates>::Vector c0 = ForgettingRls<kStates>::Vector::Zero();  // (the offsets: 0)
    ForgettingRls<kStates>::Matrix P0 = ForgettingRls<kStates>::Matrix::Zero();  // (offsets off: variance 0, stay 0)
    for (int p = 0; p < kParams; ++p) {
      double sum = 0;
      int n = 0;
      for (int j = 0; j < humanoid::kJoints; ++j)
        if (param_[j] == p && humanoid::in_leg(j, side)) {
          sum += 1.0 / belief_[j];
          ++n;
        }
      if (n == 0) continue;  // (not estimated: x 0, variance 0)
      c0[p] = sum / n;
      P0(p, p) = c0[p] * c0[p];  // prior: 100 % relative standard deviation
      c_min_[side][p] = c0[p] / kBoundFactor;
      c_max_[side][p] = c0[p] * kBoundFactor;
    }
    rls_[side] = ForgettingRls<kStates>(c0, P0, lambda);
  }
}

double StiffnessEstimator::relative_std(int side, int param) const {
  return std::sqrt(std::max(rls_[side].P()(param, param), 0.0)) / rls_[side].x()[param];
}

void StiffnessEstimator::hold_within_bounds(int side) {
  // The parameters beyond their bounds (the active set A) are set to them, and the other states (the parameters they
  // correlate with, the stance's offsets) move to their conditional mean given them, x += P_{:,A} P_AA⁻¹ (b_A − x_A):
  // the estimate projected onto the constraints in the metric P⁻¹ (Simon, "Kalman filtering with state constraints",
  // IET Control Theory Appl. 4(8), 2010). A parameter the projection pushes past its own bound joins A and the
  // projection is made again (at most once per parameter). Clamping x_A alone leaves the correlated states where the
  // unconstrained update put them, and the next innovations grow without bound (seen with a drifting gyro: the
  // offsets reached 1e40 rad within a second).
  auto& rls = rls_[side];
  using Square = Eigen::Matrix<double, kParams, kParams>;
  using Column = Eigen::Matrix<double, kParams, 1>;
  std::array<bool, kParams> active{};
  Column bound = Column::Zero();
  for (int pass = 0; pass < kParams; ++pass) {
    bool added = false;
    for (int p = 0; p < kParams; ++p) {
      const double x = rls.x()[p];
      if (active[p] || !(c_max_[side][p] > 0) || (x >= c_min_[side][p] && x <= c_max_[side][p])) continue;
      active[p] = added = true;
      bound[p] = std::clamp(x, c_min_[side][p], c_max_[side][p]);
    }
    if (!added) return;
    Square M = Square::Identity();  // P_AA, the identity on the other parameters (whose step is then 0)
    Column step = Column::Zero();
    for (int p = 0; p < kParams; ++p) {
      if (!active[p]) continue;
      step[p] = bound[p] - rls.x()[p];
      for (int q = 0; q < kParams; ++q)
        if (active[q]) M(p, q) = rls.P()(p, q);
    }
    const Eigen::LDLT<Square> factor(M);
    if (factor.info() == Eigen::Success && factor.isPositive())
      rls.x() += rls.P().leftCols<kParams>() * factor.solve(step);
    for (int p = 0; p < kParams; ++p)
      if (active[p]) rls.x()[p] = bound[p];  // (exactly, against round-off)
  }
}

bool StiffnessEstimator::on_bound(int side, int param) const {
  const double c = rls_[side].x()[param];
  return c <= c_min_[side][param] || c >= c_max_[side][param];
}

double StiffnessEstimator::relative_std(int joint) const {
  if (param_[joint] < 0) return 0.0;
  return relative_std(humanoid::in_leg(joint, 0) ? 0 : 1, param_[joint]);
}

bool StiffnessEstimator::confident(int joint) const {
  return param_[joint] >= 0 && confident_[humanoid::in_leg(joint, 0) ? 0 : 1][param_[joint]];
}

humanoid::JointVector StiffnessEstimator::lag_stiffness() const {
  humanoid::JointVector k = stiffness_;
  for (int j = 0; j < humanoid::kJoints; ++j)
    if (param_[j] >= 0 && relative_std(j) <= kLagStd && !on_bound(humanoid::in_leg(j, 0) ? 0 : 1, param_[j]))
      k[j] = estimate_[j];
  return k;
}

void StiffnessEstimator::publish(int side) {
  for (int i = 0; i < humanoid::kLegJoints; ++i) {
    const int j = humanoid::leg_first_joint(side) + i, p = param_[j];
    if (p < 0) continue;
    const bool confident_now = relative_std(side, p) <= params_.k_estimation_confidence && !on_bound(side, p);
    confident_[side][p] = confident_[side][p] || confident_now;
    estimate_[j] = 1.0 / rls_[side].x()[p];
    if (confident_now) stiffness_[j] = estimate_[j];
  }
}

void StiffnessEstimator::follow_attitude(const walking::Matrix3d& imu_R, const walking::Vector3d& delta_angle) {
  const double time = params_.k_estimation_attitude_time;
  if (time <= 0 || !attitude_started_) {
    attitude_ = imu_R;
    attitude_started_ = true;
    return;
  }
  // The IMU's turn since the last reading, less its bias (the delta angle: the turn over the period, as the
  // encoders' angles are read at its end).
  const walking::Vector3d turn = delta_angle - gyro_bias_ * period_;
  if (turn.norm() > 0) attitude_ = attitude_ * Eigen::AngleAxisd(turn.norm(), turn.normalized()).toRotationMatrix();
  const Eigen::AngleAxisd error(walking::Matrix3d(imu_R * attitude_.transpose()));
  attitude_ =
      Eigen::AngleAxisd(error.angle() * std::min(1.0, period_ / time), error.axis()).toRotationMatrix() * attitude_;
  attitude_ = Eigen::Quaterniond(attitude_).normalized().toRotationMatrix();  // (round-off)
}

walking::Matrix3d StiffnessEstimator::soles_in_pelvis(const humanoid::JointVector& encoder,
                                                      const humanoid::JointVector& torque) {
  humanoid::JointVector q = encoder;
  for (int j = 0; j < humanoid::kJoints; ++j) q[j] -= torque[j] / belief_[j];  // the link angles (the belief)
  walking::forward_kinematics(model_, data_, walking::Pose{walking::Vector3d::Zero(), walking::Matrix3d::Identity()},
                              q);
  // The two soles' mean: the normalised sum of their quaternions (same hemisphere).
  const Eigen::Quaterniond left(walking::Matrix3d(walking::sole_pose(model_, data_, 0).R));
  Eigen::Quaterniond right(walking::Matrix3d(walking::sole_pose(model_, data_, 1).R));
  if (left.dot(right) < 0) right.coeffs() *= -1;
  return Eigen::Quaterniond(left.coeffs() + right.coeffs()).normalized().toRotationMatrix();
}

bool StiffnessEstimator::calibrate_at_rest(double t, const walking::Matrix3d& imu_R,
                                           const walking::Vector3d& delta_angle, const walking::Vector3d& accel,
                                           const humanoid::JointVector& encoder, const humanoid::JointVector& torque) {
  if (calibrated_) return true;
  if (t < rest_end_) {
    if (t >= rest_end_ - params_.k_estimation_gyro_rest - 0.5 * period_ && accel.norm() > 0) {
      const double s = t - rest_end_;  // (≤ 0: small numbers)
      const walking::Vector3d up = accel.normalized();
      if (rest_.n == 0) rest_.soles_first = soles_in_pelvis(encoder, torque);
      rest_.encoder_last = encoder;
      rest_.torque_last = torque;
      if (rest_.n > 0) rest_.turn += delta_angle;  // the IMU's turn from the first reading to this one
      rest_.n += 1;
      rest_.t += s;
      rest_.tt += s * s;
      rest_.up += up;
      rest_.t_up += s * up;
    }
    return false;
  }
  calibrated_ = true;
  attitude_started_ = true;
  attitude_ = imu_R;
  if (rest_.n < 2) return true;
  // The static alignment. A robot "at rest" still turns slowly (the twin follows its observer's drift, ~1e-4
  // rad/s), so b̂ = (the gyro's turn − the pelvis's turn through the legs) / the window: with both soles flat and
  // still, the pelvis's attitude is R_sole R_ps(q)ᵀ, its turn R_ps,first R_ps,lastᵀ (pelvis frame). (The
  // accelerometer's direction would show the turn as well, but also the pelvis's slow horizontal acceleration:
  // on the twin it gave b̂ 9e-5 rad/s off against 4e-5 through the legs.)
  const double n = rest_.n, window = (n - 1) * period_;
  const walking::Matrix3d soles_last = soles_in_pelvis(rest_.encoder_last, rest_.torque_last);
  const Eigen::AngleAxisd legs(walking::Matrix3d(rest_.soles_first * soles_last.transpose()));
  gyro_bias_ = (rest_.turn - legs.angle() * legs.axis()) / window;
  // The tilt: the pelvis's up u = Rᵀ e_z (the accelerometer's direction, +g up at rest), a line u(s) = u₀ + u̇ s
  // fitted over the window (s = t − its end), at the end; the yaw the controller's.
  const double mean_t = rest_.t / n, spread = rest_.tt - n * mean_t * mean_t;
  const walking::Vector3d mean_up = rest_.up / n;
  const walking::Vector3d up_rate =
      spread > 0 ? walking::Vector3d((rest_.t_up - mean_t * rest_.up) / spread) : walking::Vector3d::Zero();
  const walking::Vector3d up_end = (mean_up - up_rate * mean_t).normalized();
  const walking::Vector3d up_now = imu_R.transpose() * walking::Vector3d::UnitZ();
  attitude_ = imu_R * walking::Matrix3d(Eigen::Quaterniond::FromTwoVectors(up_end, up_now));  // R u_end = e_z
  return true;
}

int StiffnessEstimator::update(double t, const humanoid::JointVector& encoder, const walking::Matrix3d& imu_R,
                               const humanoid::Imu& imu, const humanoid::JointVector& torque,
                               const std::array<humanoid::ForceTorque, 2>& ft, const SupportPlan& support,
                               bool sensors_ok) {
  const walking::Vector3d delta(imu.delta_angle[0], imu.delta_angle[1], imu.delta_angle[2]),
      accel(imu.accel[0], imu.accel[1], imu.accel[2]);
  const bool imu_finite = imu_R.allFinite() && delta.allFinite() && accel.allFinite();
  if (!imu_finite || !identification_inputs_ok(t, encoder, torque, ft) || !sensors_ok) {
    ++bad_data_;
    if (imu_finite && calibrated_) follow_attitude(imu_R, delta);  // (the IMU's turn is not to be missed)
    return 0;
  }
  lag_.update(torque, lag_stiffness(), params_, period_);
  if (!calibrate_at_rest(t, imu_R, delta, accel, encoder, torque)) return 0;
  follow_attitude(imu_R, delta);
  for (int side = 0; side < 2; ++side) rls_[side].forget();
  walking::forward_kinematics(model_, data_, walking::Pose{walking::Vector3d::Zero(), attitude_}, encoder);
  int used = 0;
  for (int side = 0; side < 2; ++side) {
    if (support.swinging[side]) {
      new_stance_[side] = true;
      continue;
    }
    const walking::FootContact contact = sole_contact(model_, ft[side], support.soles[side].R, side);
    if (!firm_support(model_, contact, side, kFirmWeightShare)) continue;
    const walking::Pose sole = walking::sole_pose(model_, data_, side);
    const walking::LegJacobian J = walking::leg_jacobian(model_, data_, side, sole.p);
    // The regressors: H(:, p) = Σ_{i∈p} (a_i)_xy τ_i.
    Eigen::Matrix<double, 2, kParams> H = Eigen::Matrix<double, 2, kParams>::Zero();
    for (int i = 0; i < humanoid::kLegJoints; ++i) {
      const int j = humanoid::leg_first_joint(side) + i;
      if (param_[j] < 0) continue;
      H.col(param_[j]) += J.block<2, 1>(3, i) * lag_.torque()[j];
    }
    if (H.norm() < params_.k_estimation_min_torque) continue;
    // The foot's tilt through the chain, less the sole's own tilt in its contact (the belief).
    const Eigen::Vector2d omega =
        Eigen::Vector2d(-sole.R(1, 2), sole.R(0, 2)) - (sole.R * sole_tilt(contact, params_)).head<2>();
    if (params_.k_estimation_stance_offset && (new_stance_[side] || rls_[side].P()(kParams, kParams) == 0)) {
      // A new stance: its tilt offset (the attitude's slow error, the sole's seat) starts anew.
      for (int r = 0; r < 2; ++r) rls_[side].restart(kParams + r, kOffsetStd * kOffsetStd);
      new_stance_[side] = false;
    }
    for (int r = 0; r < 2; ++r) {
      ForgettingRls<kStates>::Vector h = ForgettingRls<kStates>::Vector::Zero();
      h.head<kParams>() = H.row(r).transpose();
      h[kParams + r] = 1.0;  // ω = H c + e
      rls_[side].update(h, omega[r], noise_variance_);
    }
    hold_within_bounds(side);
    publish(side);
    ++used;
  }
  samples_ += used;
  return used;
}

}  // namespace flexgait::compensation
