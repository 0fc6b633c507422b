#pragma once
// A test fixture of the compensation tests: the builtin robot standing still on both feet, the soles
// flat under the hips, the COM over the middle of the soles, and what its F/T sensors read.
#include <array>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/walking/leg_kinematics.hpp"

namespace flexgait::compensation::fixtures {

using humanoid::JointVector;
using walking::Matrix3d;
using walking::Pose;
using walking::Vector3d;

/// Standing on both feet, soles flat under the hips, the COM over the middle of the soles.
struct Stance {
  walking::RobotModel model = walking::make_robot_model(humanoid::RobotParams{});
  std::array<Pose, 2> soles;
  JointVector q{};
  Stance() {
    const double y = model.leg[0].anchor[0].y();
    soles = {Pose{Vector3d(0, y, 0), Matrix3d::Identity()}, Pose{Vector3d(0, -y, 0), Matrix3d::Identity()}};
    Pose pelvis{Vector3d(0, 0, 0.72), Matrix3d::Identity()};
    walking::RobotModelData data;
    for (int it = 0; it < 40; ++it) {
      for (int side = 0; side < 2; ++side) {
        const walking::IkSolution ik =
            walking::leg_inverse_kinematics(model.leg[side], Pose{soles[side].p - pelvis.p, Matrix3d::Identity()});
        for (int i = 0; i < humanoid::kLegJoints; ++i) q[humanoid::leg_first_joint(side) + i] = ik.q[i];
      }
      walking::forward_kinematics(model, data, pelvis, q);
      pelvis.p.x() -= walking::center_of_mass(model, data).x();
    }
  }
  SupportPlan plan() const {
    SupportPlan p;
    p.soles = soles;
    p.zmp_ref = 0.5 * (soles[0].p + soles[1].p).head<2>();  // equal split, each share at its sole centre
    return p;
  }
  /// What each ankle F/T sensor reads when the ground pushes W/2 up at each sole centre: the leg's
  /// wrench on the foot (foot frame, about the foot origin) = −(ground's) − (the foot's weight).
  std::array<humanoid::ForceTorque, 2> readings() const {
    walking::RobotModelData data;
    walking::forward_kinematics(model, data, Pose{Vector3d::Zero(), Matrix3d::Identity()}, q);
    std::array<humanoid::ForceTorque, 2> ft;
    for (int side = 0; side < 2; ++side) {
      const Pose& foot = data.frame[model.foot[side]];
      const auto& b = model.bodies[model.foot[side]];
      const Vector3d ground(0, 0, 0.5 * model.total_mass * humanoid::kDefaultGravity),
          weight(0, 0, -b.mass * humanoid::kDefaultGravity);
      const Vector3d f = -ground - weight;
      const Vector3d m =
          -(walking::sole_pose(model, data, side).p - foot.p).cross(ground) - (foot.R * b.com).cross(weight);
      const Vector3d fs = foot.R.transpose() * f, ms = foot.R.transpose() * m;
      for (int i = 0; i < 3; ++i) ft[side].force[i] = fs(i), ft[side].torque[i] = ms(i);
    }
    return ft;
  }
};

/// The stance's F/T readings, measured at time t (their stamps).
inline std::array<humanoid::ForceTorque, 2> readings(const Stance& s, double t) {
  std::array<humanoid::ForceTorque, 2> ft = s.readings();
  ft[0].stamp = ft[1].stamp = t;
  return ft;
}

/// The compensators' belief of every gear's k in the identification tests [Nm/rad].
inline constexpr double kBelief = 1000.0;

/// The identification tests' parameters: the belief kBelief, observation noise 1e-4 rad, k estimation `mode`.
inline CompensationParams identification_params(KEstimation mode) {
  CompensationParams p;
  p.k_joint = kBelief;
  p.k_estimation = mode;
  p.k_estimation_noise = 1e-4;
  return p;
}

}  // namespace flexgait::compensation::fixtures
