#pragma once
/// \file elastic_drives.hpp
/// The elastic gear actuators (elastic_actuator.hpp) coupled to MuJoCo hinge joints, for the
/// twin's own sources (not installed). Per physics step, with the link state θ_l, θ̇_l at the
/// step's start:
///
///   motor:  step_motor (semi-implicit Euler) toward the command
///   link:   qfrc_applied = k dz(θ_m − θ_l) + d θ̇_m       (the spring and the motor-side damping)
///           −d θ̇_l                                         (the joint's damping, implicit in MuJoCo)
///
/// The spring is a generalised force beside the damping term: the joint's own MuJoCo stiffness is
/// zero (ElasticDrives::take_springs), so the model stays const while the twin runs.
#include <mujoco/mujoco.h>

#include <vector>

#include "flexgait/twin/elastic_actuator.hpp"

namespace flexgait::twin {

/// The drives' configuration (immutable while running); their states live with the plant's state.
class ElasticDrives {
 public:
  /// A joint the robot does not have (a trunk without a waist): its drive reads 0 and acts on nothing.
  static constexpr int kAbsentJoint = -1;
  /// \param joints MuJoCo joint ids (hinges whose damping the model holds), or kAbsentJoint.
  ElasticDrives(const mjModel* m, std::vector<int> joints, std::vector<ActuatorParams> params);
  /// Zeroes the joints' MuJoCo stiffness: the drives apply the spring (call before running).
  void take_springs(mjModel* m) const;
  /// Motors at rest at the link angles of d (no deflection), integrators cleared.
  std::vector<ActuatorState> at_rest(const mjData* d) const;
  /// One physics step: motors advance toward `commands` (one per joint), the spring and the
  /// motor-side damping go into qfrc_applied, then mj_step.
  void step(const mjModel* m, mjData* d, std::vector<ActuatorState>& states, const double* commands) const;
  const std::vector<ActuatorParams>& params() const { return params_; }
  const std::vector<int>& qpos_index() const { return qpos_; }
  const std::vector<int>& dof_index() const { return dof_; }

 private:
  std::vector<int> joints_, qpos_, dof_;
  std::vector<ActuatorParams> params_;
};

}  // namespace flexgait::twin
