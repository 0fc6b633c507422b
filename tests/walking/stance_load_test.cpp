// The joint torques of a leg carrying a ground force alone (stance_load.hpp (L1)):
// against the principle of virtual work through the model's own forward kinematics (an
// independent route: no Jacobian), and against the hand computation for the knee of the bent
// standing leg — a force through the knee's axis loads it with nothing, and moving a vertical
// force to the heel loads it with the force times the shift.
#include "flexgait/walking/stance_load.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flexgait::walking {
namespace {

using humanoid::JointVector;
using humanoid::leg_first_joint;

/// Both legs bent as the twin stands (hip pitch −0.6, knee 1.06, ankle pitch −0.46 rad), a little
/// yaw and roll so that no axis is trivially aligned.
JointVector bent_pose() {
  JointVector q{};
  for (int side = 0; side < 2; ++side) {
    const int j = leg_first_joint(side);
    q[j + 0] = 0.05, q[j + 1] = 0.03, q[j + 2] = -0.6, q[j + 3] = 1.06, q[j + 4] = -0.46, q[j + 5] = -0.03;
  }
  return q;
}

TEST(StanceLoad, TorquesDoTheForcesVirtualWork) {
  // τ_i δq_i = F · δc_i for a point c fixed to the foot (central differences of the forward
  // kinematics, h = 1e-6 rad: O(h²) truncation and 1e-10 rounding of a 100 N m torque).
  const RobotModel model = make_robot_model(humanoid::RobotParams{});
  RobotModelData data;
  const JointVector q = bent_pose();
  const Pose pelvis{Vector3d(0.01, -0.02, 0.72), Matrix3d::Identity()};
  forward_kinematics(model, data, pelvis, q);
  for (int side = 0; side < 2; ++side) {
    const Pose foot = data.frame[model.foot[side]];
    const Vector3d point = sole_pose(model, data, side).p + Vector3d(-0.09, 0.03, 0);  // the heel, inside
    const Vector3d in_foot = foot.R.transpose() * (point - foot.p);
    const Vector3d force(40, -25, 560);
    const LegTorque tau = stance_joint_torques(model, data, side, force, point);
    const double h = 1e-6;
    for (int i = 0; i < 6; ++i) {
      RobotModelData moved;
      JointVector qp = q, qm = q;
      qp[leg_first_joint(side) + i] += h;
      qm[leg_first_joint(side) + i] -= h;
      forward_kinematics(model, moved, pelvis, qp);
      const Vector3d cp = moved.frame[model.foot[side]].p + moved.frame[model.foot[side]].R * in_foot;
      forward_kinematics(model, moved, pelvis, qm);
      const Vector3d cm = moved.frame[model.foot[side]].p + moved.frame[model.foot[side]].R * in_foot;
      EXPECT_NEAR(tau(i), force.dot(cp - cm) / (2 * h), 1e-6) << "side " << side << " joint " << i;
    }
  }
}

TEST(StanceLoad, KneeCarriesTheForceTimesItsLever) {
  // Sagittal pose (no yaw or roll): the knee's axis is the world y axis through the knee.
  const RobotModel model = make_robot_model(humanoid::RobotParams{});
  RobotModelData data;
  JointVector q{};
  const int j = leg_first_joint(0);
  q[j + 2] = -0.6, q[j + 3] = 1.06, q[j + 4] = -0.46;
  forward_kinematics(model, data, Pose{Vector3d(0, 0, 0.72), Matrix3d::Identity()}, q);
  int knee_body = 0;
  while (model.bodies[knee_body].joint != humanoid::kLeftKnee) ++knee_body;
  const Vector3d knee = data.frame[knee_body].p, centre = sole_pose(model, data, 0).p;
  const double weight = 57.0 * humanoid::kDefaultGravity;
  // A force along the line from the sole through the knee's axis: no knee torque.
  const Vector3d through = (knee - centre).normalized() * weight;
  EXPECT_NEAR(stance_joint_torques(model, data, 0, through, centre)(3), 0.0, 1e-9 * weight);
  // The weight at the sole's centre and at its heel (9 cm back): |τ| = W |x − x_knee|; the bent
  // knee stands ahead of the ankle, so the heel adds W × 0.09 m (50 N m).
  const Vector3d down(0, 0, weight), heel = centre - Vector3d(0.09, 0, 0);
  const double at_centre = stance_joint_torques(model, data, 0, down, centre)(3);
  const double at_heel = stance_joint_torques(model, data, 0, down, heel)(3);
  EXPECT_GT(knee.x(), centre.x());
  EXPECT_NEAR(std::abs(at_centre), weight * (knee.x() - centre.x()), 1e-9 * weight);
  EXPECT_NEAR(std::abs(at_heel) - std::abs(at_centre), weight * 0.09, 1e-9 * weight);
}

}  // namespace
}  // namespace flexgait::walking
