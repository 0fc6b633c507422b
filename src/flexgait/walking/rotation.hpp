#pragma once
/// \file rotation.hpp
/// Poses, elementary rotations and roll-pitch-yaw (Z-Y-X) angles; right-handed, world z up.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace flexgait::walking {

using Eigen::Matrix3d;
using Eigen::Vector3d;

inline Matrix3d rot_x(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Matrix3d R;
  R << 1, 0, 0, 0, c, -s, 0, s, c;
  return R;
}
inline Matrix3d rot_y(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Matrix3d R;
  R << c, 0, s, 0, 1, 0, -s, 0, c;
  return R;
}
inline Matrix3d rot_z(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Matrix3d R;
  R << c, -s, 0, s, c, 0, 0, 0, 1;
  return R;
}
/// A pose of a frame: position [m] and orientation.
struct Pose {
  Vector3d p = Vector3d::Zero();
  Matrix3d R = Matrix3d::Identity();
};

/// R = Rz(yaw) Ry(pitch) Rx(roll).
inline Matrix3d rpy_to_matrix(double roll, double pitch, double yaw) {
  return rot_z(yaw) * rot_y(pitch) * rot_x(roll);
}
/// The rotation vector φ = θ a of R (SO(3)'s log), |φ| ≤ π.
inline Vector3d rotation_vector(const Matrix3d& R) {
  const Eigen::AngleAxisd a(R);
  return a.angle() * a.axis();
}

/// [a]×, the matrix of a × (·).
inline Matrix3d skew(const Vector3d& a) {
  Matrix3d s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

/// The inverse of SO(3)'s left Jacobian at φ: log(exp([δ]×) exp([φ]×)) = φ + J_l⁻¹(φ) δ + O(δ²),
///     J_l⁻¹(φ) = I − ½[φ]× + (1/θ² − (1 + cos θ)/(2 θ sin θ)) [φ]×²,  θ = |φ| < π
/// (the bracket's series 1/12 + θ²/720 below θ = 1e-4).
inline Matrix3d left_jacobian_inverse(const Vector3d& phi) {
  const double theta = phi.norm();
  const Matrix3d W = skew(phi);
  const double b = theta < 1e-4 ? 1.0 / 12.0 + theta * theta / 720.0
                                : 1.0 / (theta * theta) - (1 + std::cos(theta)) / (2 * theta * std::sin(theta));
  return Matrix3d::Identity() - 0.5 * W + b * W * W;
}

/// Roll and pitch of R = Rz(yaw) Ry(pitch) Rx(roll) (|pitch| < π/2) [rad].
inline double roll_of(const Matrix3d& R) {
  return std::atan2(R(2, 1), R(2, 2));
}
inline double pitch_of(const Matrix3d& R) {
  return std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
}
inline double yaw_of(const Matrix3d& R) {
  return std::atan2(R(1, 0), R(0, 0));
}
/// Rotation matrix of a unit quaternion (w, x, y, z).
inline Matrix3d quat_to_matrix(const double* q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

}  // namespace flexgait::walking
