// A robot from its description (issue 16): the builtin twin's MJCF loaded back gives the same
// controller model and a twin that compiles to the same numbers; the controller's model of a
// loaded robot against MuJoCo's own (COM, sole poses, Jacobians, gravity torques); the errors.
#include "flexgait/twin/robot_loader.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"
#include "flexgait/robot/urdf_export.hpp"
#include "flexgait/twin/twin_mjcf.hpp"
#include "flexgait/walking/robot_model.hpp"
#include "../walking/model_agreement.hpp"
#include "compiled_model.hpp"

namespace flexgait::humanoid {
namespace {

using walking::Matrix3d;
using walking::Pose;
using walking::RobotModel;
using walking::Vector3d;
using testing::Compiled;
using testing::expect_model_agrees_with_mujoco;
using testing::small_biped_walk;

LoadedRobot builtin_loaded() {
  return load_robot_text(humanoid_mjcf(RobotParams{}, PlantParams{}), "xml", "builtin.xml", RobotDescriptionParams{});
}

// The second robot walks 10 steps at 1 s/step with and without compensation (numeric leg IK).
TEST(RobotLoader, SecondRobotWalks) {
  for (const auto mode : {compensation::CompensationMode::kBoth, compensation::CompensationMode::kOff}) {
    experiments::WalkRunParams walk = small_biped_walk();
    walk.control.mode = mode;
    const experiments::WalkResult r = experiments::run_walk(walk);
    EXPECT_TRUE(r.metrics.completed()) << r.metrics.fall_text() << r.metrics.failure_text();
    EXPECT_EQ(r.metrics.steps_completed, 10);
    EXPECT_EQ(r.metrics.ik_clamped, 0);
    EXPECT_EQ(r.metrics.mujoco_warnings, 0);
  }
}

// A robot without a waist (robot.joints.waist_yaw: none): its trunk is rigid in the twin (no waist
// joint, no drive) and in the controller's model (the chest joint −1 carrying the trunk's mass),
// which still agrees with MuJoCo's to 1e-10; it walks.
TEST(RobotLoader, RobotWithoutAWaistHasARigidTrunk) {
  const char* dir = std::getenv("FLEXGAIT_TEST_DATA");
  const std::filesystem::path file = std::filesystem::path(dir ? dir : "tests/humanoid/data") / "small_biped.yaml";
  experiments::WalkRunParams walk = experiments::walk_run_from_config(
      resolve_config(experiments::walk_run_schema(), file, {"robot.joints.waist_yaw=none", "walk.steps=4"}));
  ASSERT_TRUE(walk.loaded);
  EXPECT_FALSE(walk.loaded->has_joint(kWaistYaw));
  const std::string twin = twin_mjcf(*walk.loaded, walk.robot, walk.plant);
  EXPECT_EQ(twin.find("waist_yaw"), std::string::npos);
  expect_model_agrees_with_mujoco(*walk.loaded);
  const RobotModel model = walking::make_robot_model(*walk.loaded);
  EXPECT_EQ(model.bodies[1].joint, -1);
  EXPECT_NEAR(model.total_mass, 34.6, 1e-12);
  EXPECT_NE(urdf_mapping(*walk.loaded).find("robot.joints.waist_yaw=none"), std::string::npos);
  const experiments::WalkResult r = experiments::run_walk(walk);
  EXPECT_TRUE(r.metrics.completed()) << r.metrics.fall_text() << r.metrics.failure_text();
  EXPECT_EQ(r.metrics.steps_completed, 4);
  EXPECT_EQ(r.metrics.mujoco_warnings, 0);
}

std::string error_key(const std::string& text, const RobotDescriptionParams& params) {
  try {
    load_robot_text(text, "xml", "test.xml", params);
  } catch (const ConfigError& e) {
    return e.key() + " | " + e.what();
  }
  return "no error";
}

TEST(RobotLoader, ErrorsNameTheKeyAndTheName) {
  const std::string xml = humanoid_mjcf(RobotParams{}, PlantParams{});
  RobotDescriptionParams p;
  p.description = "/no/such/robot.xml";
  try {
    load_robot(p);
    ADD_FAILURE() << "a missing file loaded";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "robot.description");
    EXPECT_NE(std::string(e.what()).find("/no/such/robot.xml"), std::string::npos);
  }
  EXPECT_NE(error_key("<mujoco><worldbody><body></mujoco>", {}).find("robot.description | "), std::string::npos);
  EXPECT_NE(error_key("<mujoco><worldbody><body></mujoco>", {}).find("MuJoCo"), std::string::npos);
  p = {};
  p.joints[kLeftKnee] = "left_knee_joint";
  const std::string missing = error_key(xml, p);
  EXPECT_EQ(missing.rfind("robot.joints.l_knee | ", 0), 0u) << missing;
  EXPECT_NE(missing.find("left_knee_joint"), std::string::npos);
  p = {};
  p.feet[0].body = "l_ankle_pitch_link";  // five joints from the root to it
  EXPECT_EQ(error_key(xml, p).rfind("robot.feet.left.body | ", 0), 0u) << error_key(xml, p);
  EXPECT_NE(error_key(xml, p).find("5 joints"), std::string::npos);
  p = {};
  p.feet[1].sole_geom = "none";
  EXPECT_EQ(error_key(xml, p).rfind("robot.feet.right.sole_geom | ", 0), 0u) << error_key(xml, p);
  p = {};
  p.feet[1].sole_geom = "l_sole";
  EXPECT_EQ(error_key(xml, p).rfind("robot.feet.right.sole_geom | ", 0), 0u) << error_key(xml, p);
  p = {};
  p.imu_body = "nose";
  EXPECT_EQ(error_key(xml, p).rfind("robot.imu_body | ", 0), 0u);
  p = {};
  p.exclude_contacts = "pelvis-chest";
  EXPECT_EQ(error_key(xml, p).rfind("robot.exclude_contacts | ", 0), 0u);
}

// Colliding geoms that touch at zero angles are refused, naming the pair; excluding it loads.
TEST(RobotLoader, SelfContactAtZeroAnglesIsReportedAndCanBeExcluded) {
  std::string xml = humanoid_mjcf(RobotParams{}, PlantParams{});
  // A deeper pelvis box that reaches into the hip roll links (grandchildren: MuJoCo does not
  // exclude them), all three colliding.
  const std::string pelvis = R"(<geom type="box" size="0.09 0.14 0.05")";
  xml.replace(xml.find(pelvis), pelvis.size(), R"(<geom contype="1" conaffinity="1" type="box" size="0.09 0.14 0.1")");
  const std::string roll = R"(<geom type="box" size="0.05 0.04 0.035")";
  for (std::size_t at = xml.find(roll); at != std::string::npos; at = xml.find(roll, at + 1))
    xml.insert(at + 5, R"( contype="1" conaffinity="1")");
  const std::string what = error_key(xml, {});
  EXPECT_EQ(what.rfind("robot.exclude_contacts | ", 0), 0u) << what;
  EXPECT_NE(what.find("pelvis:l_hip_roll_link"), std::string::npos) << what;
  RobotDescriptionParams p;
  p.exclude_contacts = "pelvis:l_hip_roll_link,pelvis:r_hip_roll_link";
  EXPECT_EQ(error_key(xml, p), "no error");
}

// A sole given by its size and centre instead of a geom: the same sole.
TEST(RobotLoader, SoleBySizeAndCentre) {
  RobotDescriptionParams p;
  for (auto& f : p.feet) {
    f.sole_geom = "none";
    f.sole_size = "0.22 0.15";
    f.sole_center = "0 0 -0.1145";
  }
  const LoadedRobot r = load_robot_text(humanoid_mjcf(RobotParams{}, PlantParams{}), "xml", "b.xml", p);
  for (int side = 0; side < 2; ++side) {
    EXPECT_EQ(r.sole[side].geom, -1);
    EXPECT_EQ(r.sole[side].length, 0.22);
    EXPECT_NEAR(r.sole[side].center[2], builtin_loaded().sole[side].center[2], 1e-15);
  }
  const Compiled twin(twin_mjcf(r, RobotParams{}, PlantParams{}));
  EXPECT_GE(mj_name2id(twin.m, mjOBJ_GEOM, "l_sole"), 0);
  // Soles that differ are refused by the controller's model, naming the right foot.
  p.feet[1].sole_size = "0.22 0.16";
  try {
    (void)walking::make_robot_model(load_robot_text(humanoid_mjcf(RobotParams{}, PlantParams{}), "xml", "b.xml", p));
    ADD_FAILURE() << "different soles accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "robot.feet.right.body");
    EXPECT_NE(std::string(e.what()).find("0.22 x 0.16 m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace flexgait::humanoid
