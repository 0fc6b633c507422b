#pragma once
/// \file tilt_observer.hpp
/// Kinematic–inertial tilt observer (M. Benallegue, R. Cisneros, A. Benallegue, Y. Chitour,
/// M. Morisawa, F. Kanehiro, "Lyapunov-stable orientation estimator for humanoid robots", IEEE
/// RA-L 5(4), 2020; as in mc_rtc's state observation). With R the IMU's attitude (IMU to world),
/// x1 = Rᵀ ṗ its linear velocity in its own frame and x2 = Rᵀ e_z the tilt (world up, IMU frame),
///
///     ẋ1 = x1 × ω − g0 x2 + y_a,   ẋ2 = x2 × ω                                   (T1)
///
/// (ω the gyro, y_a the accelerometer's specific force, g0 = |g|). A foot resting on the ground is
/// a fixed anchor: with p its position in the IMU frame (leg kinematics) the velocity is measured,
///
///     y_v = −(ω × p + ṗ)                                                           (T2)
///
/// and the observer is
///
///     dx̂1/dt  = x̂1 × ω − g0 x̂2′ + y_a + α (y_v − x̂1)
///     dx̂2′/dt = x̂2′ × ω − β (y_v − x̂1)                                            (T3)
///     dx̂2/dt  = x̂2 × (ω − γ x̂2 × x̂2′),   x̂2 renormalised
///
/// x̂2′ is the tilt the velocity error corrects (it carries the accelerations the Mahony filter
/// mistakes for tilt: T2 measures them); x̂2 is its projection on the unit sphere. Explicit Euler
/// over one control period. Allocation-free; no simulator types.
#include <Eigen/Dense>

namespace flexgait::walking {

/// The gains (their defaults and why: EstimatorParams, estimator.tilt_*).
struct TiltObserverGains {
  double alpha;    ///< α: velocity correction [1/s]
  double beta;     ///< β: tilt correction from the velocity error [1/s]
  double gamma;    ///< γ: pull of x̂2 toward x̂2′ [1/s]
  double gravity;  ///< g0 [m/s^2]
};

class TiltObserver {
 public:
  explicit TiltObserver(const TiltObserverGains& gains) : gains_(gains) {}

  /// Starts from the velocity x1 [m/s] and the tilt x2 (unit) in the IMU frame.
  void reset(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2);
  /// One period dt [s] of (T3) with the velocity y_v [m/s] (T2), the specific force y_a [m/s^2]
  /// and the gyro ω [rad/s], all in the IMU frame. Without a velocity measurement (no foot on the
  /// ground) pass y_v = velocity(): no velocity correction.
  void update(const Eigen::Vector3d& y_v, const Eigen::Vector3d& y_a, const Eigen::Vector3d& omega, double dt);

  bool started() const { return started_; }
  const Eigen::Vector3d& velocity() const { return x1_; }  ///< x̂1 [m/s]
  const Eigen::Vector3d& tilt() const { return x2_; }      ///< x̂2 = Rᵀ e_z estimated (unit)

 private:
  TiltObserverGains gains_;
  bool started_ = false;
  Eigen::Vector3d x1_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d x2_prime_ = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d x2_ = Eigen::Vector3d::UnitZ();
};

/// Roll and pitch [rad] of an attitude R = R_z(yaw) R_y(pitch) R_x(roll) from its tilt Rᵀ e_z =
/// (−sin pitch, sin roll cos pitch, cos roll cos pitch).
Eigen::Vector2d roll_pitch_of_tilt(const Eigen::Vector3d& tilt);

}  // namespace flexgait::walking
