// The twin: mass, standing on its own, gravity deflection of the elastic gears, sensors,
// encoder quantisation, determinism.
#include "flexgait/humanoid/plant.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <numbers>

#include "flexgait/humanoid/model_xml.hpp"

namespace flexgait::humanoid {
namespace {

PlantParams default_plant(double k = 1000.0) {
  PlantParams p;
  p.k_joint = k;
  return p;
}

constexpr double kStandHeight = 0.75;  // pelvis height of the nominal pose [m] (spec: walk at 0.75 m)

// Stands for `seconds` with the nominal pose commanded.
HumanoidPlant& stand(HumanoidPlant& plant, double seconds) {
  const JointVector pose = standing_pose(RobotParams{}, kStandHeight);
  plant.reset(pose);
  const int steps = static_cast<int>(std::lround(seconds / plant.params().control_period));
  for (int i = 0; i < steps; ++i) plant.step(pose);
  return plant;
}

TEST(HumanoidPlant, TotalMassIsTheParameter) {
  RobotParams r;
  HumanoidPlant a(r, default_plant());
  EXPECT_NEAR(a.total_mass(), 57.0, 1e-9);
  r.total_mass = 70.0;
  HumanoidPlant b(r, default_plant());
  EXPECT_NEAR(b.total_mass(), 70.0, 1e-9);
}

TEST(HumanoidPlant, StandingPoseReachesTheRequestedHeight) {
  HumanoidPlant plant(RobotParams{}, default_plant());
  plant.reset(standing_pose(RobotParams{}, kStandHeight));
  // Before any gear deflection, the pelvis sits at the requested height (soles on the floor).
  EXPECT_NEAR(plant.truth().pelvis_pos[2], kStandHeight, 1e-9);
}

TEST(HumanoidPlant, StandsTenSecondsAndTheFeetCarryTheWeight) {
  HumanoidPlant plant(RobotParams{}, default_plant());
  stand(plant, 10.0);
  const GroundTruth t = plant.truth();
  EXPECT_GT(t.pelvis_pos[2], 0.6) << "fell";
  EXPECT_FALSE(t.non_sole_contact);
  EXPECT_EQ(t.warnings, 0);
  // The F/T sensors carry everything above them: total mass minus the two feet (1 %).
  const RobotParams r;
  const double above = (plant.total_mass() - 2 * r.m_foot) * 9.81;
  const auto& s = plant.sensors();
  // Force on the foot from the leg, foot frame (level): z component is minus the load.
  const double carried = -(s.ft[0].force[2] + s.ft[1].force[2]);
  EXPECT_NEAR(carried, above, 0.01 * above);
  // The floor carries the whole robot.
  EXPECT_NEAR(t.normal_force, plant.total_mass() * 9.81, 0.01 * plant.total_mass() * 9.81);
}

// The gears deflect by the gravity torque over their stiffness (spec eqs. 2-3). The torque the
// static pose demands is taken from MuJoCo's own balance (bias force minus contact forces at the
// joint), independent of the actuator code. 2 % (the bound).
TEST(HumanoidPlant, StaticDeflectionIsGravityTorqueOverStiffness) {
  for (double k : {600.0, 1000.0, 2000.0}) {
    HumanoidPlant plant(RobotParams{}, default_plant(k));
    stand(plant, 6.0);
    const mjModel* m = plant.model();
    const mjData* d = plant.data();
    const GroundTruth t = plant.truth();
    for (int side = 0; side < 2; ++side) {
      for (int offset : {1, 2, 3}) {  // hip roll, hip pitch, knee
        const int j = leg_first_joint(side) + offset;
        const int dof = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, std::string(kJointNames[j]).c_str())];
        const double required = d->qfrc_bias[dof] - d->qfrc_constraint[dof];
        const double deflection = t.motor_angle[j] - t.link_angle[j];
        if (std::abs(required) < 1.0) continue;  // hip roll carries almost nothing in a symmetric stance
        EXPECT_NEAR(deflection, required / k, 0.02 * std::abs(required / k)) << kJointNames[j] << ", k = " << k;
      }
    }
    // The knees carry tens of Nm: deflections of a few hundredths of a radian at k = 1000.
    if (k == 1000.0) {
      EXPECT_GT(std::abs(t.motor_angle[kLeftKnee] - t.link_angle[kLeftKnee]), 0.005);
    }
  }
}

TEST(HumanoidPlant, EncodersAreQuantisedExactly) {
  HumanoidPlant plant(RobotParams{}, default_plant());
  stand(plant, 1.0);
  const double q = 2 * std::numbers::pi / plant.params().encoder_steps;
  const GroundTruth t = plant.truth();
  for (int j = 0; j < kJoints; ++j) {
    const double steps = plant.sensors().encoder[j] / q;
    EXPECT_EQ(steps, std::nearbyint(steps)) << kJointNames[j];  // an exact multiple of the step
    EXPECT_LE(std::abs(plant.sensors().encoder[j] - t.motor_angle[j]), 0.5 * q * (1 + 1e-12));
  }
}

TEST(HumanoidPlant, SameInputSameBytes) {
  PlantParams p = default_plant();
  p.ft_force_noise = 0.5;  // noise with a seed is reproducible too
  p.gyro_noise = 0.01;
  HumanoidPlant a(RobotParams{}, p), b(RobotParams{}, p);
  stand(a, 1.0);
  stand(b, 1.0);
  const GroundTruth ta = a.truth(), tb = b.truth();
  EXPECT_EQ(0, std::memcmp(ta.link_angle.data(), tb.link_angle.data(), sizeof(double) * kJoints));
  EXPECT_EQ(0, std::memcmp(&a.sensors().ft, &b.sensors().ft, sizeof(a.sensors().ft)));
  EXPECT_EQ(0, std::memcmp(&a.sensors().imu, &b.sensors().imu, sizeof(a.sensors().imu)));
}

}  // namespace
}  // namespace flexgait::humanoid
