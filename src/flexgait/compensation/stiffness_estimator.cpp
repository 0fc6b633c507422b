#include "flexgait/compensation/stiffness_estimator.hpp"

#include <algorithm>
#include <cmath>

#include "flexgait/walking/foot_wrench.hpp"

namespace flexgait::compensation {

namespace {
constexpr double kStaleAge = 0.05;        // an F/T reading older than this is stale [s]
constexpr double kFirmWeightShare = 0.25; // firm support: normal force ≥ this × the weight
constexpr double kFirmCopShare = 0.3;     // ... and |CoP − sole centre| ≤ this × the sole's length, width
constexpr double kBoundFactor = 10.0;     // c ∈ [c₀/10, 10 c₀]
}  // namespace

StiffnessEstimator::StiffnessEstimator(const walking::RobotModel& model, const CompensationParams& params, double period)
    : model_(model),
      params_(params),
      noise_variance_(params.k_estimation_noise * params.k_estimation_noise),
      period_(period),
      belief_(params.stiffness()),
      estimate_(belief_),
      stiffness_(belief_) {
  group_.fill(kNone);
  const double lambda = std::exp(-period / params.k_estimation_memory);
  for (int side = 0; side < 2; ++side) {
    // A joint's group by its axis: mostly x (roll) or y (pitch); z (yaw) is not observed.
    for (const auto& body : model_.bodies) {
      const int j = body.joint;
      if (j < humanoid::leg_first_joint(side) || j >= humanoid::leg_first_joint(side) + humanoid::kLegJoints) continue;
      const walking::Vector3d a = body.axis.cwiseAbs();
      if (a.z() >= a.x() && a.z() >= a.y()) continue;
      group_[j] = a.x() >= a.y() ? kRoll : kPitch;
    }
    ForgettingRls<kGroups>::Vector c0;
    ForgettingRls<kGroups>::Matrix P0 = ForgettingRls<kGroups>::Matrix::Zero();
    for (int g = 0; g < kGroups; ++g) {
      double sum = 0;
      int n = 0;
      for (int j = 0; j < humanoid::kJoints; ++j)
        if (group_[j] == g && j >= humanoid::leg_first_joint(side) && j < humanoid::leg_first_joint(side) + humanoid::kLegJoints) {
          sum += 1.0 / belief_[j];
          ++n;
        }
      c0[g] = n > 0 ? sum / n : 1.0 / params.k_joint;
      P0(g, g) = c0[g] * c0[g];  // prior: 100 % relative standard deviation
      c_min_[side][g] = c0[g] / kBoundFactor;
      c_max_[side][g] = c0[g] * kBoundFactor;
    }
    rls_[side] = ForgettingRls<kGroups>(c0, P0, lambda);
  }
}

double StiffnessEstimator::relative_std(int side, Group g) const {
  return std::sqrt(std::max(rls_[side].P()(g, g), 0.0)) / rls_[side].x()[g];
}

void StiffnessEstimator::publish(int side) {
  for (int g = 0; g < kGroups; ++g) confident_[side][g] = confident_[side][g] || relative_std(side, Group(g)) <= params_.k_estimation_confidence;
  for (int i = 0; i < humanoid::kLegJoints; ++i) {
    const int j = humanoid::leg_first_joint(side) + i;
    if (group_[j] == kNone) continue;
    const double c = rls_[side].x()[group_[j]];
    estimate_[j] = 1.0 / c;
    if (relative_std(side, group_[j]) <= params_.k_estimation_confidence) stiffness_[j] = estimate_[j];
  }
}

void StiffnessEstimator::follow_attitude(const walking::Matrix3d& imu_R, const walking::Vector3d& gyro) {
  const double time = params_.k_estimation_attitude_time;
  if (time <= 0 || !attitude_started_) {
    attitude_ = imu_R;
    attitude_started_ = true;
    return;
  }
  const double turn = gyro.norm() * period_;
  if (turn > 0) attitude_ = attitude_ * Eigen::AngleAxisd(turn, gyro.normalized()).toRotationMatrix();
  const Eigen::AngleAxisd error(walking::Matrix3d(imu_R * attitude_.transpose()));
  attitude_ = Eigen::AngleAxisd(error.angle() * std::min(1.0, period_ / time), error.axis()).toRotationMatrix() * attitude_;
  attitude_ = Eigen::Quaterniond(attitude_).normalized().toRotationMatrix();  // (round-off)
}

int StiffnessEstimator::update(double t, const humanoid::JointVector& encoder, const walking::Matrix3d& imu_R,
                               const walking::Vector3d& gyro, const humanoid::JointVector& torque,
                               const std::array<humanoid::ForceTorque, 2>& ft, const SupportPlan& support, bool sensors_ok) {
  bool finite = imu_R.allFinite() && gyro.allFinite();
  for (int j = 0; j < humanoid::kJoints; ++j) finite = finite && std::isfinite(encoder[j]) && std::isfinite(torque[j]);
  for (int side = 0; side < 2; ++side)
    for (int a = 0; a < 3; ++a) finite = finite && std::isfinite(ft[side].force[a]) && std::isfinite(ft[side].torque[a]);
  const bool stale = t - ft[0].stamp > kStaleAge || t - ft[1].stamp > kStaleAge;
  if (!finite || stale || !sensors_ok) {
    ++bad_data_;
    return 0;
  }
  follow_attitude(imu_R, gyro);
  for (int side = 0; side < 2; ++side) rls_[side].forget();
  walking::forward_kinematics(model_, data_, walking::Pose{walking::Vector3d::Zero(), attitude_}, encoder);
  const double weight = model_.total_mass * walking::kGravity;
  int used = 0;
  for (int side = 0; side < 2; ++side) {
    if (support.swinging[side]) continue;
    const walking::FootContact c = walking::foot_contact(ft[side], support.soles[side].R, model_.leg[side].ankle_to_sole,
                                                         model_.bodies[static_cast<std::size_t>(model_.foot[side])].mass);
    const Eigen::Vector2d cop = c.cop - model_.sole_offset[side].head<2>();
    if (c.normal_force < kFirmWeightShare * weight || std::abs(cop.x()) > kFirmCopShare * model_.sole_length ||
        std::abs(cop.y()) > kFirmCopShare * model_.sole_width)
      continue;
    const walking::Pose sole = walking::sole_pose(model_, data_, side);
    const walking::LegJacobian J = walking::leg_jacobian(model_, data_, side, sole.p);
    // The regressors: H(:, g) = Σ_{i∈g} (a_i)_xy τ_i.
    Eigen::Matrix<double, 2, kGroups> H = Eigen::Matrix<double, 2, kGroups>::Zero();
    for (int i = 0; i < humanoid::kLegJoints; ++i) {
      const int j = humanoid::leg_first_joint(side) + i;
      if (group_[j] == kNone) continue;
      H.col(group_[j]) += J.block<2, 1>(3, i) * torque[j];
    }
    if (H.norm() < params_.k_estimation_min_torque) continue;
    const Eigen::Vector2d omega(-sole.R(1, 2), sole.R(0, 2));  // the foot's tilt through the chain
    for (int r = 0; r < 2; ++r) rls_[side].update(H.row(r).transpose(), omega[r], noise_variance_);
    auto& x = rls_[side].x();
    for (int g = 0; g < kGroups; ++g) x[g] = std::clamp(x[g], c_min_[side][g], c_max_[side][g]);
    publish(side);
    ++used;
  }
  samples_ += used;
  return used;
}

}  // namespace flexgait::compensation
