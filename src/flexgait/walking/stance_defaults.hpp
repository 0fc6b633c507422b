#pragma once
/// \file stance_defaults.hpp
/// The walking height and step width a robot walks at unless the configuration sets them
/// (docs/guide/robot.md: `walk.pelvis_height: auto`, `walk.step_width: auto`, the defaults). Rules on the
/// controller's model, so a loaded robot gets its own numbers and the builtin keeps ROBOTIS's.
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

struct StanceDefaults {
  double pelvis_height = 0;  ///< walk.pelvis_height: stretched height − kCrouchShare · (thigh + shank), to 1 mm [m]
  double step_width = 0;     ///< walk.step_width: the sole centres under the hip points, to 1 mm [m]
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

}  // namespace flexgait::walking
