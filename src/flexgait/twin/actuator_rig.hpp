#pragma once
/// \file actuator_rig.hpp
/// One elastic gear actuator (elastic_actuator.hpp) on a fixed housing, driving a light arm with a
/// point load about a horizontal hinge (+y), in MuJoCo: the plant of the stiffness bench (thesis
/// Fig. 12, experiments/stiffness_bench.hpp). The arm's angle is measured from horizontal,
/// positive down (the load's gravity torque on the hinge is m g l cos θ).
#include <memory>
#include <string>

#include "flexgait/robot/robot_params.hpp"
#include "flexgait/twin/elastic_actuator.hpp"

namespace flexgait::twin {

struct ActuatorRigParams {
  ActuatorParams actuator;
  double arm_length = 0.3;                     ///< hinge to load [m]
  double load_mass = 13.6;                     ///< point load at the arm's end [kg]
  double physics_dt = 0.001;                   ///< [s]
  double gravity = humanoid::kDefaultGravity;  ///< along −z [m/s^2]
};

class ActuatorRig {
 public:
  /// The arm at rest at `link_angle` [rad], the motor at the same angle (no deflection).
  ActuatorRig(const ActuatorRigParams& params, double link_angle);
  ~ActuatorRig();
  ActuatorRig(const ActuatorRig&) = delete;
  ActuatorRig& operator=(const ActuatorRig&) = delete;

  /// One physics step with this motor-side position command [rad].
  void step(double command);
  double link_angle() const;  ///< [rad]
  const ActuatorState& motor() const;
  int warnings() const;               ///< MuJoCo warnings so far
  std::string warnings_text() const;  ///< as one line ("" if none)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace flexgait::twin
