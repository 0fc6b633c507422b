// The controller's model of a loaded description (walking/robot_model_loaded.cpp): the
// builtin's MJCF loaded back gives the builtin's own model; the model of a loaded robot agrees
// with MuJoCo's of the same twin (COM, sole poses, Jacobians, gravity torques), for the builtin
// and for the test robot with its own names and an offset hip pitch axis.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "flexgait/robot/urdf_export.hpp"
#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/robot_loader.hpp"
#include "flexgait/twin/twin_mjcf.hpp"
#include "flexgait/walking/robot_model.hpp"
#include "flexgait/walking/stance_defaults.hpp"
#include "model_agreement.hpp"

namespace flexgait::humanoid {
namespace {

using testing::expect_model_agrees_with_mujoco;
using testing::fixture_walk;
using testing::small_biped_walk;
using walking::Pose;
using walking::RobotModel;
using walking::Vector3d;

LoadedRobot builtin_loaded() {
  return twin::load_robot_text(twin::humanoid_mjcf(RobotParams{}, twin::PlantParams{}), "xml", "builtin.xml",
                               RobotDescriptionParams{});
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

TEST(RobotModelLoaded, ControllerModelAgreesWithMuJoCo) {
  expect_model_agrees_with_mujoco(builtin_loaded());
}

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

/// FK∘IK on leg `side` of `model`: random angles inside the joints' ranges (the knee bent 0.2 to
/// 1.5 rad the way its range allows, the others ±0.3 rad), their sole pose, the IK of that pose;
/// the IK's angles must put the sole there (the issue's 1e-10: Newton's steps stop at |e| < 1e-12)
/// and lie inside the ranges. Also the leg's own FK against the whole model's (one chain, two
/// codes) to 1e-12.
void expect_ik_inverts_fk(const RobotModel& model, int side) {
  const walking::LegGeometry& leg = model.leg[static_cast<std::size_t>(side)];
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> small(-0.3, 0.3), bend(0.2, 1.5);
  walking::RobotModelData data;
  for (int trial = 0; trial < 200; ++trial) {
    walking::LegAngles q;
    for (auto& v : q) v = small(rng);
    q[3] = leg.sign[3] * leg.knee_branch() * bend(rng);
    JointVector all{};
    for (int i = 0; i < kLegJoints; ++i) all[leg_first_joint(side) + i] = q[static_cast<std::size_t>(i)];
    walking::forward_kinematics(model, data, Pose{}, all);
    const Pose target = walking::leg_forward_kinematics(leg, q);
    const Pose whole = walking::sole_pose(model, data, side);
    ASSERT_LT((whole.p - target.p).norm(), 1e-12);
    ASSERT_LT((whole.R - target.R).cwiseAbs().maxCoeff(), 1e-12);
    const walking::IkSolution ik = walking::leg_inverse_kinematics(leg, target);
    ASSERT_EQ(ik.status, walking::IkStatus::kOk) << trial;
    const Pose back = walking::leg_forward_kinematics(leg, ik.q);
    EXPECT_LT((back.p - target.p).norm(), 1e-10) << trial;
    EXPECT_LT((back.R - target.R).cwiseAbs().maxCoeff(), 1e-10) << trial;
    for (int i = 0; i < kLegJoints; ++i) {
      EXPECT_GE(ik.q[static_cast<std::size_t>(i)], leg.lower[static_cast<std::size_t>(i)]) << trial << " joint " << i;
      EXPECT_LE(ik.q[static_cast<std::size_t>(i)], leg.upper[static_cast<std::size_t>(i)]) << trial << " joint " << i;
    }
  }
}

// A knee whose axis points along −y (ROBOTIS's right knee) and whose range only bends it forward:
// the model agrees with MuJoCo's, the IK bends that knee to negative angles (inside its range),
// with the numeric IK (the robot's offset hip pitch) and with the analytic one (no offset); the
// robot stands and walks 10 steps without a joint at its limit.
TEST(RobotModelLoaded, MinusYKneeBendsTheWayItsRangeAllows) {
  experiments::WalkRunParams walk = fixture_walk("minus_y_knee.yaml");
  ASSERT_TRUE(walk.loaded);
  expect_model_agrees_with_mujoco(*walk.loaded);
  const RobotModel model = walking::make_robot_model(*walk.loaded);
  EXPECT_EQ(model.leg[1].sign[3], -1.0);
  EXPECT_EQ(model.leg[0].sign[3], 1.0);
  EXPECT_EQ(model.range[kRightKnee][0], -2.4);
  for (int side = 0; side < 2; ++side) expect_ik_inverts_fk(model, side);
  const JointVector stand = walking::standing_angles(model, walk.walk.pelvis_height, walk.walk.step_width);
  EXPECT_GT(stand[kLeftKnee], 0.5);
  EXPECT_LT(stand[kRightKnee], -0.5);
  EXPECT_NEAR(stand[kLeftKnee], -stand[kRightKnee], 1e-9);
  // Without the hip pitch offset the leg has the analytic layout, signs and all.
  LoadedRobot aligned = *walk.loaded;
  for (auto& b : aligned.bodies)
    if (b.name == "LThigh" || b.name == "RThigh") b.pos = {0, 0, 0};
  const RobotModel analytic = walking::make_robot_model(aligned);
  ASSERT_TRUE(analytic.leg[1].analytic) << walking::analytic_ik_mismatch(aligned, 1);
  expect_model_agrees_with_mujoco(aligned);
  for (int side = 0; side < 2; ++side) expect_ik_inverts_fk(analytic, side);
  const experiments::WalkResult r = experiments::run_walk(walk);
  EXPECT_TRUE(r.metrics.completed()) << r.metrics.fall_text() << r.metrics.failure_text();
  EXPECT_EQ(r.metrics.steps_completed, 10);
  EXPECT_EQ(r.metrics.joint_limit_hits, 0);
  EXPECT_EQ(r.metrics.desired_range_hits, 0);
  EXPECT_TRUE(r.metrics.joint_ranges);
}

// A range narrower than the gait's sway (the left hip roll held within 5 mrad of its standing
// angle): the plan's angles outside it are counted. Uncompensated the command is the plan's angle,
// so the clamped commands and the desired angles outside the range are the same count.
TEST(RobotModelLoaded, PlannedAnglesOutsideARangeAreCounted) {
  experiments::WalkRunParams walk = fixture_walk("small_biped.yaml", {"walk.steps=2", "control.compensation=off"});
  ASSERT_TRUE(walk.loaded);
  const JointVector stand =
      walking::standing_angles(walking::make_robot_model(*walk.loaded), walk.walk.pelvis_height, walk.walk.step_width);
  auto narrowed = std::make_shared<LoadedRobot>(*walk.loaded);
  for (auto& body : narrowed->bodies)
    for (auto& joint : body.joints)
      if (joint.mapped == kLeftHipRoll) {
        joint.limited = true;
        joint.range = {stand[kLeftHipRoll] - 0.005, stand[kLeftHipRoll] + 0.005};
      }
  walk.loaded = narrowed;
  const experiments::WalkResult r = experiments::run_walk(walk);
  EXPECT_GT(r.metrics.desired_range_hits, 100);
  EXPECT_EQ(r.metrics.joint_limit_hits, r.metrics.desired_range_hits);
}

// Hips ordered pitch, roll, yaw from the pelvis (Unitree G1's order), mapped by role: the model's
// Jacobian columns and gravity torques are by role and agree with MuJoCo's; FK∘IK; 10 steps.
TEST(RobotModelLoaded, PitchRollYawHipsMappedByRole) {
  experiments::WalkRunParams walk = fixture_walk("pitch_roll_yaw_hips.yaml");
  ASSERT_TRUE(walk.loaded);
  EXPECT_EQ(walk.loaded->leg_order[0], (std::array<int, 6>{2, 1, 0, 3, 4, 5}));
  expect_model_agrees_with_mujoco(*walk.loaded);
  const RobotModel model = walking::make_robot_model(*walk.loaded);
  EXPECT_FALSE(model.leg[0].analytic);
  EXPECT_EQ(walking::analytic_ik_mismatch(*walk.loaded, 0), "joint 1 from the root is l_hip_pitch, not l_hip_yaw");
  for (int side = 0; side < 2; ++side) expect_ik_inverts_fk(model, side);
  const experiments::WalkResult r = experiments::run_walk(walk);
  EXPECT_TRUE(r.metrics.completed()) << r.metrics.fall_text() << r.metrics.failure_text();
  EXPECT_EQ(r.metrics.steps_completed, 10);
}

// Four spheres under each foot, the robot's only geoms that touch the floor, and no sole in the
// mapping: the sole is their hull on the lowest plane, small_biped's 0.18 x 0.10 m rectangle 60 mm
// below the ankle (the spheres' centres at its corners, radius 10 mm: 1e-15 m is rounding); the
// twin's plate only marks it (no contact) and the spheres take the sole's contact; the model agrees
// with MuJoCo's, FK∘IK; 10 steps on the spheres, no other contact.
TEST(RobotModelLoaded, FourSphereFeetMakeTheSole) {
  experiments::WalkRunParams walk = fixture_walk("four_sphere_feet.yaml");
  ASSERT_TRUE(walk.loaded);
  for (int side = 0; side < 2; ++side) {
    const Sole& sole = walk.loaded->sole[side];
    EXPECT_EQ(sole.geom, -1);
    EXPECT_EQ(sole.hull.size(), 4u);
    EXPECT_EQ(sole.hull_geoms, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_TRUE(sole.hull_in_twin);
    EXPECT_NEAR(sole.length, 0.18, 1e-15);
    EXPECT_NEAR(sole.width, 0.10, 1e-15);
    EXPECT_NEAR(sole.center[2], -0.06, 1e-15);
    EXPECT_NEAR(std::abs(sole.center[0]) + std::abs(sole.center[1]), 0.0, 1e-15);
  }
  const std::string twin = twin::twin_mjcf(*walk.loaded, walk.robot, walk.plant);
  const auto plate = twin.find(R"(<geom name="l_sole" type="box" size="0.09 0.05 0.005")");
  ASSERT_NE(plate, std::string::npos) << twin;
  EXPECT_NE(twin.substr(plate, twin.find('\n', plate) - plate).find(R"(contype="0" conaffinity="0")"),
            std::string::npos);
  EXPECT_NE(twin.find(R"(<geom name="LBall0" type="sphere" size="0.01 0 0" pos="0.09 0.05 -0.05" quat="1 0 0 0" )"
                      R"(contype="1" conaffinity="1" condim="3" friction="1 0.005 0.0001" solref="0.005 1")"),
            std::string::npos);
  expect_model_agrees_with_mujoco(*walk.loaded);
  const RobotModel model = walking::make_robot_model(*walk.loaded);
  const RobotModel box = walking::make_robot_model(*small_biped_walk().loaded);
  EXPECT_NEAR(model.sole_length, box.sole_length, 1e-15);
  EXPECT_NEAR(model.sole_width, box.sole_width, 1e-15);
  for (int side = 0; side < 2; ++side) {
    EXPECT_LT((model.sole_offset[side] - box.sole_offset[side]).norm(), 1e-15);
    expect_ik_inverts_fk(model, side);
  }
  const experiments::WalkResult r = experiments::run_walk(walk);
  EXPECT_TRUE(r.metrics.completed()) << r.metrics.fall_text() << r.metrics.failure_text();
  EXPECT_EQ(r.metrics.steps_completed, 10);
  EXPECT_EQ(r.metrics.mujoco_warnings, 0);
}

// The fixture NAME.yaml's robot exported as URDF and loaded back by its mapping (4 steps).
experiments::WalkRunParams reloaded_from_urdf(const std::string& name, const LoadedRobot& robot) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / ("flexgait_" + name + ".urdf");
  std::ofstream(file) << robot_urdf(robot);
  std::vector<std::string> overrides{"robot.description=" + file.string(), "walk.steps=4"};
  std::istringstream lines(urdf_mapping(robot));
  for (std::string line; std::getline(lines, line);) overrides.push_back(line);
  experiments::WalkRunParams reloaded = fixture_walk(name + ".yaml", overrides);
  std::filesystem::remove(file);
  return reloaded;
}

// Eight spheres under each foot on an octagon (the 0.18 x 0.10 m rectangle with its corners cut
// 30 x 20 mm): the controller's sole polygon is that octagon, not its bounding rectangle, whose
// corners lie outside it. Exported as URDF, each sphere is a <collision> of the foot and the mapping
// names no sole: the reload makes the same polygon (1e-12 m: URDF keeps shortest round-trip
// decimals, the link frame's shift by the ankle anchor rounds once) and walks on it (4 steps, for
// the tests' time; 10 in docs/guide/robot.md's measurement).
TEST(RobotModelLoaded, OctagonSphereFeetSoleIsTheOctagonAndUrdfExportKeepsIt) {
  const experiments::WalkRunParams walk = fixture_walk("octagon_sphere_feet.yaml");
  ASSERT_TRUE(walk.loaded);
  const RobotModel model = walking::make_robot_model(*walk.loaded);
  const std::vector<Eigen::Vector2d> octagon{Eigen::Vector2d(-0.09, -0.03), Eigen::Vector2d(-0.06, -0.05),
                                             Eigen::Vector2d(0.06, -0.05),  Eigen::Vector2d(0.09, -0.03),
                                             Eigen::Vector2d(0.09, 0.03),   Eigen::Vector2d(0.06, 0.05),
                                             Eigen::Vector2d(-0.06, 0.05),  Eigen::Vector2d(-0.09, 0.03)};
  EXPECT_NEAR(model.sole_length, 0.18, 1e-15);
  EXPECT_NEAR(model.sole_width, 0.10, 1e-15);
  for (int side = 0; side < 2; ++side) {
    const walking::SolePolygon& s = model.sole_polygon[static_cast<std::size_t>(side)];
    EXPECT_FALSE(s.rectangle);
    ASSERT_EQ(s.corners.size(), octagon.size());
    for (std::size_t i = 0; i < octagon.size(); ++i) EXPECT_LT((s.corners[i] - octagon[i]).norm(), 1e-15);
    EXPECT_FALSE(walking::contains(s, Eigen::Vector2d(0.09, 0.05)));  // the bounding rectangle's corner
    EXPECT_LT((walking::nearest_point(s, Eigen::Vector2d(0.0, 0.2)) - Eigen::Vector2d(0.0, 0.05)).norm(), 1e-16);
  }
  const std::string urdf = robot_urdf(*walk.loaded), mapping = urdf_mapping(*walk.loaded);
  std::size_t collisions = 0;
  for (auto at = urdf.find("<collision>"); at != std::string::npos; at = urdf.find("<collision>", at + 1)) ++collisions;
  EXPECT_EQ(collisions, 16u);
  EXPECT_NE(mapping.find("robot.feet.left.sole_size=none"), std::string::npos) << mapping;
  const experiments::WalkRunParams reloaded = reloaded_from_urdf("octagon_sphere_feet", *walk.loaded);
  ASSERT_TRUE(reloaded.loaded);
  const RobotModel back = walking::make_robot_model(*reloaded.loaded);
  for (int side = 0; side < 2; ++side) {
    const walking::SolePolygon &a = model.sole_polygon[static_cast<std::size_t>(side)],
                               &b = back.sole_polygon[static_cast<std::size_t>(side)];
    EXPECT_FALSE(b.rectangle);
    ASSERT_EQ(b.corners.size(), a.corners.size());
    for (std::size_t i = 0; i < a.corners.size(); ++i) EXPECT_LT((b.corners[i] - a.corners[i]).norm(), 1e-12);
    EXPECT_LT((back.sole_offset[side] - model.sole_offset[side]).norm(), 1e-12);
  }
  const experiments::WalkResult r = experiments::run_walk(reloaded);
  EXPECT_TRUE(r.metrics.completed()) << r.metrics.fall_text() << r.metrics.failure_text();
  EXPECT_EQ(r.metrics.steps_completed, 4);
}

// Foot bodies whose frames follow the joint axes (turned 90 deg at zero joint angles) and a sole
// box pitched 10 deg there: the sole takes the box's frame (its z the box's face that looks most
// down, its x the axis that looks most forward), the model agrees with MuJoCo's (the twin's sole
// plate and F/T site in that frame), FK∘IK, and the robot stands with its ankles pitched 10 deg to
// level the soles and walks 10 steps.
TEST(RobotModelLoaded, TurnedFootFramesTakeTheSolesOwnFrame) {
  experiments::WalkRunParams walk = fixture_walk("turned_foot_frames.yaml");
  ASSERT_TRUE(walk.loaded);
  const Eigen::Matrix3d pitch10 = Eigen::AngleAxisd(10.0 * std::numbers::pi / 180.0, Vector3d::UnitY()).matrix();
  const RobotModel model = walking::make_robot_model(*walk.loaded);
  for (int side = 0; side < 2; ++side) {
    const Sole& sole = walk.loaded->sole[side];
    // the box's own frame in the foot body's: -80 deg about y (17 printed digits and a few products: 1e-14)
    const Eigen::Quaterniond q(sole.quat[0], sole.quat[1], sole.quat[2], sole.quat[3]);
    EXPECT_LT((q.toRotationMatrix() - Eigen::AngleAxisd(-80.0 * std::numbers::pi / 180.0, Vector3d::UnitY()).matrix())
                  .cwiseAbs()
                  .maxCoeff(),
              1e-14);
    EXPECT_NEAR(sole.length, 0.18, 1e-15);
    EXPECT_NEAR(sole.width, 0.10, 1e-15);
    EXPECT_TRUE(model.sole_tilted[side]);
    EXPECT_LT((model.sole_rotation[side] - pitch10).cwiseAbs().maxCoeff(), 1e-14);
    // the sole centre 60 mm below the ankle along the sole's normal: 50 mm to the box's centre, 10 mm
    // its half-thickness
    EXPECT_LT((model.sole_offset[side] - (Vector3d(0, 0, -0.05) + pitch10 * Vector3d(0, 0, -0.01))).norm(), 1e-14);
    EXPECT_NEAR(model.leg[side].ankle_to_sole, 0.05 * std::cos(10.0 * std::numbers::pi / 180.0) + 0.01, 1e-14);
    expect_ik_inverts_fk(model, side);
  }
  expect_model_agrees_with_mujoco(*walk.loaded);
  // Standing with level soles below the hips, the ankle pitch levels the 10 deg (hip and knee pitch
  // add up to it with the ankle, the same axis y).
  const JointVector q = walking::standing_angles(model, walk.walk.pelvis_height, walk.walk.step_width);
  for (int side = 0; side < 2; ++side) {
    const int j = leg_first_joint(side);
    EXPECT_NEAR(q[j + 2] + q[j + 3] + q[j + 4], -10.0 * std::numbers::pi / 180.0, 1e-9) << side;
  }
  const experiments::WalkResult r = experiments::run_walk(walk);
  EXPECT_TRUE(r.metrics.completed()) << r.metrics.fall_text() << r.metrics.failure_text();
  EXPECT_EQ(r.metrics.steps_completed, 10);
  EXPECT_EQ(r.metrics.mujoco_warnings, 0);
  // Exported as URDF (each frame's rpy at gimbal lock: the foot bodies are turned a quarter about
  // y) and loaded back: the same sole frame and model, to the 17 printed digits' 1e-12.
  const experiments::WalkRunParams reloaded = reloaded_from_urdf("turned_foot_frames", *walk.loaded);
  ASSERT_TRUE(reloaded.loaded);
  const RobotModel back = walking::make_robot_model(*reloaded.loaded);
  for (int side = 0; side < 2; ++side) {
    EXPECT_LT((back.sole_rotation[side] - model.sole_rotation[side]).cwiseAbs().maxCoeff(), 1e-12) << side;
    EXPECT_LT((back.sole_offset[side] - model.sole_offset[side]).norm(), 1e-12) << side;
    EXPECT_LT((back.ft_to_sole[side] - model.ft_to_sole[side]).norm(), 1e-12) << side;
    EXPECT_NEAR(back.leg[side].ankle_to_sole, model.leg[side].ankle_to_sole, 1e-12) << side;
  }
  expect_model_agrees_with_mujoco(*reloaded.loaded);
}

// Massless foot bodies (the F/T sensors between them and the ankle-roll links, which carry the
// feet's mass): the model agrees with MuJoCo's, FK∘IK; the F/T reads exactly 0 N in swing, which
// is not a stuck sensor: 10 steps, no sensor fault.
TEST(RobotModelLoaded, MasslessFootWalks) {
  experiments::WalkRunParams walk = fixture_walk("massless_foot.yaml");
  ASSERT_TRUE(walk.loaded);
  for (int side = 0; side < 2; ++side)
    EXPECT_EQ(walk.loaded->bodies[static_cast<std::size_t>(walk.loaded->foot[side])].mass, 0.0);
  expect_model_agrees_with_mujoco(*walk.loaded);
  const RobotModel model = walking::make_robot_model(*walk.loaded);
  EXPECT_NEAR(model.total_mass, 34.6, 1e-12);
  for (int side = 0; side < 2; ++side) expect_ik_inverts_fk(model, side);
  const experiments::WalkResult r = experiments::run_walk(walk);
  EXPECT_TRUE(r.metrics.completed()) << r.metrics.fall_text() << r.metrics.failure_text();
  EXPECT_EQ(r.metrics.steps_completed, 10);
  EXPECT_FALSE(r.metrics.safe_stop);
  // No reading is flagged: the swinging foot's zero, and the landing foot's, late or touching and bouncing off the
  // floor before it bears the load, are the unloaded sensor's true value.
  EXPECT_EQ(r.metrics.sensor_fault_episodes, 0) << ::testing::PrintToString(r.metrics.sensor_faults);
}

// A robot without joint ranges (small_biped.xml has none) walks: SecondRobotWalks; here, that it has none.
TEST(RobotModelLoaded, SecondRobotHasNoJointRanges) {
  const experiments::WalkRunParams walk = small_biped_walk();
  ASSERT_TRUE(walk.loaded);
  for (const LoadedBody& b : walk.loaded->bodies)
    for (const LoadedJoint& j : b.joints) EXPECT_FALSE(j.limited) << j.name;
}

// Commanded angles outside a range are clamped and counted.
TEST(RobotModelLoaded, ClampToRangesCounts) {
  RobotModel model = walking::make_robot_model(RobotParams{});
  JointVector q{};
  q[kLeftKnee] = -0.2;
  q[kRightKnee] = 2.5;
  EXPECT_EQ(walking::clamp_to_ranges(model, q), 0);  // the builtin: no ranges
  model.range[kLeftKnee] = {0, 2.4};
  model.range[kRightKnee] = {0, 2.4};
  EXPECT_EQ(walking::clamp_to_ranges(model, q), 2);
  EXPECT_EQ(q[kLeftKnee], 0.0);
  EXPECT_EQ(q[kRightKnee], 2.4);
}

}  // namespace
}  // namespace flexgait::humanoid
