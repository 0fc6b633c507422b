#pragma once
/// \file controller.hpp
/// The controller slot of the closed loop (docs/guide/loop.md): sensor readings and the time in,
/// motor position commands out. The builtin walking controller is one implementation
/// (walking_control.hpp); a user's controller (a whole-body PD, an MPC, a learned policy) is
/// another, in C++ by subclassing or in Python through the bindings. A controller sees only
/// SensorReadings, never the twin.
#include <Eigen/Core>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/robot/joints.hpp"
#include "flexgait/robot/sensors.hpp"

namespace flexgait::loop {

/// What the deformation compensators need to know of the controller's intent in a period
/// (docs/theory/humanoid.md, "The deformation model"): the readings as it used them (a health
/// check may hold bad values), which feet it swings and where it places the soles, its reference
/// ZMP, its pelvis command and its estimate of the pelvis attitude.
struct ControlContext {
  humanoid::SensorReadings sensors;   ///< the readings as the controller used them
  compensation::SupportPlan support;  ///< swinging feet, planned soles, reference ZMP, pelvis, plan's motion
  Eigen::Matrix3d attitude = Eigen::Matrix3d::Identity();  ///< the controller's pelvis attitude (pelvis to world)
  bool sensors_good = true;  ///< no reading was flagged bad this period (stiffness identification uses only these)
};

/// A controller of the twin. The loop calls `update` once per control period, then `sent` with
/// the command the servos really receive (after the compensators and the joint ranges).
class Controller {
 public:
  virtual ~Controller() = default;
  /// One control period: sensors at time t [s] in, motor-side position commands [rad] out
  /// (humanoid::kJointNames order).
  virtual humanoid::JointVector update(const humanoid::SensorReadings& sensors, double t) = 0;
  /// The command the servos received for the last update [rad].
  virtual void sent(const humanoid::JointVector& /*command*/) {}
  /// The context of the last update for the compensators; nullptr: the controller reports none and
  /// the loop takes the robot to stand on both feet (CompensationStage::standing_context).
  virtual const ControlContext* context() const { return nullptr; }
};

}  // namespace flexgait::loop
