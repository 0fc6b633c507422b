#pragma once
/// \file robot_model_dynamics.hpp
/// Inverse dynamics of the controller's own rigid-body model (robot_model.hpp) by the recursive
/// Newton–Euler algorithm (Luh, Walker and Paul 1980; Featherstone, "Rigid Body Dynamics
/// Algorithms", §5.3), in the world frame, for the floating pelvis (docs/guide/compensation.md, docs/theory/humanoid.md
/// "The actuator deformation model" beyond statics). No simulator, no allocation.
///
/// Forward pass, body i with parent p, r = p_i − p_p, a = R_i · axis (joint origins lie on the axes):
///     ω_i = ω_p + a q̇_i,            α_i = α_p + a q̈_i + ω_p × a q̇_i,
///     v_i = v_p + ω_p × r,          a_i = a_p + α_p × r + ω_p × (ω_p × r),
/// with the pelvis's a_0 = its acceleration − g (gravity as a fictitious upward acceleration).
/// Each body's inertial wrench at its centre c_i = R_i com:
///     F_i = m_i (a_i + α_i × c_i + ω_i × (ω_i × c_i)),   N_i = I_i α_i + ω_i × I_i ω_i, I_i = R_i I R_iᵀ,
/// N_i formed in the body's frame, R_i (I R_iᵀα_i + R_iᵀω_i × I R_iᵀω_i) (the same moment; I_i never formed).
/// Backward pass (children before parents): the wrench the parent applies to body i's subtree,
///     f_i = F_i + Σ_children f_j,   n_i = N_i + c_i × F_i + Σ_children (n_j + (p_j − p_i) × f_j),
/// about the body origin p_i; the joint torque is τ_i = a · n_i (the gear torque on the child,
/// the sign of leg_gravity_torque) and (f_0, n_0) is the net wrench the pelvis needs.
/// A foot's wrench may be given instead of computed (a measured ankle F/T reading: the leg's wrench
/// on the foot); then nothing below the sensor is modelled. With q̇ = q̈ = 0 and the pelvis at rest
/// the leg torques are leg_gravity_torque's.
///
/// The derivative ∂τ/∂q of one leg's torques with respect to its own joints (inverse_dynamics_derivative) is
/// the recursive derivative of the same algorithm (Carpentier and Mansard 2018, "Analytical derivatives of rigid
/// body dynamics algorithms", RSS), in spatial vectors about a fixed point (Featherstone 2008, §2). Turning joint k
/// (motion subspace S_k) turns everything below it rigidly (S_k ×) and changes the motion of every body m below it
/// by −W_k in velocity and −U_k − W_k × V_m in acceleration, W_k = S_k × V_λ(k), U_k = S_k × A_λ(k) − W_k × V_λ(k);
/// with the composite inertia I^c and the composite B^c (B_m W = I_m (W × V_m) + W ×* I_m V_m + V_m ×* I_m W) below
/// each joint,
///     ∂τ_i/∂q_k = S_iᵀ (S_k ×* f_k − I^c_k U_k − B^c_k W_k)   (i at or above k),
///     ∂τ_i/∂q_k = −S_iᵀ (I^c_i U_k + B^c_i W_k)               (i below k),
/// f_k the subtree's force. The pelvis's motion and the gravity do not turn. One backward pass over the leg (the
/// composites), no allocation.
#include <array>

#include "flexgait/robot/joints.hpp"
#include "flexgait/walking/robot_model.hpp"

namespace flexgait::walking {

/// The pelvis's motion, world frame.
struct BaseMotion {
  Vector3d velocity = Vector3d::Zero();              ///< of the pelvis origin [m/s]
  Vector3d angular_velocity = Vector3d::Zero();      ///< [rad/s]
  Vector3d acceleration = Vector3d::Zero();          ///< of the pelvis origin, d/dt velocity [m/s^2]
  Vector3d angular_acceleration = Vector3d::Zero();  ///< [rad/s^2]
};

/// A force and a moment about a stated point, world frame.
struct Wrench {
  Vector3d force = Vector3d::Zero();   ///< [N]
  Vector3d moment = Vector3d::Zero();  ///< [Nm]
};

struct RobotDynamicsData {
  std::array<Vector3d, kBodies> angular_velocity;      ///< ω_i, world [rad/s]
  std::array<Vector3d, kBodies> velocity;              ///< v_i of the body origin, world [m/s]
  std::array<Vector3d, kBodies> angular_acceleration;  ///< α_i, world [rad/s^2]
  std::array<Vector3d, kBodies> acceleration;          ///< a_i of the body origin, world, gravity taken out [m/s^2]
  std::array<Wrench, kBodies> body_wrench;   ///< each body's own inertial wrench (F_i, N_i + c_i × F_i), about p_i
  std::array<Wrench, kBodies> joint_wrench;  ///< (f_i, n_i): the parent's wrench on body i's subtree, about p_i
  humanoid::JointVector tau{};               ///< τ of every actuated joint [Nm]
};

/// Feet whose wrench is given (the leg's wrench on the foot at the foot origin, world; e.g. an
/// ankle F/T reading) rather than computed from the foot's own inertia.
struct FootWrenches {
  std::array<bool, 2> given{};
  std::array<Wrench, 2> wrench;
};

/// inverse_dynamics's forward pass alone: each body's angular velocity and acceleration and its origin's velocity
/// and acceleration (with `gravity` 1, plus g upward: the weight as an acceleration) into `data`.
void forward_motion(const RobotModel& model, const RobotModelData& kinematics, const BaseMotion& base,
                    const humanoid::JointVector& qd, const humanoid::JointVector& qdd, RobotDynamicsData& data,
                    double gravity = 1.0);

/// Inverse dynamics after forward_kinematics(model, kinematics, pelvis, q).
/// \param qd joint velocities (humanoid::kJoints) [rad/s]; \param qdd joint accelerations [rad/s^2]
/// \param gravity 1 to include the weight (model.gravity), 0 for the inertial part alone
/// \return the torques in data.tau; the pelvis's wrench in data.joint_wrench[0]
/// \param first > 0: only the bodies from `first` on and their joints' torques, after a whole pass with the same
/// arguments but these bodies' angles (e.g. kFirstLegBody: the legs' torques after a change of their angles alone,
/// the same numbers as a whole pass); the wrenches and torques above are kept from that pass.
void inverse_dynamics(const RobotModel& model, const RobotModelData& kinematics, const BaseMotion& base,
                      const humanoid::JointVector& qd, const humanoid::JointVector& qdd, RobotDynamicsData& data,
                      const FootWrenches& feet = {}, double gravity = 1.0, int first = 0);

/// The backward pass alone: inverse_dynamics's result for other given feet `feet` after an inverse_dynamics(model,
/// kinematics, base, qd, qdd, data, …) with the same pose and motion (its bodies' own wrenches, data.body_wrench, are
/// kept); the same numbers as inverse_dynamics with these feet, without its forward pass.
void inverse_dynamics_with_feet(const RobotModel& model, const RobotModelData& kinematics, RobotDynamicsData& data,
                                const FootWrenches& feet, int first = 0);

/// ∂τ_i/∂q_j of leg `side`'s joints (rows and columns in role order: hip yaw, roll, pitch, knee, ankle pitch,
/// roll) [Nm/rad].
using LegTorqueDerivative = Eigen::Matrix<double, 6, 6>;

/// ∂τ/∂q of leg `side`'s six torques with respect to its own six joint angles, the velocities, accelerations
/// and the pelvis's motion held, after inverse_dynamics(model, kinematics, …, data, feet, …) with the same
/// arguments (the motion is read from `data`). A foot's given wrench is taken as fixed in the foot (an ankle F/T
/// reading turned into the world by the foot's frame: it turns with the foot).
LegTorqueDerivative inverse_dynamics_derivative(const RobotModel& model, const RobotModelData& kinematics,
                                                const RobotDynamicsData& data, const FootWrenches& feet, int side);

}  // namespace flexgait::walking
