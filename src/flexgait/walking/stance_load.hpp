#pragma once
/// \file stance_load.hpp
/// What one leg's joints must supply to carry a ground force alone (docs/guide/humanoid.md, the capture step's
/// lift-off). A force F (world) that the ground applies to the sole at the point c, carried by
/// leg `side` quasi-statically, loads each of its joints with the moment of F about the joint's
/// axis,
///
///   τ_i = a_i · ((c − o_i) × F),   i.e. τ = J_v(c)ᵀ F,                                    (L1)
///
/// a_i the joint's unit axis and o_i a point of it (world), J_v the linear rows of the leg's
/// Jacobian at c. The leg's own links' weight (a few N m at the knee) and inertia are left out.
/// Standing on one leg with the centre of pressure at the heel, the bent knee of the twin carries
/// ≈ 0.2 m × m g ≈ 110 N m (measured, docs/guide/humanoid.md): more than its servo's 100 N m.
#include "flexgait/walking/robot_model.hpp"

namespace flexgait::walking {

/// (L1) for the leg `side` after forward_kinematics; `force` and `point` in the frame of `data` [N, m].
LegTorque stance_joint_torques(const RobotModel& model, const RobotModelData& data, int side, const Vector3d& force,
                               const Vector3d& point);

}  // namespace flexgait::walking
