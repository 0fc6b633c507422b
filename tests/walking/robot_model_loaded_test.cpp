// The controller's model of a loaded description (walking/robot_model_loaded.cpp, issue 16): the
// builtin's MJCF loaded back gives the builtin's own model; the model of a loaded robot agrees
// with MuJoCo's of the same twin (COM, sole poses, Jacobians, gravity torques), for the builtin
// and for the test robot with its own names and an offset hip pitch axis.
#include <gtest/gtest.h>

#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/robot_loader.hpp"
#include "flexgait/walking/robot_model.hpp"
#include "model_agreement.hpp"

namespace flexgait::humanoid {
namespace {

using testing::expect_model_agrees_with_mujoco;
using testing::small_biped_walk;
using walking::RobotModel;

LoadedRobot builtin_loaded() {
  return load_robot_text(humanoid_mjcf(RobotParams{}, PlantParams{}), "xml", "builtin.xml", RobotDescriptionParams{});
}

// The builtin's MJCF loaded back: the same controller model as the builtin's own (built from
// RobotParams by other arithmetic: link centres that MuJoCo computes from the geoms differ by
// rounding, 1e-15 m; 1e-12 leaves room).
TEST(RobotModelLoaded, BuiltinLoadedBackGivesTheSameControllerModel) {
  const RobotModel a = walking::make_robot_model(RobotParams{});
  const RobotModel b = walking::make_robot_model(builtin_loaded());
  EXPECT_NEAR(a.total_mass, b.total_mass, 1e-12);
  for (int k = 0; k < walking::kBodies; ++k) {
    const auto& x = a.bodies[static_cast<std::size_t>(k)];
    const auto& y = b.bodies[static_cast<std::size_t>(k)];
    EXPECT_EQ(x.parent, y.parent) << k;
    EXPECT_EQ(x.joint, y.joint) << k;
    EXPECT_LT((x.axis - y.axis).norm(), 1e-12) << k;
    EXPECT_LT((x.offset - y.offset).norm(), 1e-12) << k;
    EXPECT_NEAR(x.mass, y.mass, 1e-12) << k;
    EXPECT_LT((x.com - y.com).norm(), 1e-12) << k;
  }
  for (int side = 0; side < 2; ++side) {
    EXPECT_LT((a.leg[side].hip - b.leg[side].hip).norm(), 1e-12);
    EXPECT_NEAR(a.leg[side].thigh, b.leg[side].thigh, 1e-12);
    EXPECT_NEAR(a.leg[side].shank, b.leg[side].shank, 1e-12);
    EXPECT_NEAR(a.leg[side].ankle_to_sole, b.leg[side].ankle_to_sole, 1e-12);
    EXPECT_LT((a.sole_offset[side] - b.sole_offset[side]).norm(), 1e-12);
  }
  EXPECT_NEAR(a.sole_length, b.sole_length, 1e-15);
  EXPECT_NEAR(a.sole_width, b.sole_width, 1e-15);
}

TEST(RobotModelLoaded, ControllerModelAgreesWithMuJoCo) { expect_model_agrees_with_mujoco(builtin_loaded()); }

TEST(RobotModelLoaded, SecondRobotModelAgreesWithMuJoCo) {
  const experiments::WalkRunParams walk = small_biped_walk();
  ASSERT_TRUE(walk.loaded);
  const LoadedRobot& loaded = *walk.loaded;
  expect_model_agrees_with_mujoco(loaded);
  const RobotModel model = walking::make_robot_model(loaded);
  EXPECT_NEAR(model.total_mass, 34.6, 1e-12);
  for (int side = 0; side < 2; ++side) {
    EXPECT_FALSE(model.leg[side].analytic);  // the offset hip pitch axis
    EXPECT_EQ(walking::analytic_ik_mismatch(loaded, side), "the hip yaw, roll and pitch axes do not meet in a point");
  }
  EXPECT_TRUE(walking::make_robot_model(builtin_loaded()).leg[0].analytic);
}

}  // namespace
}  // namespace flexgait::humanoid
