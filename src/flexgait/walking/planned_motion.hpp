#pragma once
/// \file planned_motion.hpp
/// The plan's own joint and pelvis motion — velocities and accelerations without the balance
/// loops — for the inertial torques of control.load_model = dynamic (docs/guide/compensation.md).
///
/// The plan is smooth: the COM of the preview controller's cart-table (its state (c, ċ, c̈) is the
/// COM's position, velocity and acceleration), the soles of feet_target (quintic swing, C²), the
/// pelvis at its height and the feet's mean heading. Its pose at time t + s is the IK of
///     c(t + s) = c + s ċ + s²/2 c̈,   soles(t + s),   yaw(t + s),
/// with the pelvis position found so that the model's COM lies over c (Newton on the pelvis's xy,
/// the Jacobian ∂c/∂p of the centre pose by differences). The joint
/// motion is the central difference of three such poses, s = −h, 0, h:
///     q̇ = (q₊ − q₋) / 2h,   q̈ = (q₊ − 2 q₀ + q₋) / h²,   the same for the pelvis,
/// noise-free and O(h²) (the cart's jerk term, odd in s, cancels in both). The balance loops'
/// corrections (foot rotations and lifts, the pelvis's counter-tilt, the ZMP feedback's COM
/// shift) are fed back from the sensors: they enter the poses as constants, not as motion;
/// differenced, their sensor noise reaches the accelerations amplified by 4/T².
#include <array>

#include "flexgait/robot/joints.hpp"
#include "flexgait/walking/footstep_plan.hpp"
#include "flexgait/walking/leg_kinematics.hpp"
#include "flexgait/walking/preview_control.hpp"
#include "flexgait/walking/robot_model.hpp"
#include "flexgait/walking/robot_model_dynamics.hpp"

namespace flexgait::walking {

struct PlannedMotion {
  bool valid = false;                            ///< computed this period
  humanoid::JointVector velocity{};              ///< q̇ of the plan [rad/s]
  humanoid::JointVector acceleration{};          ///< q̈ of the plan [rad/s^2]
  BaseMotion pelvis;                             ///< the pelvis's planned motion (world)
  Vector3d com_acceleration = Vector3d::Zero();  ///< the cart-table's c̈ (horizontal; world) [m/s^2]
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

/// The plan's motion at time t by central differences of step h [s] (h > 0), each pose's
/// pelvis from `guess` (the pelvis of a nearby pose, e.g. the commanded one). `inverse`: (∂c/∂p)⁻¹,
/// the pelvis's Newton step per COM miss, recomputed at the centre pose when `refresh` (else used
/// as given: from a pose of the last ~0.1 s it still converges). `data` is scratch.
PlannedMotion planned_motion(const PlanPoseInputs& in, double t, double h, const Pose& guess, RobotModelData& data,
                             Eigen::Matrix2d& inverse, bool refresh = true);

}  // namespace flexgait::walking
