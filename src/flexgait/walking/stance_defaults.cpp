#include "flexgait/walking/stance_defaults.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "flexgait/core/config.hpp"

namespace flexgait::walking {

namespace {

/// Rounded to the millimetre, so a derived default reads as a number a user would type.
double to_millimetre(double x) {
  return std::round(x * 1000.0) / 1000.0;
}

}  // namespace

LegReach leg_reach(const RobotModel& model) {
  LegReach r;
  r.length = std::numeric_limits<double>::infinity();
  Vector3d hip[2];
  for (int side = 0; side < 2; ++side) {
    const LegGeometry& leg = model.leg[static_cast<std::size_t>(side)];
    Vector3d sole = leg.sole;
    for (const Vector3d& a : leg.anchor) sole += a;
    r.stretched_height += -0.5 * sole.z();
    r.length = std::min(r.length, leg.anchor[3].norm() + leg.anchor[4].norm());
    hip[side] = leg.anchor[0] + leg.anchor[1] + leg.anchor[2];
  }
  r.hip_spacing = std::abs(hip[0].y() - hip[1].y());
  return r;
}

namespace {

/// Whether standing at this height and width keeps every joint `margin` inside its range, the IK
/// reaching the soles.
bool stands_inside_ranges(const RobotModel& model, double pelvis_height, double step_width, double margin) {
  for (int side = 0; side < 2; ++side) {
    const Pose sole{Vector3d(0, (side == 0 ? 0.5 : -0.5) * step_width, -pelvis_height), Matrix3d::Identity()};
    const IkSolution s = leg_inverse_kinematics(model.leg[static_cast<std::size_t>(side)], sole);
    if (s.status != IkStatus::kOk) return false;
    for (int i = 0; i < humanoid::kLegJoints; ++i) {
      const auto& r = model.range[static_cast<std::size_t>(humanoid::leg_first_joint(side) + i)];
      const double q = s.q[static_cast<std::size_t>(i)];
      if (!(q >= r[0] + std::min(margin, 0.25 * (r[1] - r[0])) && q <= r[1] - std::min(margin, 0.25 * (r[1] - r[0]))))
        return false;
    }
  }
  return true;
}

}  // namespace

StanceDefaults stance_defaults(const RobotModel& model) {
  const LegReach r = leg_reach(model);
  StanceDefaults d{to_millimetre(r.stretched_height - kCrouchShare * r.length), to_millimetre(r.hip_spacing)};
  if (stands_inside_ranges(model, d.pelvis_height, d.step_width, 0.0)) return d;
  // The rule's height bends a joint out of its range (a robot whose zero pose is not THORMANG's):
  // the nearest height, millimetre by millimetre within the crouch's span either way, that keeps
  // each joint kStandingRangeMargin inside its range (a quarter of a narrower range).
  const int span = static_cast<int>(std::ceil(kCrouchShare * r.length * 1000.0));
  for (int k = 1; k <= span; ++k)
    for (const int sign : {1, -1}) {
      const double h = to_millimetre(d.pelvis_height + sign * k * 1e-3);
      if (h < r.stretched_height && stands_inside_ranges(model, h, d.step_width, kStandingRangeMargin)) {
        d.pelvis_height = h;
        return d;
      }
    }
  return d;  // none: check_standing_pose names the joint
}

double hip_to_ankle(const LegReach& reach, double pelvis_height) {
  return pelvis_height - (reach.stretched_height - reach.length);
}

humanoid::JointVector standing_angles(const RobotModel& model, double pelvis_height, double step_width) {
  humanoid::JointVector q{};
  for (int side = 0; side < 2; ++side) {
    const Pose sole{Vector3d(0, (side == 0 ? 0.5 : -0.5) * step_width, -pelvis_height), Matrix3d::Identity()};
    const IkSolution s = leg_inverse_kinematics(model.leg[static_cast<std::size_t>(side)], sole);
    for (int i = 0; i < humanoid::kLegJoints; ++i)
      q[humanoid::leg_first_joint(side) + i] = s.q[static_cast<std::size_t>(i)];
  }
  return q;
}

void check_standing_pose(const RobotModel& model, double pelvis_height, double step_width) {
  const humanoid::JointVector q = standing_angles(model, pelvis_height, step_width);
  for (int j = 0; j < humanoid::kJoints; ++j) {
    const auto& r = model.range[static_cast<std::size_t>(j)];
    constexpr double kSlack = 1e-9;  // [rad] the IK's rounding at a range's end
    if (q[j] >= r[0] - kSlack && q[j] <= r[1] + kSlack) continue;
    const std::string key = "robot.joints." + std::string(humanoid::kJointNames[j]);
    throw ConfigError(key, fmt::format("key '{}': standing at walk.pelvis_height = {} with walk.step_width = {} needs "
                                       "{:.4f} rad at this joint, outside its range [{:.4f}, {:.4f}] rad; the robot "
                                       "cannot stand there (change the height or width, or the joint's range)",
                                       key, pelvis_height, step_width, q[j], r[0], r[1]));
  }
}

double standing_com_height(const RobotModel& model, double pelvis_height, double step_width) {
  RobotModelData data;
  forward_kinematics(model, data, Pose{Vector3d(0, 0, pelvis_height), Matrix3d::Identity()},
                     standing_angles(model, pelvis_height, step_width));
  return center_of_mass(model, data).z();
}

RobotScale robot_scale(const RobotModel& model, double pelvis_height, const RobotModel& reference,
                       double reference_pelvis_height) {
  const double width = stance_defaults(model).step_width, reference_width = stance_defaults(reference).step_width;
  return {model.total_mass / reference.total_mass, leg_reach(model).length / leg_reach(reference).length,
          standing_com_height(model, pelvis_height, width) /
              standing_com_height(reference, reference_pelvis_height, reference_width)};
}

double scaled_default(const ScaledDefault& d, double builtin, const RobotScale& scale) {
  const double x =
      builtin * std::pow(scale.mass, d.mass) * std::pow(scale.leg, d.leg) * std::pow(scale.com_height, d.com_height);
  if (!(x > 0) || !std::isfinite(x)) return builtin;
  return std::stod(fmt::format("{:.3g}", x));  // 3 significant digits, as a user would type them
}

humanoid::JointVector joint_actuator_torques(const humanoid::LoadedRobot& robot) {
  humanoid::JointVector limit{};
  for (int j = 0; j < humanoid::kJoints; ++j) {
    if (!robot.has_joint(j)) continue;
    const auto [body, joint] = robot.joint[static_cast<std::size_t>(j)];
    limit[j] = robot.bodies[static_cast<std::size_t>(body)].joints[static_cast<std::size_t>(joint)].force_limit;
  }
  return limit;
}

double leg_actuator_torque(const humanoid::LoadedRobot& robot) {
  const humanoid::JointVector limit = joint_actuator_torques(robot);
  double largest = 0;
  for (int j = 0; j < humanoid::kJoints; ++j)
    if (j != humanoid::kWaistYaw) largest = std::max(largest, limit[j]);
  return largest;
}

double fastest_gear_mode(const humanoid::LoadedRobot& robot, const humanoid::JointVector& stiffness) {
  double fastest = 0;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    if (!robot.has_joint(j)) continue;
    const auto [body, joint] = robot.joint[static_cast<std::size_t>(j)];
    const double inertia =
        robot.bodies[static_cast<std::size_t>(body)].joints[static_cast<std::size_t>(joint)].link_inertia;
    if (inertia > 0) fastest = std::max(fastest, std::sqrt(stiffness[j] / inertia));
  }
  return fastest;
}

double gear_physics_step(double rate, double step) {
  // (at most 10 halvings: a step of 1 ms / 1024 would make a walk of seconds take hours)
  for (int i = 0; i < 10 && rate * step > kMaxGearPhasePerStep; ++i) step *= 0.5;
  return step;
}

}  // namespace flexgait::walking
