#pragma once
/// \file planned_motion.hpp
/// The plan's own joint and pelvis motion — velocities and accelerations without the balance
/// loops — for the inertial torques of control.load_model = dynamic (docs/guide/compensation.md).
///
/// The plan is smooth: the COM of the preview controller's cart-table (its state (c, ċ, c̈) is the
/// COM's position, velocity and acceleration), the soles of feet_target (quintic swing, C²), the
/// pelvis at its height and the feet's mean heading. Its pose at time t is the IK of c, the soles
/// and the heading, with the pelvis position found so that the model's COM lies over c (Newton on
/// the pelvis's xy, the Jacobian ∂c/∂p the last pose's exact one, by differences at first). The joint and pelvis motion
/// is that pose's exact derivative: the soles' rates from feet_motion (the plan's own derivatives),
/// each leg's q̇ = J⁻¹(sole twist − the pelvis's motion carried to the sole) and q̈ = J⁻¹(sole
/// acceleration − the bias of q̈ = 0) with J the leg's Jacobian, and the pelvis's horizontal
/// velocity and acceleration such that the model's COM moves as ċ and c̈ (the COM Jacobian with the
/// soles held). The balance loops' corrections (foot rotations and lifts, the pelvis's
/// counter-tilt, the ZMP feedback's COM shift) are fed back from the sensors: they enter the pose as
/// constants, not as motion (differenced, their sensor noise would reach the accelerations).
#include <array>

#include "flexgait/robot/joints.hpp"
#include "flexgait/walking/footstep_plan.hpp"
#include "flexgait/walking/leg_kinematics.hpp"
#include "flexgait/walking/preview_control.hpp"
#include "flexgait/walking/robot_model.hpp"
#include "flexgait/walking/robot_model_dynamics.hpp"

namespace flexgait::walking {

struct PlannedMotion {
  bool valid = false;                               ///< computed this period
  humanoid::JointVector velocity{};                 ///< q̇ of the plan [rad/s]
  humanoid::JointVector acceleration{};             ///< q̈ of the plan [rad/s^2]
  BaseMotion pelvis;                                ///< the pelvis's planned motion (world)
  Vector3d pelvis_position = Vector3d::Zero();      ///< the plan pose's pelvis origin (world) [m]
  Matrix3d pelvis_attitude = Matrix3d::Identity();  ///< the plan pose's pelvis attitude (world)
  Vector3d com_position = Vector3d::Zero();         ///< the COM the pose was placed at: the cart's c + offset (xy) [m]
  Vector3d com_velocity = Vector3d::Zero();         ///< the cart-table's ċ (horizontal; world) [m/s]
  Vector3d com_acceleration = Vector3d::Zero();     ///< the cart-table's c̈ (horizontal; world) [m/s^2]
  /// ∂c/∂φ: the COM's horizontal move per rotation φ of the pelvis (world; its origin and the soles held) [m/rad].
  Eigen::Matrix<double, 2, 3> com_per_rotation = Eigen::Matrix<double, 2, 3>::Zero();
};

/// Pelvis position (its attitude pelvis.R given) and joint angles that put the soles at `soles`
/// and the COM's xy at `com`: `iterations` rounds of IK and a shift of the pelvis by the COM's
/// miss, from pelvis.p. With `kinematics`, leaves the pose's kinematics in `data`; the waist yaw is 0.
void solve_com_pose(const RobotModel& model, RobotModelData& data, const Eigen::Vector2d& com,
                    const std::array<Pose, 2>& soles, Pose& pelvis, humanoid::JointVector& q,
                    std::array<IkStatus, 2>& ik, int iterations, bool kinematics = true);

/// The pelvis heading of two soles: the mean of their headings (as unit vectors, no wrap at ±π) [rad].
double heading_of(const std::array<Pose, 2>& soles);

/// What the plan's pose at a time depends on besides the time.
struct PlanPoseInputs {
  const RobotModel* model = nullptr;
  const WalkPlan* plan = nullptr;
  double swing_height = 0;                               ///< walk.swing_height [m]
  double pelvis_height = 0;                              ///< walk.pelvis_height [m]
  std::array<Eigen::Vector3d, 2> cart;                   ///< (c, ċ, c̈) of x and y at time t [m, m/s, m/s^2]
  Eigen::Vector2d com_offset = Eigen::Vector2d::Zero();  ///< constant shift of the COM (balance) [m]
  Matrix3d tilt = Matrix3d::Identity();                  ///< constant pelvis tilt after the heading (balance)
};

/// The plan's motion at time t, the pose's pelvis from `guess` (the pelvis of a nearby pose: the
/// last period's plan pose carried forward by its motion, or the commanded one). `inverse`:
/// (∂c/∂p)⁻¹, the pelvis's Newton step per COM miss, by differences at the guess when `refresh`
/// (else used as given: from a pose of the last ~0.1 s it still converges); left as the pose's
/// exact one (the COM Jacobian with the soles held, which the rates use) when the motion is valid.
/// Newton stops once the COM's miss is at most kPlanComTolerance. `data` is scratch (it holds the
/// pose's kinematics after). Not valid (all zero) where a leg's Jacobian is singular.
/// 1e-7 m: the loads' torques move by the weight times the miss (~6e-5 Nm for 60 kg), the deflections by 6e-8 rad,
/// 1/200 of an encoder count (1e-9 cost 3.9k more instructions per control period in the default walk).
inline constexpr double kPlanComTolerance = 1e-7;  ///< [m] on each horizontal axis

PlannedMotion planned_motion(const PlanPoseInputs& in, double t, const Pose& guess, RobotModelData& data,
                             Eigen::Matrix2d& inverse, bool refresh = true);

/// The pelvis position a period T after the plan pose `last` that puts the COM at `com` with the pelvis at
/// `attitude`, to first order: `last` carried by its motion (which moves the COM by ċT + c̈T²/2 and turns the heading
/// by ψ̇T + ψ̈T²/2), then a Newton step, with `inverse` = (∂c/∂p)⁻¹ at `last`, for what the motion does not hold: the
/// target's move beyond it (the preview's jerk, T³u/6; the balance's COM shift) and the attitude's turn beyond the
/// heading's (the balance's counter-tilt) through last.com_per_rotation. Its miss is of second order in the changes
/// (the default walk's median 4e-8 m; without the tilt's term 1.4e-6 m).
Vector3d carried_pelvis(const PlannedMotion& last, double T, const Eigen::Vector2d& com, const Matrix3d& attitude,
                        const Eigen::Matrix2d& inverse);

}  // namespace flexgait::walking
