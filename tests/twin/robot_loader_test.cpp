// A robot from its description: the builtin twin's MJCF loaded back gives the same
// controller model and a twin that compiles to the same numbers; the controller's model of a
// loaded robot against MuJoCo's own (COM, sole poses, Jacobians, gravity torques); the errors.
#include "flexgait/twin/robot_loader.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../walking/model_agreement.hpp"
#include "compiled_model.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/robot/urdf_export.hpp"
#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/twin_mjcf.hpp"
#include "flexgait/walking/robot_model.hpp"
#include "flexgait/walking/stance_defaults.hpp"

namespace flexgait::twin {
namespace {

using humanoid::testing::expect_model_agrees_with_mujoco;
using humanoid::testing::small_biped_walk;
using testing::Compiled;
using walking::Matrix3d;
using walking::Pose;
using walking::RobotModel;
using walking::Vector3d;

humanoid::LoadedRobot builtin_loaded() {
  return load_robot_text(humanoid_mjcf(humanoid::RobotParams{}, PlantParams{}), "xml", "builtin.xml",
                         humanoid::RobotDescriptionParams{});
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
  EXPECT_FALSE(walk.loaded->has_joint(humanoid::kWaistYaw));
  const std::string twin = twin_mjcf(*walk.loaded, walk.robot, walk.plant);
  EXPECT_EQ(twin.find("waist_yaw"), std::string::npos);
  expect_model_agrees_with_mujoco(*walk.loaded);
  const RobotModel model = walking::make_robot_model(*walk.loaded);
  EXPECT_EQ(model.bodies[1].joint, -1);
  EXPECT_NEAR(model.total_mass, 34.6, 1e-12);
  EXPECT_NE(humanoid::urdf_mapping(*walk.loaded).find("robot.joints.waist_yaw=none"), std::string::npos);
  const experiments::WalkResult r = experiments::run_walk(walk);
  EXPECT_TRUE(r.metrics.completed()) << r.metrics.fall_text() << r.metrics.failure_text();
  EXPECT_EQ(r.metrics.steps_completed, 4);
  EXPECT_EQ(r.metrics.mujoco_warnings, 0);
}

std::string error_key(const std::string& text, const humanoid::RobotDescriptionParams& params) {
  try {
    load_robot_text(text, "xml", "test.xml", params);
  } catch (const ConfigError& e) {
    return e.key() + " | " + e.what();
  }
  return "no error";
}

TEST(RobotLoader, ErrorsNameTheKeyAndTheName) {
  const std::string xml = humanoid_mjcf(humanoid::RobotParams{}, PlantParams{});
  humanoid::RobotDescriptionParams p;
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
  p.joints[humanoid::kLeftKnee] = "left_knee_joint";
  const std::string missing = error_key(xml, p);
  EXPECT_EQ(missing.rfind("robot.joints.l_knee | ", 0), 0u) << missing;
  EXPECT_NE(missing.find("left_knee_joint"), std::string::npos);
  p = {};
  p.feet[0].body = "l_ankle_pitch_link";  // five joints from the root to it
  EXPECT_EQ(error_key(xml, p).rfind("robot.feet.left.body | ", 0), 0u) << error_key(xml, p);
  EXPECT_NE(error_key(xml, p).find("5 joints"), std::string::npos);
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

// The file's gravity is the robot's: the twin and the controller's model both take it (the model's
// leg gravity torques equal MuJoCo's qfrc_bias under it to 1e-10: a model left at 9.81 is off by
// 2.6 times too large here). Gravity that does not point straight down is refused, naming the file.
TEST(RobotLoader, TheFilesGravityReachesTheTwinAndTheModel) {
  const std::string xml = humanoid_mjcf(humanoid::RobotParams{}, PlantParams{});
  const std::string earth = "gravity=\"0 0 -9.81\"";
  ASSERT_NE(xml.find(earth), std::string::npos);
  std::string mars = xml;
  mars.replace(mars.find(earth), earth.size(), "gravity=\"0 0 -3.72\"");
  const humanoid::LoadedRobot loaded = load_robot_text(mars, "xml", "mars.xml", {});
  EXPECT_EQ(loaded.gravity, 3.72);
  EXPECT_EQ(walking::make_robot_model(loaded).gravity, 3.72);
  EXPECT_NE(twin_mjcf(loaded, humanoid::RobotParams{}, PlantParams{}).find("gravity=\"0 0 -3.72\""), std::string::npos);
  expect_model_agrees_with_mujoco(loaded);
  EXPECT_EQ(load_robot_text(xml, "xml", "earth.xml", {}).gravity, humanoid::kDefaultGravity);
  std::string tilted = xml;
  tilted.replace(tilted.find(earth), earth.size(), "gravity=\"0.5 0 -9.81\"");
  const std::string error = error_key(tilted, {});
  EXPECT_EQ(error.rfind("robot.description | ", 0), 0u) << error;
  EXPECT_NE(error.find("straight down"), std::string::npos) << error;
}

// Colliding geoms that touch at zero angles are refused, naming the pair; excluding it loads.
TEST(RobotLoader, SelfContactAtZeroAnglesIsReportedAndCanBeExcluded) {
  std::string xml = humanoid_mjcf(humanoid::RobotParams{}, PlantParams{});
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
  humanoid::RobotDescriptionParams p;
  p.exclude_contacts = "pelvis:l_hip_roll_link,pelvis:r_hip_roll_link";
  EXPECT_EQ(error_key(xml, p), "no error");
  // The file's own <contact><exclude> counts as the key's: one pair in the file, the other by key.
  const std::string own = R"(<contact><exclude body1="pelvis" body2="l_hip_roll_link"/></contact>)";
  std::string with_exclude = xml;
  with_exclude.insert(with_exclude.rfind("</mujoco>"), own);
  p.exclude_contacts = "pelvis:r_hip_roll_link";
  EXPECT_EQ(error_key(with_exclude, p), "no error");
  EXPECT_EQ(load_robot_text(with_exclude, "xml", "x.xml", p).exclude.size(), 2u);
}

// A loaded robot has no builtin names as defaults: every unmapped leg role is listed; an unmapped
// waist is a rigid trunk.
TEST(RobotLoader, UnmappedRolesAreListed) {
  const char* dir = std::getenv("FLEXGAIT_TEST_DATA");
  const std::filesystem::path file = std::filesystem::path(dir ? dir : "tests/humanoid/data") / "small_biped.xml";
  std::ifstream in(file);
  const std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  humanoid::RobotDescriptionParams p;
  p.feet = {humanoid::FootMapping{"LFoot", "LSole"}, humanoid::FootMapping{"RFoot", "RSole"}};
  const std::string what = error_key(xml, p);
  EXPECT_EQ(what.rfind("robot.joints.l_hip_yaw | ", 0), 0u) << what;
  EXPECT_NE(what.find("unmapped: l_hip_yaw, l_hip_roll, l_hip_pitch, l_knee, l_ankle_pitch, l_ankle_roll, r_hip_yaw, "
                      "r_hip_roll, r_hip_pitch, r_knee, r_ankle_pitch, r_ankle_roll)"),
            std::string::npos)
      << what;
  const std::array<const char*, 12> names = {"LHipYaw", "LHipRoll", "LHipPitch", "LKnee", "LAnklePitch", "LAnkleRoll",
                                             "RHipYaw", "RHipRoll", "RHipPitch", "RKnee", "RAnklePitch", "RAnkleRoll"};
  for (int i = 0; i < 12; ++i)
    p.joints[static_cast<std::size_t>(humanoid::kLeftHipYaw + i)] = names[static_cast<std::size_t>(i)];
  p.joints[humanoid::kLeftKnee] = "l_knee";  // one role left at its builtin name
  EXPECT_NE(error_key(xml, p).find("(unmapped: l_knee)"), std::string::npos) << error_key(xml, p);
  p.joints[humanoid::kLeftKnee] = "LKnee";
  const humanoid::LoadedRobot r = load_robot_text(xml, "xml", "small_biped.xml", p);  // the waist left unmapped: rigid
  EXPECT_FALSE(r.has_joint(humanoid::kWaistYaw));
}

// MJCF written for MuJoCo 3: translated with one warning per attribute, the knees' ranges limit
// them (autolimits), their actuatorfrcrange is their torque limit, the model agrees with MuJoCo's.
TEST(RobotLoader, MuJoCo3AttributesAreTranslated) {
  const experiments::WalkRunParams walk = humanoid::testing::fixture_walk("mujoco3_attributes.yaml");
  ASSERT_TRUE(walk.loaded);
  const std::vector<std::string> expected = {
      "line 33: actuatorfrcrange read as the joint's torque limit (MuJoCo 3: the clamp of the actuators' force at the "
      "joint) (2 times)",
      "line 9: ellipsoidinertia dropped (MuJoCo 3; the twin drives the joints and draws the robot itself)",
      "line 80: inheritrange dropped (MuJoCo 3; the twin drives the joints and draws the robot itself)",
      "line 7: integrator=implicitfast taken as \"implicit\" (MuJoCo 2.2.2 has no implicitfast; the twin sets its own "
      "integrator)",
      "line 80: kv dropped (MuJoCo 3; the twin drives the joints and draws the robot itself)"};
  EXPECT_EQ(walk.loaded->warnings, expected);
  const auto [body, k] = walk.loaded->joint[humanoid::kLeftKnee];
  const humanoid::LoadedJoint& knee =
      walk.loaded->bodies[static_cast<std::size_t>(body)].joints[static_cast<std::size_t>(k)];
  EXPECT_TRUE(knee.limited);
  EXPECT_EQ(knee.range[1], 2.4);
  // The knees' actuatorfrcrange="-60 60" is their torque limit (their position servo has no force range of its own);
  // the other joints have none.
  EXPECT_EQ(knee.force_limit, 60.0);
  const auto [hb, hk] = walk.loaded->joint[humanoid::kLeftHipPitch];
  EXPECT_EQ(walk.loaded->bodies[static_cast<std::size_t>(hb)].joints[static_cast<std::size_t>(hk)].force_limit, 0.0);
  EXPECT_EQ(walk.plant.joint_torque_limit[humanoid::kRightKnee], 60.0);
  expect_model_agrees_with_mujoco(*walk.loaded);
}

// Mesh files that are not there (published robots without their assets): the meshes and the geoms
// showing them are dropped with one warning; the robot loads on its inertials.
TEST(RobotLoader, MissingMeshFilesAreDropped) {
  const char* dir = std::getenv("FLEXGAIT_TEST_DATA");
  const std::filesystem::path file = std::filesystem::path(dir ? dir : "tests/humanoid/data") / "small_biped.xml";
  std::ifstream in(file);
  std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  xml.insert(xml.find("<worldbody>"),
             R"(<asset><mesh file="no_such_shell.stl"/><mesh name="hull" file="no/such/hull.stl"/></asset>)");
  const std::string base = R"(<geom type="box" size="0.08 0.1 0.05" mass="8"/>)";
  xml.insert(xml.find(base) + base.size(), R"(<geom mesh="no_such_shell" contype="0"/><geom mesh="hull"/>)");
  humanoid::RobotDescriptionParams p = humanoid::testing::fixture_walk("small_biped.yaml").description;
  const humanoid::LoadedRobot r = load_robot_text(xml, "xml", "small_biped.xml", p);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find(
                "2 mesh files not found (first: no_such_shell); they and the 2 geoms showing them are dropped"),
            std::string::npos)
      << r.warnings[0];
  EXPECT_EQ(r.bodies[0].geoms.size(), 1u);
  EXPECT_NEAR(r.bodies[0].mass, 8.0, 1e-12);
}

// A waist hinge between the root and the legs: unmapped, held rigid (the twin has no such joint,
// the model agrees with MuJoCo's); mapped as the waist, refused naming robot.joints.waist_yaw.
TEST(RobotLoader, WaistBelowTheRootIsRigidUnlessMapped) {
  const experiments::WalkRunParams walk = humanoid::testing::fixture_walk("waist_below_root.yaml");
  ASSERT_TRUE(walk.loaded);
  EXPECT_EQ(twin_mjcf(*walk.loaded, walk.robot, walk.plant).find("WaistPitch"), std::string::npos);
  expect_model_agrees_with_mujoco(*walk.loaded);
  try {
    (void)humanoid::testing::fixture_walk("waist_below_root.yaml", {"robot.joints.waist_yaw=WaistPitch"});
    ADD_FAILURE() << "a mapped waist below the root accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "robot.joints.waist_yaw");
    EXPECT_NE(std::string(e.what()).find("between the root and the leg to LFoot"), std::string::npos) << e.what();
  }
}

// Quaternions printed to 6 digits: the feet tilted by a few 1e-6 rad are accepted and their tilt
// modelled (the sole poses agree with MuJoCo's to 1e-10); so is a foot turned further whose sole
// keeps the body's axes (the loader gives a turned foot's sole a frame of its own: TurnedFootFrames).
TEST(RobotLoader, PrintedQuaternionsAreModelled) {
  const experiments::WalkRunParams walk = humanoid::testing::fixture_walk("printed_quaternions.yaml");
  ASSERT_TRUE(walk.loaded);
  const RobotModel model = walking::make_robot_model(*walk.loaded);
  EXPECT_TRUE(model.sole_tilted[0]);
  EXPECT_TRUE(model.sole_tilted[1]);
  expect_model_agrees_with_mujoco(*walk.loaded);
  humanoid::LoadedRobot tilted = *walk.loaded;
  tilted.bodies[static_cast<std::size_t>(tilted.foot[1])].quat = {std::cos(0.0006), 0, std::sin(0.0006),
                                                                  0};  // 1.2e-3 rad about y
  const RobotModel turned = walking::make_robot_model(tilted);
  EXPECT_TRUE(turned.sole_tilted[1]);
  EXPECT_NEAR(turned.sole_rotation[1](0, 2), std::sin(0.0012), 1e-12);  // the foot's turn (its parent's 1e-6 rad)
}

// A sole given by its size and centre instead of a geom: the same sole.
TEST(RobotLoader, SoleBySizeAndCentre) {
  humanoid::RobotDescriptionParams p;
  for (auto& f : p.feet) {
    f.sole_geom = "none";
    f.sole_size = "0.22 0.15";
    f.sole_center = "0 0 -0.1145";
  }
  const humanoid::LoadedRobot r =
      load_robot_text(humanoid_mjcf(humanoid::RobotParams{}, PlantParams{}), "xml", "b.xml", p);
  for (int side = 0; side < 2; ++side) {
    EXPECT_EQ(r.sole[side].geom, -1);
    EXPECT_EQ(r.sole[side].length, 0.22);
    EXPECT_NEAR(r.sole[side].center[2], builtin_loaded().sole[side].center[2], 1e-15);
  }
  const Compiled twin(twin_mjcf(r, humanoid::RobotParams{}, PlantParams{}));
  EXPECT_GE(mj_name2id(twin.m, mjOBJ_GEOM, "l_sole"), 0);
  // Soles that differ are refused by the controller's model, naming the right foot.
  p.feet[1].sole_size = "0.22 0.16";
  try {
    (void)walking::make_robot_model(
        load_robot_text(humanoid_mjcf(humanoid::RobotParams{}, PlantParams{}), "xml", "b.xml", p));
    ADD_FAILURE() << "different soles accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "robot.feet.right.body");
    EXPECT_NE(std::string(e.what()).find("0.22 x 0.16 m"), std::string::npos) << e.what();
  }
}

std::string small_biped_xml() {
  const char* dir = std::getenv("FLEXGAIT_TEST_DATA");
  std::ifstream in(std::filesystem::path(dir ? dir : "tests/humanoid/data") / "small_biped.xml");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// No sole named or sized: the sole from the foot's contact geoms. The builtin's one box: its bottom
// face, the very rectangle sole_geom gives (to rounding, 1e-15 m), the box then the sole's own
// geom in the twin with a plate that only marks it. A foot with no contact geom at all (small_biped's
// geoms collide with nothing): refused naming sole_size and the foot.
TEST(RobotLoader, SoleFromTheFootsContactGeoms) {
  humanoid::RobotDescriptionParams p;
  p.feet[0].sole_geom = p.feet[1].sole_geom = "none";
  const humanoid::LoadedRobot r =
      load_robot_text(humanoid_mjcf(humanoid::RobotParams{}, PlantParams{}), "xml", "b.xml", p);
  const humanoid::LoadedRobot named = builtin_loaded();
  for (int side = 0; side < 2; ++side) {
    EXPECT_EQ(r.sole[side].geom, -1);
    EXPECT_EQ(r.sole[side].hull.size(), 4u);
    EXPECT_EQ(r.sole[side].hull_geoms, std::vector<int>{named.sole[side].geom});
    EXPECT_NEAR(r.sole[side].length, named.sole[side].length, 1e-15);
    EXPECT_NEAR(r.sole[side].width, named.sole[side].width, 1e-15);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.sole[side].center[i], named.sole[side].center[i], 1e-15);
  }
  const Compiled twin(twin_mjcf(r, humanoid::RobotParams{}, PlantParams{}));
  const int plate = mj_name2id(twin.m, mjOBJ_GEOM, "l_sole");
  ASSERT_GE(plate, 0);
  EXPECT_EQ(twin.m->geom_contype[plate], 0);
  humanoid::RobotDescriptionParams biped = humanoid::testing::fixture_walk("small_biped.yaml").description;
  biped.feet[0].sole_geom = "none";
  const std::string e = error_key(small_biped_xml(), biped);
  EXPECT_EQ(e.rfind("robot.feet.left.sole_size | ", 0), 0u) << e;
  EXPECT_NE(e.find("the foot LFoot has no contact geom"), std::string::npos) << e;
}

// A foot whose collision mesh file is missing: refused naming the mesh and the geom (its class makes
// it collide) unless the mapping gives the sole; then the mesh is dropped with the warning, as a
// missing visual mesh always is.
TEST(RobotLoader, MissingFootCollisionMeshIsAnErrorUnlessTheSoleIsMapped) {
  std::string xml = small_biped_xml();
  const std::string defaults = R"(<geom contype="0" conaffinity="0"/>)";
  xml.insert(xml.find(defaults) + defaults.size(),
             R"(<default class="collision"><geom type="mesh" contype="1" conaffinity="1"/></default>)");
  xml.insert(
      xml.find("<worldbody>"),
      R"(<asset><mesh name="shell" file="no_such_shell.stl"/><mesh name="foot" file="no_such_foot.stl"/></asset>)");
  const std::string base = R"(<geom type="box" size="0.08 0.1 0.05" mass="8"/>)";
  xml.insert(xml.find(base) + base.size(), R"(<geom mesh="shell"/>)");
  const std::string sole = R"(<geom name="LSole" type="box" pos="0 0 -0.05" size="0.09 0.05 0.01" mass="1.0"/>)";
  xml.insert(xml.find(sole) + sole.size(), R"(<geom name="LFootCollision" class="collision" mesh="foot"/>)");
  humanoid::RobotDescriptionParams p = humanoid::testing::fixture_walk("small_biped.yaml").description;
  const humanoid::LoadedRobot mapped = load_robot_text(xml, "xml", "small_biped.xml", p);
  ASSERT_EQ(mapped.warnings.size(), 1u);
  EXPECT_NE(mapped.warnings[0].find("2 mesh files not found"), std::string::npos) << mapped.warnings[0];
  p.feet[0].sole_geom = "none";
  const std::string e = error_key(xml, p);
  EXPECT_EQ(e.rfind("robot.feet.left.sole_size | ", 0), 0u) << e;
  EXPECT_NE(e.find("the file of mesh 'foot', which the contact geom 'LFootCollision' of the foot LFoot shows, is "
                   "missing"),
            std::string::npos)
      << e;
  p.feet[0].sole_size = "0.18 0.1";
  p.feet[0].sole_center = "0 0 -0.06";
  EXPECT_EQ(load_robot_text(xml, "xml", "small_biped.xml", p).sole[0].length, 0.18);
}

// Export as MJCF, load back with the mapping written beside it, export again: the same bytes, and
// the loaded numbers (masses, inertias, frames, joints, soles) equal to the bit.
TEST(RobotLoader, ExportedMjcfLoadsBackExactly) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("flexgait_reload_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  for (const char* yaml :
       {"four_sphere_feet.yaml", "printed_quaternions.yaml", "massless_foot.yaml", "pitch_roll_yaw_hips.yaml"}) {
    const experiments::WalkRunParams a = humanoid::testing::fixture_walk(yaml);
    ASSERT_TRUE(a.loaded);
    const std::string first = twin_mjcf(*a.loaded, a.robot, a.plant);
    const std::filesystem::path file = dir / (std::string(yaml) + ".xml");
    std::ofstream(file) << first;
    std::vector<std::string> overrides{"robot.description=" + file.string()};
    std::istringstream mapping(twin_mjcf_mapping(*a.loaded));
    for (std::string line; std::getline(mapping, line);) overrides.push_back(line);
    const experiments::WalkRunParams b =
        experiments::walk_run_from_config(resolve_config(experiments::walk_run_schema(), std::nullopt, overrides));
    ASSERT_TRUE(b.loaded);
    EXPECT_EQ(twin_mjcf(*b.loaded, a.robot, a.plant), first) << yaml;
    ASSERT_EQ(a.loaded->bodies.size(), b.loaded->bodies.size());
    // (the root's pose is the twin's own; a massless body's inertial frame is no number of the robot)
    for (std::size_t i = 0; i < a.loaded->bodies.size(); ++i) {
      const humanoid::LoadedBody &x = a.loaded->bodies[i], &y = b.loaded->bodies[i];
      EXPECT_EQ(x.mass, y.mass) << yaml << " " << x.name;
      if (x.mass > 0) {
        EXPECT_EQ(x.inertia, y.inertia) << yaml << " " << x.name;
        EXPECT_EQ(x.ipos, y.ipos) << yaml << " " << x.name;
        EXPECT_EQ(x.iquat, y.iquat) << yaml << " " << x.name;
      }
      if (i > 0) {
        EXPECT_EQ(x.pos, y.pos) << yaml << " " << x.name;
        EXPECT_EQ(x.quat, y.quat) << yaml << " " << x.name;
      }
      ASSERT_EQ(x.joints.size(), y.joints.size()) << yaml << " " << x.name;
      for (std::size_t j = 0; j < x.joints.size(); ++j) {
        EXPECT_EQ(x.joints[j].pos, y.joints[j].pos) << yaml << " " << x.name;
        EXPECT_EQ(x.joints[j].axis, y.joints[j].axis) << yaml << " " << x.name;
      }
    }
    for (int side = 0; side < 2; ++side) {
      EXPECT_EQ(a.loaded->sole[side].center, b.loaded->sole[side].center) << yaml;
      EXPECT_EQ(a.loaded->sole[side].length, b.loaded->sole[side].length) << yaml;
      EXPECT_EQ(a.loaded->sole[side].width, b.loaded->sole[side].width) << yaml;
    }
  }
  std::filesystem::remove_all(dir);
}

// URDF keeps the joints' damping and friction (<dynamics>) and armature (flexgait's extension of
// <dynamics>, read back by the loader, passed over by MuJoCo's URDF reader); a negative armature is
// refused naming the line.
TEST(RobotLoader, UrdfKeepsJointDynamics) {
  std::string xml = small_biped_xml();
  const std::string knee = R"(<joint name="LKnee" axis="0 1 0")";
  xml.insert(xml.find(knee) + knee.size(), R"( damping="0.25" frictionloss="0.5" armature="0.0625")");
  const humanoid::RobotDescriptionParams p = humanoid::testing::fixture_walk("small_biped.yaml").description;
  const humanoid::LoadedRobot a = load_robot_text(xml, "xml", "small_biped.xml", p);
  const std::string urdf = humanoid::robot_urdf(a);
  EXPECT_NE(urdf.find(R"(<dynamics damping="0.25" friction="0.5" armature="0.0625"/>)"), std::string::npos) << urdf;
  humanoid::RobotDescriptionParams q;
  std::istringstream mapping(humanoid::urdf_mapping(a));
  for (std::string line; std::getline(mapping, line);) {
    const auto eq = line.find('=');
    const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    for (int j = 0; j < humanoid::kJoints; ++j)
      if (key == "robot.joints." + std::string(humanoid::kJointNames[j])) q.joints[j] = value;
    for (int side = 0; side < 2; ++side) {
      const std::string f = std::string("robot.feet.") + (side == 0 ? "left" : "right");
      humanoid::FootMapping& m = q.feet[side];
      if (key == f + ".body") m.body = value;
      if (key == f + ".sole_geom") m.sole_geom = value;
      if (key == f + ".sole_size") m.sole_size = value;
      if (key == f + ".sole_center") m.sole_center = value;
    }
  }
  const humanoid::LoadedRobot b = load_robot_text(urdf, "urdf", "robot.urdf", q);
  const auto [body, k] = b.joint[humanoid::kLeftKnee];
  const humanoid::LoadedJoint& j = b.bodies[static_cast<std::size_t>(body)].joints[static_cast<std::size_t>(k)];
  EXPECT_EQ(j.damping, 0.25);
  EXPECT_EQ(j.frictionloss, 0.5);
  EXPECT_EQ(j.armature, 0.0625);
  std::string negative = urdf;
  negative.replace(negative.find(R"(armature="0.0625")"), 17, R"(armature="-1")");
  try {
    (void)load_robot_text(negative, "urdf", "robot.urdf", q);
    ADD_FAILURE() << "a negative armature accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(R"(<dynamics armature="-1">: allowed: a number >= 0 kg m^2)"),
              std::string::npos)
        << e.what();
  }
}

// A sole made of contact geoms URDF has no primitive for: four_sphere_feet with the two front spheres
// replaced by a capsule across the toe (its ends at y = ±30 mm) and one rear sphere by an ellipsoid
// (semi-axes 20, 10, 10 mm, its lowest point where the sphere's was). The URDF export writes the
// capsule as the spheres at its ends and the ellipsoid as the sphere of its smallest semi-axis through
// its lowest point, each a <collision> of the foot, and the mapping names no sole: the reload makes the
// same trapezoid hull on the same plane (1e-12 m: the end points are computed, then written as shortest
// round-trip decimals).
TEST(RobotLoader, UrdfExportKeepsAHullSoleOfCapsulesAndEllipsoids) {
  const char* dir = std::getenv("FLEXGAIT_TEST_DATA");
  std::ifstream in(std::filesystem::path(dir ? dir : "tests/humanoid/data") / "four_sphere_feet.xml");
  std::string xml{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  for (const std::string side : {"L", "R"}) {
    auto replace = [&](const std::string& from, const std::string& to) {
      const auto at = xml.find(from);
      ASSERT_NE(at, std::string::npos) << from;
      xml.replace(at, from.size(), to);
    };
    const std::string tail = R"( contype="1" conaffinity="1"/>)";
    replace(R"(<geom name=")" + side + R"(Ball0" type="sphere" size="0.01" pos="0.09 0.05 -0.05")" + tail,
            R"(<geom name=")" + side + R"(Toe" type="capsule" size="0.01" fromto="0.09 0.03 -0.05 0.09 -0.03 -0.05")" +
                tail);
    replace(R"(<geom name=")" + side + R"(Ball1" type="sphere" size="0.01" pos="0.09 -0.05 -0.05")" + tail, "");
    replace(R"(<geom name=")" + side + R"(Ball2" type="sphere" size="0.01" pos="-0.09 0.05 -0.05")" + tail,
            R"(<geom name=")" + side + R"(Heel" type="ellipsoid" size="0.02 0.01 0.01" pos="-0.09 0.05 -0.05")" + tail);
  }
  const humanoid::RobotDescriptionParams p = humanoid::testing::fixture_walk("four_sphere_feet.yaml").description;
  const humanoid::LoadedRobot a = load_robot_text(xml, "xml", "four_sphere_feet.xml", p);
  const std::string urdf = humanoid::robot_urdf(a);
  std::size_t collisions = 0;
  for (auto at = urdf.find("<collision>"); at != std::string::npos; at = urdf.find("<collision>", at + 1)) ++collisions;
  EXPECT_EQ(collisions, 8u);  // per foot: the capsule's two spheres, the ellipsoid's one, the sphere
  humanoid::RobotDescriptionParams q = p;
  std::istringstream mapping(humanoid::urdf_mapping(a));
  for (std::string line; std::getline(mapping, line);)
    for (int side = 0; side < 2; ++side) {
      const std::string f = std::string("robot.feet.") + (side == 0 ? "left" : "right");
      if (line.rfind(f + ".sole_size=", 0) == 0) q.feet[side].sole_size = line.substr(line.find('=') + 1);
    }
  EXPECT_EQ(q.feet[0].sole_size, "none");
  const humanoid::LoadedRobot b = load_robot_text(urdf, "urdf", "robot.urdf", q);
  for (int side = 0; side < 2; ++side) {
    const humanoid::Sole &x = a.sole[side], &y = b.sole[side];
    ASSERT_EQ(x.hull.size(), 4u);
    EXPECT_TRUE(y.hull_in_twin);
    ASSERT_EQ(y.hull.size(), x.hull.size());
    for (std::size_t i = 0; i < x.hull.size(); ++i)
      for (int k = 0; k < 2; ++k) EXPECT_NEAR(y.hull[i][k] - y.center[k], x.hull[i][k] - x.center[k], 1e-12);
    EXPECT_NEAR(y.center[2], x.center[2], 1e-12);
    EXPECT_NEAR(x.length, 0.18, 1e-15);
    EXPECT_NEAR(x.width, 0.10, 1e-15);
  }
  const walking::RobotModel m = walking::make_robot_model(b);
  EXPECT_FALSE(m.sole_polygon[0].rectangle);  // a trapezoid: 60 mm wide at the toe, 100 mm at the heel
}

// Each joint's link-side inertia (the gear's load in the twin) is the composite inertia of the bodies below it
// about its axis: MuJoCo's mass matrix diagonal less the armature equals the sum over the subtree of each body's
// inertia about the axis (parallel axis theorem) at zero angles, to rounding (1e-12 relative: a few dozen
// products of numbers near 1). The file's armature (its rotors' reflected inertia) is not put on the twin's links:
// the elastic drive holds the rotor behind the gear spring.
TEST(RobotLoader, LinkInertiaIsTheInertiaBelowTheJointAndTheTwinCarriesNoArmature) {
  std::string xml = small_biped_xml();
  const std::string knee = R"(<joint name="LKnee" axis="0 1 0")";
  xml.insert(xml.find(knee) + knee.size(), R"( armature="0.0625")");
  const humanoid::RobotDescriptionParams p = humanoid::testing::fixture_walk("small_biped.yaml").description;
  const humanoid::LoadedRobot a = load_robot_text(xml, "xml", "small_biped.xml", p);
  const auto rotation = [](const std::array<double, 4>& q) {
    return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  };
  const std::size_t n = a.bodies.size();
  std::vector<Matrix3d> R(n);
  std::vector<Vector3d> x(n);
  for (std::size_t b = 0; b < n; ++b) {  // (parents before children)
    const humanoid::LoadedBody& body = a.bodies[b];
    const Vector3d pos(body.pos[0], body.pos[1], body.pos[2]);
    if (body.parent < 0) {
      R[b] = Matrix3d::Identity(), x[b] = Vector3d::Zero();
      continue;
    }
    const auto up = static_cast<std::size_t>(body.parent);
    R[b] = R[up] * rotation(body.quat);
    x[b] = x[up] + R[up] * pos;
  }
  const auto below = [&](std::size_t c, std::size_t b) {
    for (int i = static_cast<int>(c); i >= 0; i = a.bodies[static_cast<std::size_t>(i)].parent)
      if (static_cast<std::size_t>(i) == b) return true;
    return false;
  };
  int checked = 0;
  for (std::size_t b = 0; b < n; ++b)
    for (const humanoid::LoadedJoint& j : a.bodies[b].joints) {
      const Vector3d anchor = x[b] + R[b] * Vector3d(j.pos[0], j.pos[1], j.pos[2]);
      const Vector3d axis = R[b] * Vector3d(j.axis[0], j.axis[1], j.axis[2]);
      double sum = 0;
      for (std::size_t c = 0; c < n; ++c) {
        if (!below(c, b)) continue;
        const humanoid::LoadedBody& body = a.bodies[c];
        const Matrix3d Ri = R[c] * rotation(body.iquat);
        const Matrix3d I =
            Ri * Vector3d(body.inertia[0], body.inertia[1], body.inertia[2]).asDiagonal() * Ri.transpose();
        const Vector3d r = x[c] + R[c] * Vector3d(body.ipos[0], body.ipos[1], body.ipos[2]) - anchor;
        sum += axis.dot(I * axis) + body.mass * r.cross(axis).squaredNorm();
      }
      EXPECT_NEAR(j.link_inertia, sum, 1e-12 * sum) << j.name;
      EXPECT_GT(j.link_inertia, 0) << j.name;
      ++checked;
    }
  EXPECT_GE(checked, 12);
  const auto [kb, kk] = a.joint[humanoid::kLeftKnee];
  EXPECT_EQ(a.bodies[static_cast<std::size_t>(kb)].joints[static_cast<std::size_t>(kk)].armature, 0.0625);
  const Compiled twin(twin_mjcf(a, humanoid::RobotParams{}, PlantParams{}));
  for (int v = 0; v < twin.m->nv; ++v) EXPECT_EQ(twin.m->dof_armature[v], 0.0) << v;
}

// The physics step's bound (walking::kMaxGearPhasePerStep) is what the builtin's fastest gear mode turns in its
// 1 ms step, to the 3 digits it is written with.
TEST(RobotLoader, BuiltinsFastestGearModeSetsThePhysicsStepsBound) {
  const double phase = walking::fastest_gear_mode(builtin_loaded(), PlantParams{}.gear_stiffness()) * 0.001;
  EXPECT_NEAR(phase, walking::kMaxGearPhasePerStep, 5e-4);
  EXPECT_LE(phase, walking::kMaxGearPhasePerStep);  // the builtin keeps 1 ms
}

}  // namespace
}  // namespace flexgait::twin
