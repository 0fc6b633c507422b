// The deformation model against the twin (MuJoCo, elastic gears) in a static single-support pose,
// where the load is determinate (all on the stance foot, under the COM): the input compensator
// (eqs. 8-9, full form) brings the true link angles to the desired ones within 1e-6 rad (the
// issue asks 1e-4), and the output compensator (eqs. 10-13) reads them back from the quantised
// encoders within two encoder steps (2.5e-5 rad); without
// compensation the stance leg is centiradians off, and the thesis form (no leg weight) is worse
// than the full form. The same for a loaded robot of another layout (the test robot
// tests/humanoid/data/small_biped.xml, numeric leg IK).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/twin/plant.hpp"
#include "flexgait/walking/leg_kinematics.hpp"

namespace flexgait::compensation {
namespace {

using walking::Matrix3d;
using walking::Pose;
using walking::Vector3d;

constexpr double kSwingLift = 0.05;  // the right foot held this high [m]
// The whole body's slow sway on its compliant legs (~0.5 Hz) takes this long to die out to 1e-9 rad.
constexpr double kHoldTime = 12.0;                                         // [s]
const double kEncoderStep = 2 * M_PI / twin::PlantParams{}.encoder_steps;  // the twin's encoder resolution [rad]

/// A robot: the controller's model, the twin, the pelvis height of the test pose [m].
struct Robot {
  walking::RobotModel model;
  twin::TwinModel twin;
  double pelvis_height = 0.72;
};

/// The builtin robot, or (second) the loaded test robot, with this plant.
Robot robot(bool second, const twin::PlantParams& plant) {
  if (!second)
    return {walking::make_robot_model(humanoid::RobotParams{}), twin::builtin_twin(humanoid::RobotParams{}, plant),
            0.72};
  const char* dir = std::getenv("FLEXGAIT_TEST_DATA");
  const std::filesystem::path file = std::filesystem::path(dir ? dir : "tests/humanoid/data") / "small_biped.yaml";
  experiments::WalkRunParams w =
      experiments::walk_run_from_config(resolve_config(experiments::walk_run_schema(), file, {}));
  w.plant = plant;
  return {experiments::walk_controller_model(w), experiments::walk_twin(w), 0.56};
}

/// Standing on the left foot, the right raised, the COM over the left sole centre (the model's).
humanoid::JointVector single_support_pose(const walking::RobotModel& model, double pelvis_height,
                                          std::array<Pose, 2>& soles) {
  const double y = model.leg[0].anchor[0].y();  // under the hip yaw axes
  soles = {Pose{Vector3d(0, y, 0), Matrix3d::Identity()}, Pose{Vector3d(0, -y, kSwingLift), Matrix3d::Identity()}};
  Pose pelvis{Vector3d(0, 0, pelvis_height), Matrix3d::Identity()};
  walking::RobotModelData data;
  humanoid::JointVector q{};
  for (int it = 0; it < 40; ++it) {
    for (int side = 0; side < 2; ++side) {
      const Pose local{pelvis.R.transpose() * (soles[side].p - pelvis.p), pelvis.R.transpose() * soles[side].R};
      const walking::IkSolution ik = walking::leg_inverse_kinematics(model.leg[side], local);
      for (int i = 0; i < humanoid::kLegJoints; ++i) q[humanoid::leg_first_joint(side) + i] = ik.q[i];
    }
    walking::forward_kinematics(model, data, pelvis, q);
    const Vector3d com = walking::center_of_mass(model, data);
    pelvis.p.x() -= com.x() - soles[0].p.x();
    pelvis.p.y() -= com.y() - soles[0].p.y();
  }
  return q;
}

struct Hold {
  double link_error = 0;      ///< max over the leg joints of |θ_link − θ_d| [rad]
  double estimate_error = 0;  ///< max |θ̂ − θ_link| of the output compensator [rad]
  double deflection = 0;      ///< max |θ_enc − θ_link| [rad]
};

/// Holds the compensated pose on the twin for kHoldTime (servo with integral action: the compensator
/// models the gear, not the servo's proportional sag).
Hold hold(CompensationMode mode, GravityForm form, bool second = false) {
  twin::PlantParams plant;
  plant.servo_integral_time = 0.05;
  const Robot r = robot(second, plant);
  const walking::RobotModel& model = r.model;
  std::array<Pose, 2> soles;
  const humanoid::JointVector desired = single_support_pose(model, r.pelvis_height, soles);
  CompensationParams p;
  p.mode = mode;
  p.gravity = form;
  p.split = WeightSplit::kCom;
  DeformationCompensator compensator(model, p);
  SupportPlan plan;
  plan.swinging = {false, true};
  plan.soles = soles;
  const humanoid::JointVector command = compensator.input(desired, Matrix3d::Identity(), plan);
  twin::HumanoidPlant twin(r.twin, plant);
  twin.reset(desired);
  for (int k = 0; k < static_cast<int>(kHoldTime / plant.control_period); ++k) twin.step(command);
  const twin::GroundTruth g = twin.truth();
  EXPECT_TRUE(g.sole_contact[0]);
  EXPECT_FALSE(g.sole_contact[1]);
  const Matrix3d imu = walking::quat_to_matrix(twin.sensors().imu.quat.data());
  const OutputEstimate& e = compensator.output(twin.sensors().encoder, imu, plan);
  EXPECT_TRUE(e.converged);
  Hold h;
  for (int j = humanoid::kLeftHipYaw; j < humanoid::kJoints; ++j) {
    h.link_error = std::max(h.link_error, std::abs(g.link_angle[j] - desired[j]));
    h.estimate_error = std::max(h.estimate_error, std::abs(e.newton[j] - g.link_angle[j]));
    h.deflection = std::max(h.deflection, std::abs(twin.sensors().encoder[j] - g.link_angle[j]));
  }
  return h;
}

TEST(TwinStatic, InputCompensationPutsTheLinksWhereDesired) {
  const Hold off = hold(CompensationMode::kOff, GravityForm::kFull);
  const Hold full = hold(CompensationMode::kBoth, GravityForm::kFull);
  const Hold thesis = hold(CompensationMode::kBoth, GravityForm::kThesis);
  RecordProperty("link_error_off", std::to_string(off.link_error));
  RecordProperty("link_error_full", std::to_string(full.link_error));
  RecordProperty("link_error_thesis", std::to_string(thesis.link_error));
  EXPECT_GT(off.link_error, 0.02);                    // the gears sag by centiradians under the body
  EXPECT_LT(full.link_error, 1e-6);                   // the target is 1e-4; the model matches the twin to ~1e-8
  EXPECT_GT(thesis.link_error, 5 * full.link_error);  // the legs' own weight matters
}

TEST(TwinStatic, InputCompensationPutsTheLinksWhereDesiredOnASecondRobot) {
  const Hold off = hold(CompensationMode::kOff, GravityForm::kFull, true);
  const Hold full = hold(CompensationMode::kBoth, GravityForm::kFull, true);
  RecordProperty("link_error_off", std::to_string(off.link_error));
  RecordProperty("link_error_full", std::to_string(full.link_error));
  EXPECT_GT(off.link_error, 0.02);   // the gears sag by centiradians under this body too (0.042 rad)
  EXPECT_LT(full.link_error, 1e-6);  // the same bound as the builtin's
}

TEST(TwinStatic, OutputCompensationReadsTheLinkAnglesFromTheEncoders) {
  for (const CompensationMode mode : {CompensationMode::kOff, CompensationMode::kBoth}) {
    const Hold h = hold(mode, GravityForm::kFull);
    EXPECT_GT(h.deflection, 0.02);
    EXPECT_LT(h.estimate_error, 2 * kEncoderStep) << name_of(mode);  // the encoders' quantisation
  }
}

}  // namespace
}  // namespace flexgait::compensation
