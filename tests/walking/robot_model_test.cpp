// The controller's own model against the twin's MuJoCo model (two independent implementations of
// the spec's robot): sole poses, whole-body COM, the legs' gravity torques; the Jacobian against
// finite differences of the forward kinematics.
#include "flexgait/walking/robot_model.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <array>
#include <random>
#include <string>

#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"

namespace flexgait::walking {
namespace {

using humanoid::JointVector;
using humanoid::kJointNames;
using humanoid::kJoints;

struct Twin {
  mjModel* m;
  mjData* d;
  Twin() {
    twin::PlantParams p;
    m = twin::load_mjcf(twin::humanoid_mjcf(humanoid::RobotParams{}, p));
    d = mj_makeData(m);
  }
  ~Twin() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  void set(const Pose& pelvis, const JointVector& q) {
    mj_resetData(m, d);
    for (int i = 0; i < 3; ++i) d->qpos[i] = pelvis.p(i);
    const Eigen::Quaterniond quat(pelvis.R);
    d->qpos[3] = quat.w(), d->qpos[4] = quat.x(), d->qpos[5] = quat.y(), d->qpos[6] = quat.z();
    for (int j = 0; j < kJoints; ++j)
      d->qpos[m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, std::string(kJointNames[j]).c_str())]] = q[j];
    mj_forward(m, d);
  }
};

JointVector random_pose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> a(-0.5, 0.5);
  JointVector q;
  for (auto& v : q) v = a(rng);
  return q;
}

Pose random_pelvis(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> a(-0.3, 0.3);
  return {Vector3d(a(rng), a(rng), 0.8 + a(rng)), rpy_to_matrix(a(rng), a(rng), a(rng))};
}

TEST(RobotModel, AgreesWithTheTwin) {
  const RobotModel model = make_robot_model(humanoid::RobotParams{});
  RobotModelData data;
  Twin twin;
  EXPECT_NEAR(model.total_mass, twin.m->body_subtreemass[0], 1e-12);
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Pose pelvis = random_pelvis(rng);
    const JointVector q = random_pose(rng);
    forward_kinematics(model, data, pelvis, q);
    twin.set(pelvis, q);
    // Whole-body COM (the twin: subtree COM of the pelvis). Both exact up to rounding: 1e-12 m.
    const Vector3d com = center_of_mass(model, data);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(com(i), twin.d->subtree_com[3 + i], 1e-12);
    for (int side = 0; side < 2; ++side) {
      // The sole centre: the F/T site (ankle) moved down the foot's z axis and sole_offset_y outward.
      const int site = mj_name2id(twin.m, mjOBJ_SITE, side == 0 ? "l_ft" : "r_ft");
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(twin.d->site_xmat + 9 * site);
      const Vector3d ankle(twin.d->site_xpos + 3 * site);
      const Pose sole = sole_pose(model, data, side);
      EXPECT_LT((sole.p - (ankle - R.col(2) * model.leg[side].ankle_to_sole + R * model.leg[side].sole_shift)).norm(),
                1e-12);
      EXPECT_LT((sole.R - Matrix3d(R)).cwiseAbs().maxCoeff(), 1e-12);
      // The leg's own gravity torque against MuJoCo's: with the foot free, the pelvis held and
      // at rest, the bias force at each leg joint is the torque that holds the links below it.
      const LegTorque g = leg_gravity_torque(model, data, side);
      for (int i = 0; i < 6; ++i) {
        const int j = humanoid::leg_first_joint(side) + i;
        const int dof = twin.m->jnt_dofadr[mj_name2id(twin.m, mjOBJ_JOINT, std::string(kJointNames[j]).c_str())];
        EXPECT_NEAR(g(i), twin.d->qfrc_bias[dof], 1e-10) << kJointNames[j];
      }
    }
  }
}

TEST(RobotModel, JacobianIsTheDerivativeOfTheSolePose) {
  const RobotModel model = make_robot_model(humanoid::RobotParams{});
  RobotModelData data;
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    const Pose pelvis = random_pelvis(rng);
    JointVector q = random_pose(rng);
    for (int side = 0; side < 2; ++side) {
      forward_kinematics(model, data, pelvis, q);
      const Pose sole = sole_pose(model, data, side);
      const LegJacobian J = leg_jacobian(model, data, side, sole.p);
      const double h = 1e-6;
      for (int i = 0; i < 6; ++i) {
        const int j = humanoid::leg_first_joint(side) + i;
        JointVector qp = q, qm = q;
        qp[j] += h;
        qm[j] -= h;
        forward_kinematics(model, data, pelvis, qp);
        const Pose a = sole_pose(model, data, side);
        forward_kinematics(model, data, pelvis, qm);
        const Pose b = sole_pose(model, data, side);
        const Vector3d v = (a.p - b.p) / (2 * h);
        const Matrix3d dR = (a.R - b.R) / (2 * h) * sole.R.transpose();  // skew(ω)
        const Vector3d w(dR(2, 1), dR(0, 2), dR(1, 0));
        // Central differences: truncation ~h² ≈ 1e-12, rounding ~1e-16/h ≈ 1e-10.
        EXPECT_LT((v - J.block<3, 1>(0, i)).norm(), 1e-8);
        EXPECT_LT((w - J.block<3, 1>(3, i)).norm(), 1e-8);
      }
    }
  }
}

// Each joint turns its frame by Rot(axis, q): for the builtin's x, y and z axes the kinematics turn only the plane's
// two columns. The frames must equal the general product parent R · AngleAxis(q, axis) (the 3 × 3 product with
// AngleAxisd's matrix) in every bit (== holds ±0 equal), the joint angles exactly 0 included; and each joint's world
// axis the kinematics keep is R a, likewise in every bit.
TEST(RobotModel, CoordinateAxisJointsTurnFramesAsTheGeneralProduct) {
  const RobotModel model = make_robot_model(humanoid::RobotParams{});
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    JointVector q = random_pose(rng);
    if (trial % 2 == 1) q[humanoid::kWaistYaw] = q[2] = 0.0;  // sin 0 = 0: the structural zeros meet zeros
    const Pose pelvis = trial == 0 ? Pose{} : random_pelvis(rng);
    RobotModelData data;
    forward_kinematics(model, data, pelvis, q);
    std::array<Pose, kBodies> general;
    for (int i = 0; i < kBodies; ++i) {
      const auto& b = model.bodies[i];
      if (b.parent < 0) {
        general[i] = pelvis;
        continue;
      }
      const Pose& parent = general[b.parent];
      general[i].p = parent.p + parent.R * b.offset;
      general[i].R = b.joint >= 0 ? Matrix3d(parent.R * Eigen::AngleAxisd(q[b.joint], b.axis)) : parent.R;
    }
    for (int i = 0; i < kBodies; ++i) {
      EXPECT_EQ(data.frame[i].R, general[i].R) << "trial " << trial << " body " << i;
      EXPECT_EQ(data.frame[i].p, general[i].p) << "trial " << trial << " body " << i;
      const auto& b = model.bodies[i];
      EXPECT_EQ(data.axis[i], b.joint >= 0 ? Vector3d(general[i].R * b.axis) : Vector3d::Zero()) << i;
      EXPECT_EQ(b.axis_index >= 0, b.joint >= 0) << i;  // (the builtin's axes are all x, y or z)
    }
  }
}

}  // namespace
}  // namespace flexgait::walking
