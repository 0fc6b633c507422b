#include "flexgait/walking/attitude_estimator.hpp"

#include <algorithm>
#include <cmath>

namespace flexgait::walking {

void AttitudeEstimator::reset() {
  R_.setIdentity();
  bias_.setZero();
  initialised_ = false;
  time_ = 0;
  level_sum_.setZero();
  level_count_ = 0;
  waiting_ = 0;
  wait_sum_.setZero();
}

void AttitudeEstimator::level(const Vector3d& a, const Vector3d& planned_accel, double T) {
  const double g = params_.gravity;
  waiting_ += T;
  // (the plan's acceleration out as the filter does once running, with the attitude unknown yet
  // taken level: the error is the tilt times it, second order)
  wait_sum_ += a - planned_accel;
  const bool near_g = std::abs(a.norm() - g) <= 0.05 * g;
  const bool along =
      level_count_ == 0 || std::atan2(a.cross(level_sum_).norm(), a.dot(level_sum_)) <= params_.level_tolerance;
  if (!(near_g && along)) {  // not steady: the window starts again (at this reading if it can)
    level_sum_.setZero();
    level_count_ = 0;
    if (near_g) {
      level_sum_ = a;
      level_count_ = 1;
    }
  } else {
    level_sum_ += a;
    ++level_count_;
  }
  // The window holds level_count_ periods of readings (half a period: the round-off of Σ T).
  const bool steady = level_count_ > 0 && level_count_ * T + 0.5 * T >= params_.level_time;
  const bool timed_out = waiting_ > params_.align_time + 0.5 * T;
  if (!steady && !timed_out) return;
  // Tilt from gravity alone: up = Rᵀ e_z = (−sin p, sin r cos p, cos r cos p) for R = Rz Ry Rx.
  const Vector3d v = (steady ? level_sum_ : wait_sum_).normalized();
  const double roll = std::atan2(v.y(), v.z());
  const double pitch = std::atan2(-v.x(), std::hypot(v.y(), v.z()));
  R_ = rpy_to_matrix(roll, pitch, 0.0);
  initialised_ = true;
  if (!steady) time_ = params_.align_time;  // the wait's mean is already aligned: no high-gain phase
}

void AttitudeEstimator::update(const Vector3d& gyro, const Vector3d* accel, const Vector3d& planned_accel, double T) {
  const double g = params_.gravity;
  // Prediction: R̂⁻ = R̂ exp([ω_y − b̂]× T) (exact for a constant rate over the period).
  auto turn = [this](const Vector3d& w, double dt) {
    const double angle = w.norm() * dt;
    if (angle > 0) R_ = R_ * Eigen::AngleAxisd(angle, w.normalized()).toRotationMatrix();
  };
  if (initialised_) turn(gyro - bias_, T);
  if (accel != nullptr) {
    // Specific force a = Rᵀ (p̈ + g e_z): without the pelvis's own acceleration it points up.
    Vector3d v = *accel;
    if (params_.accel_compensation && initialised_) v -= R_.transpose() * planned_accel;
    const double n = v.norm();
    if (n > 0.5 * g && n < 1.5 * g) {
      if (!initialised_) {
        level(v, planned_accel, T);
        return;
      }
      v /= n;
      // Correction against the predicted attitude: (32c), then (32a)'s k_P term and (32b);
      // while aligning, a higher gain and no bias integration.
      // The alignment ends early, for good, once the plan accelerates the COM: the
      // accelerometer then measures the motion as well as gravity, and at align_kp it would take
      // the gap between the planned and the real acceleration for tilt.
      if (planned_accel.head<2>().norm() > params_.align_accel) time_ = std::max(time_, params_.align_time);
      const bool aligning = time_ + 0.5 * T < params_.align_time;  // (half a period: round-off of Σ T)
      const Vector3d omega_mes = v.cross(R_.transpose() * Vector3d::UnitZ());
      turn((aligning ? params_.align_kp : params_.kp) * omega_mes, T);
      if (!aligning) bias_ -= T * params_.ki * omega_mes;
    }
  }
  if (!initialised_) return;  // no attitude before the first usable accelerometer reading
  time_ += T;
  // Keep R̂ a rotation (round-off): re-orthonormalise through the quaternion.
  R_ = Eigen::Quaterniond(R_).normalized().toRotationMatrix();
}

}  // namespace flexgait::walking
