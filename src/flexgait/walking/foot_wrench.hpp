#pragma once
/// \file foot_wrench.hpp
/// What an ankle F/T sensor says about the ground under the foot (Kajita et al., "Introduction
/// to Humanoid Robotics", §3.3): the sensor reads the leg's wrench on the foot at the ankle; the
/// ground's is its opposite less the foot's weight. With the sole d below the ankle, the centre of
/// pressure in the sole frame is
///
///   p_x = (−τ_y − d f_x) / f_z,   p_y = (τ_x − d f_y) / f_z,
///
/// and the ground's torque about that point is τ + (0, 0, d) × f. A sole whose centre is shifted
/// by s = (s_x, s_y) from below the sensor (foot frame; the builtin's 14 mm outward) has p − s and
/// the torque about its centre, less s × f.
#include <Eigen/Dense>

#include "flexgait/robot/sensors.hpp"

namespace flexgait::walking {

struct FootContact {
  double normal_force = 0;                          ///< ground force along the sole normal [N]
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< the ground's force on the sole, sole frame [N]
  Eigen::Vector2d cop =
      Eigen::Vector2d::Zero();  ///< centre of pressure in the sole frame [m] (valid if normal_force > 0)
  Eigen::Vector2d torque = Eigen::Vector2d::Zero();  ///< ground torque about the sole centre, sole x and y [Nm]
};

/// \param sole_R orientation of the sole (world), for the foot's weight
/// \param ankle_to_sole d [m]; \param foot_mass mass below the sensor [kg]; \param gravity along −z [m/s^2]
/// \param sole_shift s [m]: cop and torque are then about the sole centre
FootContact foot_contact(const humanoid::ForceTorque& ft, const Eigen::Matrix3d& sole_R, double ankle_to_sole,
                         double foot_mass, double gravity, const Eigen::Vector2d& sole_shift = Eigen::Vector2d::Zero());

}  // namespace flexgait::walking
