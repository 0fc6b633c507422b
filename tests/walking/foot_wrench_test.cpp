// The ground under a foot from its ankle F/T sensor (walking/foot_wrench.hpp): a ground force f
// applied at a known point p of the sole (sensor frame, sole d below the ankle), read by the sensor
// as the leg's wrench on a foot of mass m_f in equilibrium, comes back as N = f_z, the centre of
// pressure p and the torque (p − c) × f about the sole centre c, for a flat and a tilted foot and a
// shifted sole.
#include "flexgait/walking/foot_wrench.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "flexgait/walking/robot_model.hpp"

namespace flexgait::walking {
namespace {

constexpr double kDepth = 0.1;     // ankle to sole [m]
constexpr double kFootMass = 1.7;  // [kg]

// The sensor's reading of a foot in equilibrium: the leg's wrench on the foot balances the ground
// force f at p (sole frame, p_z = −d) and the foot's weight, whose line passes through the ankle.
humanoid::ForceTorque reading(const Eigen::Vector3d& f, const Eigen::Vector2d& p, const Eigen::Matrix3d& sole_R) {
  const Eigen::Vector3d weight = sole_R.transpose() * Eigen::Vector3d(0, 0, -humanoid::kDefaultGravity * kFootMass);
  const Eigen::Vector3d at(p.x(), p.y(), -kDepth);
  const Eigen::Vector3d force = -(f + weight), torque = -at.cross(f);
  humanoid::ForceTorque ft;
  for (int i = 0; i < 3; ++i) {
    ft.force[static_cast<std::size_t>(i)] = force(i);
    ft.torque[static_cast<std::size_t>(i)] = torque(i);
  }
  return ft;
}

TEST(FootWrench, RecoversTheNormalForceCentreOfPressureAndTorque) {
  const Eigen::Vector3d f(12.0, -7.0, 310.0);
  const Eigen::Vector2d p(0.04, -0.015);
  for (const Eigen::Matrix3d& R : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()),
                                   Eigen::Matrix3d(Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 0.5, 0).normalized()))}) {
    for (const Eigen::Vector2d& s : {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.005, 0.014)}) {
      const FootContact c = foot_contact(reading(f, p, R), R, kDepth, kFootMass, humanoid::kDefaultGravity, s);
      // Products of forces of 300 N and lengths of 0.1 m: rounding ~1e-13; bound 1e-12.
      EXPECT_NEAR(c.normal_force, f.z(), 1e-12);
      EXPECT_NEAR(c.cop.x(), p.x() - s.x(), 1e-12);
      EXPECT_NEAR(c.cop.y(), p.y() - s.y(), 1e-12);
      // About the sole centre c = (s, −d): (p − c) × f, its x and y.
      const Eigen::Vector3d arm(p.x() - s.x(), p.y() - s.y(), 0.0);
      const Eigen::Vector3d torque = arm.cross(f);
      EXPECT_NEAR(c.torque.x(), torque.x(), 1e-11);
      EXPECT_NEAR(c.torque.y(), torque.y(), 1e-11);
    }
  }
}

TEST(FootWrench, AFootInTheAirHasNoCentreOfPressure) {
  // Off the ground the sensor carries only the foot's weight.
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  const FootContact c = foot_contact(reading(Eigen::Vector3d::Zero(), Eigen::Vector2d(0.03, 0.02), R), R, kDepth,
                                     kFootMass, humanoid::kDefaultGravity);
  EXPECT_NEAR(c.normal_force, 0.0, 1e-12);
  EXPECT_EQ(c.cop, Eigen::Vector2d::Zero());
}

}  // namespace
}  // namespace flexgait::walking
