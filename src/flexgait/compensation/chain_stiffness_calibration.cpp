#include "flexgait/compensation/chain_stiffness_calibration.hpp"

#include <algorithm>
#include <cmath>

#include "flexgait/compensation/stiffness_estimator.hpp"
#include "flexgait/walking/rotation.hpp"

namespace flexgait::compensation {

namespace {
constexpr double kMinWeightShare = 0.05;  // a sole in support carries at least this share of the weight
constexpr double kBoundFactor = 10.0;     // c ∈ [c₀/10, 10 c₀]
constexpr double kOffsetStd = 0.05;       // prior std of y₀'s roll and pitch [rad]
constexpr double kSettleTime = 1.0;       // after a pass publishes, the commanded pose's change settles [s]

}  // namespace

ChainStiffnessCalibration::ChainStiffnessCalibration(const walking::RobotModel& model, const CompensationParams& params,
                                                     double period, double begin, double end)
    : model_(model),
      params_(params),
      period_(period),
      noise_variance_(params.k_estimation_noise * params.k_estimation_noise),
      begin_(begin),
      end_(end),
      belief_(params.stiffness()),
      estimate_(belief_),
      stiffness_(belief_) {
  state_.fill(-1);
  int n = 0;
  for (const auto& body : model_.bodies) {
    const int j = body.joint;
    if (!(humanoid::in_leg(j, 0) || humanoid::in_leg(j, 1)) || yaw_axis(body.axis)) continue;
    state_[j] = n;
    c_min_[n] = 1.0 / (belief_[j] * kBoundFactor);
    c_max_[n] = kBoundFactor / belief_[j];
    ++n;
  }
  start_fit();
}

void ChainStiffnessCalibration::start_fit() {
  InformationLeastSquares<kStates>::Vector x0, P0;  // (unused states: variance 0, held at 0)
  x0.setZero();
  P0.setZero();
  for (int j = 0; j < humanoid::kJoints; ++j) {
    const int n = state_[j];
    if (n < 0) continue;
    x0[n] = 1.0 / stiffness_[j];
    P0[n] = x0[n] * x0[n];  // prior: 100 % relative standard deviation
  }
  for (int r = 0; r < 2; ++r) P0[kMaxJoints + r] = kOffsetStd * kOffsetStd;
  fit_ = InformationLeastSquares<kStates>(x0, P0);
}

void ChainStiffnessCalibration::publish() {
  for (int j = 0; j < humanoid::kJoints; ++j)
    if (state_[j] >= 0 && relative_std(j) <= params_.k_estimation_confidence) stiffness_[j] = estimate_[j];
}

int ChainStiffnessCalibration::pass(double t) const {
  const int passes = params_.k_calibration_passes;
  if (!(end_ > begin_)) return 0;  // (an empty window: one pass)
  return std::clamp(static_cast<int>(std::floor((t - begin_) / (end_ - begin_) * passes)), 0, passes - 1);
}

double ChainStiffnessCalibration::relative_std(int joint) const {
  const int n = state_[joint];
  return n < 0 ? 0.0 : std::sqrt(std::max(fit_.variance(n), 0.0)) / std::clamp(fit_.x()[n], c_min_[n], c_max_[n]);
}

Eigen::Matrix<double, 2, ChainStiffnessCalibration::kStates> ChainStiffnessCalibration::regressor(
    const humanoid::JointVector& encoder, const humanoid::JointVector& torque, Eigen::Vector2d& y) {
  return regressor(encoder, torque, {walking::Vector3d::Zero(), walking::Vector3d::Zero()}, y);
}

Eigen::Matrix<double, 2, ChainStiffnessCalibration::kStates> ChainStiffnessCalibration::regressor(
    const humanoid::JointVector& encoder, const humanoid::JointVector& torque,
    const std::array<walking::Vector3d, 2>& sole_tilts, Eigen::Vector2d& y) {
  walking::forward_kinematics(model_, data_, walking::Pose{walking::Vector3d::Zero(), walking::Matrix3d::Identity()},
                              encoder);
  const walking::Pose left = walking::sole_pose(model_, data_, 0), right = walking::sole_pose(model_, data_, 1);
  const walking::Vector3d phi = walking::rotation_vector(left.R.transpose() * right.R);
  y = phi.head<2>();
  const walking::Matrix3d to_y = walking::left_jacobian_inverse(phi) * left.R.transpose();
  y -= (to_y * (right.R * sole_tilts[1] - left.R * sole_tilts[0])).head<2>();  // (the soles' own tilts)
  Eigen::Matrix<double, 2, kStates> H = Eigen::Matrix<double, 2, kStates>::Zero();
  for (int side = 0; side < 2; ++side) {
    const walking::LegJacobian J = walking::leg_jacobian(model_, data_, side, side == 0 ? left.p : right.p);
    for (int i = 0; i < humanoid::kLegJoints; ++i) {
      const int j = humanoid::leg_first_joint(side) + i;
      const walking::Vector3d axis = J.block<3, 1>(3, i);  // (the angular rows: the joint's axis)
      const Eigen::Vector2d h = (side == 0 ? -1.0 : 1.0) * (to_y * axis).head<2>() * torque[j];
      if (state_[j] >= 0)
        H.col(state_[j]) = h;
      else
        y -= h / stiffness_[j];  // (a yaw joint: its deflection by the belief, taken out of y)
    }
  }
  H.rightCols<2>().setIdentity();
  return H;
}

int ChainStiffnessCalibration::update(double t, const humanoid::JointVector& encoder,
                                      const humanoid::JointVector& torque,
                                      const std::array<humanoid::ForceTorque, 2>& ft, const SupportPlan& support,
                                      bool sensors_ok) {
  if (t > end_ && !published_) {
    // The calibration is over: the compensators take each confident joint's estimate from now on.
    published_ = true;
    publish();
  }
  if (t < begin_ || t > end_) return 0;
  if (const int p = pass(t); p > pass_) {
    // A pass is over: the compensators take its estimate, so the torques are modelled with it (the estimated pose,
    // the lag d/k); the next pass fits afresh from it, once the commanded pose has settled.
    pass_ = p;
    publish();
    start_fit();
    settle_until_ = t + kSettleTime;
  }
  if (t < settle_until_ || support.swinging[0] || support.swinging[1]) return 0;
  if (!identification_inputs_ok(t, encoder, torque, ft) || !sensors_ok) {
    ++bad_data_;
    return 0;
  }
  lag_.update(torque, stiffness_, params_, period_);  // (every period with good data)
  std::array<walking::Vector3d, 2> sole_tilts;
  for (int side = 0; side < 2; ++side) {
    const walking::FootContact contact = sole_contact(model_, ft[side], support.soles[side].R, side);
    if (!firm_support(model_, contact, side, kMinWeightShare)) return 0;
    sole_tilts[side] = sole_tilt(contact, params_);
  }
  Eigen::Vector2d y;
  const Eigen::Matrix<double, 2, kStates> H = regressor(encoder, lag_.torque(), sole_tilts, y);
  for (int r = 0; r < 2; ++r) fit_.add(H.row(r).transpose(), y[r], noise_variance_);
  fit_.solve();
  for (int j = 0; j < humanoid::kJoints; ++j) {
    const int n = state_[j];
    if (n < 0) continue;
    estimate_[j] = 1.0 / std::clamp(fit_.x()[n], c_min_[n], c_max_[n]);  // (the fit itself is not clamped)
  }
  ++samples_;
  return 1;
}

}  // namespace flexgait::compensation
