#pragma once
/// \file thormang3_inertials.hpp
/// THORMANG3's link masses, centres of mass and inertias (docs/theory/humanoid.md, "The robot";
/// thormang3-inertials.csv beside it, from ROBOTIS's CAD table), and where ROBOTIS's link frames
/// sit (the joint origins of ROBOTIS's kinematics, thormang3_kinematics_dynamics). What the builtin
/// robot's bodies are made of (builtin_inertials.hpp).
#include <array>
#include <string_view>

namespace flexgait::humanoid {

struct Thormang3Link {
  std::string_view name;
  double mass;                    ///< [kg]
  std::array<double, 3> com;      ///< in the link frame [m]
  std::array<double, 6> inertia;  ///< about the centre of mass: ixx, ixy, ixz, iyy, iyz, izz [kg m^2]
};

/// The row of that link (r_leg_hip_p, torso_y, ...); throws std::logic_error if there is none.
const Thormang3Link& thormang3_link(std::string_view name);
/// The sum of the table's masses, 42.533 kg (no batteries or computers).
double thormang3_mass();

}  // namespace flexgait::humanoid
