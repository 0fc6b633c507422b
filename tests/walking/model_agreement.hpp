#pragma once
// The controller's model of a loaded robot against MuJoCo's own model of the same twin, and the
// test robot tests/humanoid/data/small_biped.yaml's walk: shared by the tests of the loader
// (tests/twin/robot_loader_test.cpp) and of the controller's model of a loaded robot
// (tests/walking/robot_model_loaded_test.cpp).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "../twin/compiled_model.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/twin/twin_mjcf.hpp"
#include "flexgait/walking/robot_model.hpp"

namespace flexgait::humanoid::testing {

using walking::Matrix3d;
using walking::Pose;
using walking::RobotModel;
using walking::Vector3d;

// The controller's model of a loaded robot against MuJoCo's own model of the same twin: COM,
// sole poses, leg Jacobians (mj_jac at the sole centre) and the legs' gravity torques (qfrc_bias
// at rest). Both are exact rigid-body kinematics up to rounding: 1e-10.
inline void expect_model_agrees_with_mujoco(const LoadedRobot& loaded) {
  const RobotModel model = walking::make_robot_model(loaded);
  walking::RobotModelData data;
  twin::testing::Compiled twin(twin::twin_mjcf(loaded, RobotParams{}, twin::PlantParams{}));
  EXPECT_NEAR(model.total_mass, twin.m->body_subtreemass[0], 1e-10);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> a(-0.5, 0.5), small(-0.3, 0.3);
  std::vector<mjtNum> jacp(static_cast<std::size_t>(3 * twin.m->nv)), jacr(static_cast<std::size_t>(3 * twin.m->nv));
  for (int trial = 0; trial < 30; ++trial) {
    const Pose pelvis{Vector3d(small(rng), small(rng), 0.8 + small(rng)),
                      walking::rpy_to_matrix(small(rng), small(rng), small(rng))};
    JointVector q;
    for (auto& v : q) v = a(rng);
    walking::forward_kinematics(model, data, pelvis, q);
    twin.set(pelvis, q);
    const Vector3d com = walking::center_of_mass(model, data);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(com(i), twin.d->subtree_com[3 + i], 1e-10);
    for (int side = 0; side < 2; ++side) {
      const int geom = mj_name2id(twin.m, mjOBJ_GEOM, side == 0 ? "l_sole" : "r_sole");
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(twin.d->geom_xmat + 9 * geom);
      const Vector3d bottom = Vector3d(twin.d->geom_xpos + 3 * geom) - R.col(2) * twin.m->geom_size[3 * geom + 2];
      const Pose sole = walking::sole_pose(model, data, side);
      EXPECT_LT((sole.p - bottom).norm(), 1e-10);
      EXPECT_LT((sole.R - Matrix3d(R)).cwiseAbs().maxCoeff(), 1e-10);
      const walking::LegJacobian J = walking::leg_jacobian(model, data, side, sole.p);
      mj_jac(twin.m, twin.d, jacp.data(), jacr.data(), sole.p.data(), twin.m->geom_bodyid[geom]);
      const walking::LegTorque g = walking::leg_gravity_torque(model, data, side);
      for (int i = 0; i < kLegJoints; ++i) {
        const int dof = twin.dof(leg_first_joint(side) + i);
        for (int r = 0; r < 3; ++r) {
          EXPECT_NEAR(J(r, i), jacp[static_cast<std::size_t>(r * twin.m->nv + dof)], 1e-10);
          EXPECT_NEAR(J(3 + r, i), jacr[static_cast<std::size_t>(r * twin.m->nv + dof)], 1e-10);
        }
        EXPECT_NEAR(g(i), twin.d->qfrc_bias[dof], 1e-10);
      }
    }
  }
}

/// The walk of a fixture robot of tests/humanoid/data (its YAML mapping, with these overrides).
inline experiments::WalkRunParams fixture_walk(const std::string& yaml,
                                               const std::vector<std::string>& overrides = {}) {
  const char* dir = std::getenv("FLEXGAIT_TEST_DATA");
  const std::filesystem::path file = std::filesystem::path(dir ? dir : "tests/humanoid/data") / yaml;
  return experiments::walk_run_from_config(resolve_config(experiments::walk_run_schema(), file, overrides));
}

/// The second robot's walk (tests/humanoid/data/small_biped.yaml: the robot small_biped.xml with
/// its own names and an offset hip pitch axis, 10 steps at 1 s/step); its description path is
/// relative to the YAML file.
inline experiments::WalkRunParams small_biped_walk() {
  return fixture_walk("small_biped.yaml");
}

}  // namespace flexgait::humanoid::testing
