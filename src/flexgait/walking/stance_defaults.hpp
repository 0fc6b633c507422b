#pragma once
/// \file stance_defaults.hpp
/// The walking height and step width a robot walks at unless the configuration sets them
/// (docs/guide/robot.md: `walk.pelvis_height: auto`, `walk.step_width: auto`, the defaults). Rules on the
/// controller's model, so a loaded robot gets its own numbers and the builtin keeps ROBOTIS's.
#include <array>
#include <string_view>

#include "flexgait/robot/robot_description.hpp"
#include "flexgait/walking/robot_model.hpp"

namespace flexgait::walking {

/// A leg's reach: what the rules and the reach checks need, from the general chain (LegGeometry::anchor).
struct LegReach {
  double stretched_height = 0;  ///< pelvis origin above the sole with every leg joint at zero [m] (mean of the legs)
  double length = 0;            ///< thigh + shank: hip pitch → knee → ankle pitch anchors [m] (the shorter leg)
  double hip_spacing = 0;       ///< lateral distance between the hip points (hip pitch anchors) [m]
};

LegReach leg_reach(const RobotModel& model);

/// Share of thigh + shank by which the pelvis walks below its stretched-leg height: ROBOTIS's
/// walking height for THORMANG3, 0.723 m of 0.8075 m with 0.3 m + 0.3 m legs (the knee bent
/// about 1.07 rad with the hip above the ankle).
inline constexpr double kCrouchShare = 0.0845 / 0.6;

/// How far inside each joint's range a derived walking height keeps the standing pose when the
/// crouch rule's height would not: room for the balance loops' corrections [rad].
inline constexpr double kStandingRangeMargin = 0.1;

struct StanceDefaults {
  /// walk.pelvis_height: stretched height − kCrouchShare · (thigh + shank), to 1 mm; where that
  /// bends a joint out of its range, the nearest height that keeps every joint kStandingRangeMargin
  /// inside its range [m]
  double pelvis_height = 0;
  double step_width = 0;  ///< walk.step_width: the sole centres under the hip points, to 1 mm [m]
};

StanceDefaults stance_defaults(const RobotModel& model);

/// The hip-to-ankle distance at this pelvis height, standing on level ground [m].
double hip_to_ankle(const LegReach& reach, double pelvis_height);

/// The legs' angles standing: each sole level, straight below the pelvis origin, step_width / 2
/// to its side, pelvis_height below it (the leg IK, on the knee branch the ranges allow).
humanoid::JointVector standing_angles(const RobotModel& model, double pelvis_height, double step_width);

/// Throws ConfigError naming robot.joints.<name> when the standing pose (standing_angles) puts a
/// joint outside its range: such a robot cannot stand at this height and width.
void check_standing_pose(const RobotModel& model, double pelvis_height, double step_width);

/// A robot's size against the builtin THORMANG-class robot at its default parameters (the reference of
/// the scaled defaults): ratios of total mass, of thigh + shank and of the standing COM height.
struct RobotScale {
  double mass = 1, leg = 1, com_height = 1;
};

/// The centre of mass's height standing at this pelvis height and step width (standing_angles) [m].
double standing_com_height(const RobotModel& model, double pelvis_height, double step_width);

/// `model` standing at `pelvis_height` against `reference` standing at `reference_pelvis_height`
/// (both at the reference's step width would not do: each at its own hip spacing, StanceDefaults).
RobotScale robot_scale(const RobotModel& model, double pelvis_height, const RobotModel& reference,
                       double reference_pelvis_height);

/// One key whose default follows the robot by dynamic similarity: the builtin's value times
/// mass^m · leg^l · com_height^c (RobotScale's ratios), to 3 significant digits (control.k_joint and
/// balance.capture_torque_limit take the plant's value instead, walk_experiment.cpp). With g fixed, Froude
/// similarity (Alexander & Jayes 1983) makes times scale as √leg and lengths as leg; the linear inverted
/// pendulum's time constant √(z/g) (Kajita et al. 2003) makes the preview and the balance loops' times
/// scale as √com_height and their rates as its inverse; torques scale as weight × leg.
struct ScaledDefault {
  std::string_view key;
  double mass = 0, leg = 0, com_height = 0;
  std::string_view rule;  ///< the rule in words, for the key's documentation (ParamSpec::derived)
};

inline constexpr std::array<ScaledDefault, 18> kScaledDefaults{{
    {"walk.step_time", 0, 0.5, 0, "1 s x sqrt(leg / the builtin's), Froude scaling (the builtin: 1 s)"},
    {"walk.step_length", 0, 1, 0, "0.1 m x leg / the builtin's, Froude scaling (the builtin: 0.1 m)"},
    {"walk.swing_height", 0, 1, 0, "0.05 m x leg / the builtin's (the builtin: 0.05 m)"},
    {"walk.preview_time", 0, 0, 0.5, "1.6 s x sqrt(COM height / the builtin's) (the builtin: 1.6 s)"},
    {"plant.k_joint", 1, 1, 0,
     "1000 Nm/rad x mass x leg / the builtin's: the builtin's gear deflection under the standing weight's torque "
     "(the builtin: 1000)"},
    {"plant.gear_damping", 1, 1.5, 0,
     "80 Nm s/rad x mass x leg^1.5 / the builtin's: the builtin's damping ratio at that stiffness (the builtin: 80)"},
    {"plant.rotor_inertia", 1, 2, 0,
     "0.8 kg m^2 x mass x leg^2 / the builtin's: the builtin's ratio to the leg's inertia (the builtin: 0.8)"},
    {"plant.servo_bandwidth", 0, -0.5, 0, "30 Hz x sqrt(the builtin's leg / leg), Froude scaling (the builtin: 30 Hz)"},
    {"plant.physics_dt", 0, 0, 0,
     "1 ms, halved until the fastest gear mode, sqrt(k / the inertia its joint turns), turns per step at most what "
     "the builtin's turns in 1 ms, 0.224 rad (the explicit gear spring; the builtin: 1 ms)"},
    {"plant.torque_limit", 1, 1, 0,
     "the largest force range of the file's actuators on the leg joints; else 100 Nm x mass x leg / the builtin's "
     "(the builtin: 100); while derived, a joint the file's actuators limit keeps its own limit, set it holds every "
     "joint"},
    {"control.k_joint", 1, 1, 0,
     "plant.k_joint, set or derived: the controller believes the gears' true stiffness (the builtin: 1000)"},
    {"balance.capture_torque_limit", 1, 1, 0, "plant.torque_limit, set or derived (the builtin: 100)"},
    {"balance.contact_force", 1, 0, 0, "50 N x mass / the builtin's (the builtin: 50 N)"},
    {"balance.ankle_damping", 1, 0, 1.5,
     "3000 Nm s/rad x mass x COM height^1.5 / the builtin's: its tilt rate per weight torque scales as the "
     "pendulum's rate (the builtin: 3000)"},
    {"balance.foot_force_damping", 1, 0, -0.5,
     "3000 N s/m x mass / sqrt(COM height), over the builtin's (the builtin: 3000)"},
    {"balance.zmp_ki", 0, 0, -0.5, "0.3 /s x sqrt(the builtin's COM height / COM height) (the builtin: 0.3)"},
    {"balance.dcm_kp", 0, 0, -0.5, "5 /s x sqrt(the builtin's COM height / COM height) (the builtin: 5)"},
    {"balance.dcm_ki", 0, 0, -1, "10 /s^2 x the builtin's COM height / COM height (the builtin: 10)"},
}};

/// `builtin` (the key's value for the builtin robot) scaled by `d`'s rule, to 3 significant digits.
double scaled_default(const ScaledDefault& d, double builtin, const RobotScale& scale);

/// The largest torque the file's actuators can apply on each mapped joint (LoadedJoint::force_limit) [Nm];
/// 0 for a joint the file does not limit or the mapping leaves out.
humanoid::JointVector joint_actuator_torques(const humanoid::LoadedRobot& robot);

/// The fastest gear mode of a loaded robot [rad/s]: the largest over its mapped joints of sqrt(k_j / I_j), the
/// gear's stiffness against the inertia the joint turns (LoadedJoint::link_inertia); 0 if none is known.
double fastest_gear_mode(const humanoid::LoadedRobot& robot, const humanoid::JointVector& stiffness);

/// The most a gear mode may turn in one physics step [rad]: what the builtin's fastest gear mode turns in its
/// 1 ms step (a 1000 Nm/rad gear on the inertia its joint turns, sqrt(k / I) = 223.8 rad/s; a test checks it).
/// MuJoCo's Euler integrator takes a joint's spring explicitly (its damping implicitly): a robot whose gears
/// turn more per step than the builtin's is integrated less accurately than the builtin was validated at (the
/// symplectic Euler method on an oscillator of rate w is stable only for w dt < 2; Hairer, Lubich and Wanner 2006).
inline constexpr double kMaxGearPhasePerStep = 0.224;

/// The physics step for a robot whose fastest gear mode is `rate` [rad/s]: `step` halved until rate x step is at
/// most kMaxGearPhasePerStep (at most 10 times); `step` itself when it already is.
double gear_physics_step(double rate, double step);

/// The largest torque the file's actuators can apply on the mapped leg joints (joint_actuator_torques)
/// [Nm]; 0 when the file limits none of them.
double leg_actuator_torque(const humanoid::LoadedRobot& robot);

}  // namespace flexgait::walking
