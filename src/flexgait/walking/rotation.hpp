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
inline Matrix3d rpy_to_matrix(double roll, double pitch, double yaw) { return rot_z(yaw) * rot_y(pitch) * rot_x(roll); }
/// Roll and pitch of R = Rz(yaw) Ry(pitch) Rx(roll) (|pitch| < π/2) [rad].
inline double roll_of(const Matrix3d& R) { return std::atan2(R(2, 1), R(2, 2)); }
inline double pitch_of(const Matrix3d& R) { return std::asin(std::clamp(-R(2, 0), -1.0, 1.0)); }
inline double yaw_of(const Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }
/// Rotation matrix of a unit quaternion (w, x, y, z).
inline Matrix3d quat_to_matrix(const double* q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

}  // namespace flexgait::walking
