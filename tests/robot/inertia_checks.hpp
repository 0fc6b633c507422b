#pragma once
// Checks of a rigid body's inertial for the robot's tables: positive mass, and an inertia tensor
// (ixx, ixy, ixz, iyy, iyz, izz about the centre of mass) that a body can have: symmetric positive
// definite with principal moments obeying the triangle inequality I1 + I2 >= I3.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <string>

namespace flexgait::humanoid::testing {

inline Eigen::Matrix3d inertia_matrix(const std::array<double, 6>& i) {
  Eigen::Matrix3d I;
  I << i[0], i[1], i[2], i[1], i[3], i[4], i[2], i[4], i[5];
  return I;
}

/// The triangle inequality with a relative slack `slack` (tables rounded to 8 digits, thin rods
/// that reach it: 1e-6).
inline void expect_physical_inertial(const std::string& name, double mass, const std::array<double, 6>& inertia,
                                     double slack = 1e-6) {
  EXPECT_GT(mass, 0.0) << name;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertia_matrix(inertia));
  const Eigen::Vector3d p = eig.eigenvalues();  // ascending
  EXPECT_GT(p(0), 0.0) << name;
  EXPECT_GE(p(0) + p(1), p(2) * (1 - slack)) << name << ": principal moments " << p.transpose();
}

}  // namespace flexgait::humanoid::testing
