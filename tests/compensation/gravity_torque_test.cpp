// The deformation model's load (spec eqs. 4-6 and the full form) on the controller's own model:
// the weight split at both feet and the midpoint, the centres of pressure carry the weight's
// moment, τ_g = −Jᵀ F by virtual work, and the two forms differ by exactly the legs' own weight.
#include "flexgait/compensation/gravity_torque.hpp"

#include <gtest/gtest.h>

#include <random>

#include "flexgait/walking/leg_kinematics.hpp"

namespace flexgait::compensation {
namespace {

using walking::Matrix3d;
using walking::Pose;
using walking::Vector3d;

constexpr std::array<bool, 2> kDouble{false, false};
const std::array<walking::SolePolygon, 2> kSoles{walking::rectangle_sole(0.22, 0.15),
                                                 walking::rectangle_sole(0.22, 0.15)};

TEST(WeightSplit, AtBothFeetAndTheMidpoint) {
  const Eigen::Vector2d left(0.1, 0.093), right(0.0, -0.093);
  EXPECT_DOUBLE_EQ(weight_split(left, left, right), 1.0);  // eq. 5: all on the left
  EXPECT_DOUBLE_EQ(weight_split(right, left, right), 0.0);
  EXPECT_NEAR(weight_split(0.5 * (left + right), left, right), 0.5, 1e-15);
  EXPECT_NEAR(weight_split(0.75 * left + 0.25 * right, left, right), 0.75, 1e-15);
  // Along the line only: a sideways offset of the point does not change μ.
  const Eigen::Vector2d normal(-(left - right).y(), (left - right).x());
  EXPECT_NEAR(weight_split(0.5 * (left + right) + 0.3 * normal, left, right), 0.5, 1e-15);
  // Clamped to [0, 1] beyond the feet.
  EXPECT_DOUBLE_EQ(weight_split(left + (left - right), left, right), 1.0);
  EXPECT_DOUBLE_EQ(weight_split(right - (left - right), left, right), 0.0);
}

TEST(SupportLoads, SingleSupportPutsEverythingOnTheStanceFootUnderThePoint) {
  const std::array<Pose, 2> soles = {Pose{Vector3d(0.2, 0.1, 0), walking::rot_z(0.3)},
                                     Pose{Vector3d(0.0, -0.1, 0.04), Matrix3d::Identity()}};
  const Eigen::Vector2d point(0.21, 0.08);
  const FootLoads loads = support_loads(point, soles, {false, true}, kSoles);
  EXPECT_DOUBLE_EQ(loads.share[0], 1.0);
  EXPECT_DOUBLE_EQ(loads.share[1], 0.0);
  const Vector3d cop = soles[0].p + soles[0].R * Vector3d(loads.cop[0].x(), loads.cop[0].y(), 0);
  EXPECT_LT((cop.head<2>() - point).norm(), 1e-15);
  // Outside the sole: clamped to its edge.
  const FootLoads far = support_loads(Eigen::Vector2d(1.0, 0.1), soles, {false, true}, kSoles);
  EXPECT_LE(far.cop[0].x(), 0.11 + 1e-15);
  EXPECT_LE(std::abs(far.cop[0].y()), 0.075 + 1e-15);
}

TEST(SupportLoads, DoubleSupportForcesHaveTheirResultantAtThePoint) {
  const std::array<Pose, 2> soles = {Pose{Vector3d(0.1, 0.093, 0), Matrix3d::Identity()},
                                     Pose{Vector3d(0.0, -0.093, 0), Matrix3d::Identity()}};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> s(0.0, 1.0), off(-0.03, 0.03);
  for (int trial = 0; trial < 100; ++trial) {
    const double a = s(rng);
    const Eigen::Vector2d point =
        a * soles[0].p.head<2>() + (1 - a) * soles[1].p.head<2>() + Eigen::Vector2d(off(rng), 0);
    const FootLoads loads = support_loads(point, soles, kDouble, kSoles);
    EXPECT_NEAR(loads.share[0] + loads.share[1], 1.0, 1e-15);
    Eigen::Vector2d resultant = Eigen::Vector2d::Zero();
    for (int side = 0; side < 2; ++side) resultant += loads.share[side] * (soles[side].p.head<2>() + loads.cop[side]);
    EXPECT_LT((resultant - point).norm(), 1e-14);  // the weight's moment is carried
  }
}

/// A random pose of the controller's model: pelvis tilted a little, legs bent.
humanoid::JointVector random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  humanoid::JointVector q{};
  for (int side = 0; side < 2; ++side) {
    const int j = humanoid::leg_first_joint(side);
    q[j] = 0.3 * u(rng);
    q[j + 1] = 0.5 * u(rng);
    q[j + 2] = -0.4 + u(rng);
    q[j + 3] = 0.8 + u(rng);
    q[j + 4] = -0.4 + u(rng);
    q[j + 5] = 0.5 * u(rng);
  }
  return q;
}

TEST(GravityTorque, IsMinusJacobianTransposeTimesTheGroundForceByVirtualWork) {
  const walking::RobotModel model = walking::make_robot_model(humanoid::RobotParams{});
  walking::RobotModelData data, shifted;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> tilt(-0.1, 0.1);
  const double weight = model.total_mass * humanoid::kDefaultGravity;
  for (int trial = 0; trial < 50; ++trial) {
    const Pose pelvis{Vector3d(0.1, 0.0, 0.7), walking::rot_x(tilt(rng)) * walking::rot_y(tilt(rng))};
    const humanoid::JointVector q = random_pose(rng);
    walking::forward_kinematics(model, data, pelvis, q);
    FootLoads loads;
    loads.share = {0.3, 0.7};
    loads.cop = {Eigen::Vector2d(0.02, -0.01), Eigen::Vector2d(-0.05, 0.03)};
    const humanoid::JointVector thesis = gravity_torque(model, data, loads, GravityForm::kThesis);
    const humanoid::JointVector full = gravity_torque(model, data, loads, GravityForm::kFull);
    for (int side = 0; side < 2; ++side) {
      const walking::LegTorque g = walking::leg_gravity_torque(model, data, side);
      for (int i = 0; i < humanoid::kLegJoints; ++i) {
        const int j = humanoid::leg_first_joint(side) + i;
        // Thesis form: the force at the sole centre. Virtual work: τ_j = −F · ∂p_sole/∂θ_j.
        const double h = 1e-6;
        humanoid::JointVector qp = q, qm = q;
        qp[j] += h;
        qm[j] -= h;
        walking::forward_kinematics(model, shifted, pelvis, qp);
        const Vector3d pp = walking::sole_pose(model, shifted, side).p;
        walking::forward_kinematics(model, shifted, pelvis, qm);
        const Vector3d pm = walking::sole_pose(model, shifted, side).p;
        const double virtual_work = -(loads.share[side] * weight) * (pp - pm).z() / (2 * h);
        EXPECT_NEAR(thesis[j], virtual_work, 1e-8 * weight) << humanoid::kJointNames[j];
        // The forms differ by the legs' own weight and the force's point of action (cop).
        const walking::LegJacobian J = walking::leg_jacobian(
            model, data, side,
            walking::sole_pose(model, data, side).p +
                walking::sole_pose(model, data, side).R * Vector3d(loads.cop[side].x(), loads.cop[side].y(), 0));
        const double expected = g(i) - J(2, i) * loads.share[side] * weight;
        EXPECT_NEAR(full[j], expected, 1e-10) << humanoid::kJointNames[j];
      }
    }
    EXPECT_EQ(thesis[humanoid::kWaistYaw], 0.0);
  }
}

TEST(GravityTorque, SwingLegCarriesOnlyItsOwnWeightInTheFullFormAndNothingInTheThesisForm) {
  const walking::RobotModel model = walking::make_robot_model(humanoid::RobotParams{});
  walking::RobotModelData data;
  std::mt19937 rng(11);
  walking::forward_kinematics(model, data, Pose{Vector3d(0, 0, 0.7), Matrix3d::Identity()}, random_pose(rng));
  const FootLoads loads = com_loads(model, data, {false, true});
  const walking::LegTorque g = walking::leg_gravity_torque(model, data, 1);
  const humanoid::JointVector full = gravity_torque(model, data, loads, GravityForm::kFull);
  const humanoid::JointVector thesis = gravity_torque(model, data, loads, GravityForm::kThesis);
  for (int i = 0; i < humanoid::kLegJoints; ++i) {
    EXPECT_NEAR(full[humanoid::leg_first_joint(1) + i], g(i), 1e-14);
    EXPECT_EQ(thesis[humanoid::leg_first_joint(1) + i], 0.0);
  }
}

}  // namespace
}  // namespace flexgait::compensation
