// The twin: mass, standing on its own, gravity deflection of the elastic gears, sensors (the IMU's delta angle,
// the servos' torque from their current), encoder quantisation, determinism.
#include "flexgait/twin/plant.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

#include "flexgait/robot/thormang3_inertials.hpp"
#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"

namespace flexgait::twin {
namespace {

PlantParams default_plant(double k = 1000.0) {
  PlantParams p;
  p.k_joint = k;
  return p;
}

constexpr double kStandHeight = 0.75;  // pelvis height of the nominal pose [m] (spec: walk at 0.75 m)

// Stands for `seconds` with the nominal pose commanded.
HumanoidPlant& stand(HumanoidPlant& plant, double seconds) {
  const humanoid::JointVector pose = standing_pose(humanoid::RobotParams{}, kStandHeight);
  plant.reset(pose);
  const int steps = static_cast<int>(std::lround(seconds / plant.params().control_period));
  for (int i = 0; i < steps; ++i) plant.step(pose);
  return plant;
}

TEST(HumanoidPlant, TotalMassIsTheParameter) {
  humanoid::RobotParams r;
  HumanoidPlant a(r, default_plant());
  EXPECT_NEAR(a.total_mass(), 57.0, 1e-9);
  r.total_mass = 70.0;
  HumanoidPlant b(r, default_plant());
  EXPECT_NEAR(b.total_mass(), 70.0, 1e-9);
}

TEST(HumanoidPlant, StandingPoseReachesTheRequestedHeight) {
  HumanoidPlant plant(humanoid::RobotParams{}, default_plant());
  plant.reset(standing_pose(humanoid::RobotParams{}, kStandHeight));
  // Before any gear deflection, the pelvis sits at the requested height (soles on the floor).
  EXPECT_NEAR(plant.truth().pelvis_pos[2], kStandHeight, 1e-9);
}

TEST(HumanoidPlant, StandsTenSecondsAndTheFeetCarryTheWeight) {
  HumanoidPlant plant(humanoid::RobotParams{}, default_plant());
  stand(plant, 10.0);
  const GroundTruth t = plant.truth();
  EXPECT_GT(t.pelvis_pos[2], 0.6) << "fell";
  EXPECT_FALSE(t.non_sole_contact);
  EXPECT_EQ(t.warnings, 0);
  // The F/T sensors carry everything above them: total mass minus the two feet (1 %).
  const humanoid::RobotParams r;
  const double above = (plant.total_mass() - 2 * humanoid::thormang3_link("l_leg_foot").mass) * 9.81;
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
    HumanoidPlant plant(humanoid::RobotParams{}, default_plant(k));
    stand(plant, 6.0);
    const mjModel* m = plant_model(plant);
    const mjData* d = plant_data(plant);
    const GroundTruth t = plant.truth();
    for (int side = 0; side < 2; ++side) {
      for (int offset : {1, 2, 3}) {  // hip roll, hip pitch, knee
        const int j = humanoid::leg_first_joint(side) + offset;
        const int dof = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, std::string(humanoid::kJointNames[j]).c_str())];
        const double required = d->qfrc_bias[dof] - d->qfrc_constraint[dof];
        const double deflection = t.motor_angle[j] - t.link_angle[j];
        if (std::abs(required) < 1.0) continue;  // hip roll carries almost nothing in a symmetric stance
        EXPECT_NEAR(deflection, required / k, 0.02 * std::abs(required / k))
            << humanoid::kJointNames[j] << ", k = " << k;
      }
    }
    // The knees carry tens of Nm: deflections of a few hundredths of a radian at k = 1000.
    if (k == 1000.0) {
      EXPECT_GT(std::abs(t.motor_angle[humanoid::kLeftKnee] - t.link_angle[humanoid::kLeftKnee]), 0.005);
    }
  }
}

TEST(HumanoidPlant, EncodersAreQuantisedExactly) {
  HumanoidPlant plant(humanoid::RobotParams{}, default_plant());
  stand(plant, 1.0);
  const double q = 2 * std::numbers::pi / plant.params().encoder_steps;
  const GroundTruth t = plant.truth();
  for (int j = 0; j < humanoid::kJoints; ++j) {
    const double steps = plant.sensors().encoder[j] / q;
    EXPECT_EQ(steps, std::nearbyint(steps)) << humanoid::kJointNames[j];  // an exact multiple of the step
    EXPECT_LE(std::abs(plant.sensors().encoder[j] - t.motor_angle[j]), 0.5 * q * (1 + 1e-12));
  }
}

TEST(HumanoidPlant, SameInputSameBytes) {
  PlantParams p = default_plant();
  p.ft_force_noise = 0.5;  // noise with a seed is reproducible too
  p.gyro_noise = 0.01;
  HumanoidPlant a(humanoid::RobotParams{}, p), b(humanoid::RobotParams{}, p);
  stand(a, 1.0);
  stand(b, 1.0);
  const GroundTruth ta = a.truth(), tb = b.truth();
  EXPECT_EQ(0, std::memcmp(ta.link_angle.data(), tb.link_angle.data(), sizeof(double) * humanoid::kJoints));
  EXPECT_EQ(0, std::memcmp(&a.sensors().ft, &b.sensors().ft, sizeof(a.sensors().ft)));
  EXPECT_EQ(0, std::memcmp(&a.sensors().imu, &b.sensors().imu, sizeof(a.sensors().imu)));
}

// A copy of the plant is its whole state: stepped with the same commands as the original, it
// gives the same bytes (MuJoCo's state, motors, sensor noise generator and drifts, faults, pushes).
TEST(HumanoidPlant, ACopyContinuesAsTheOriginal) {
  PlantParams params = default_plant();
  params.ft_force_noise = 2.0;  // the noise generator is part of the state
  params.imu.gyro_bias_walk = 0.01;
  HumanoidPlant a(humanoid::RobotParams{}, params);
  const humanoid::JointVector pose = standing_pose(humanoid::RobotParams{}, kStandHeight);
  a.reset(pose);
  a.set_push(Push{0.3, PushBody::kChest, {30, 0, 0}, 0.4});
  humanoid::JointVector command = pose;
  for (int i = 0; i < 100; ++i) a.step(command);
  HumanoidPlant b = a;
  HumanoidPlant c(humanoid::RobotParams{}, params);
  c = a;
  for (int i = 0; i < 100; ++i) {
    command[humanoid::kLeftKnee] = pose[humanoid::kLeftKnee] + 0.1 * std::sin(0.05 * i);
    a.step(command);
    b.step(command);
    c.step(command);
  }
  for (const HumanoidPlant* copy : {&b, &c}) {
    const GroundTruth ta = a.truth(), tb = copy->truth();
    EXPECT_EQ(ta.link_angle, tb.link_angle);
    EXPECT_EQ(ta.motor_angle, tb.motor_angle);
    EXPECT_EQ(ta.pelvis_pos, tb.pelvis_pos);
    EXPECT_EQ(ta.push_impulse, tb.push_impulse);
    EXPECT_EQ(ta.floor_impulse, tb.floor_impulse);
    EXPECT_EQ(0, std::memcmp(&a.sensors().ft, &copy->sensors().ft, sizeof(a.sensors().ft)));
    EXPECT_EQ(0, std::memcmp(&a.sensors().imu, &copy->sensors().imu, sizeof(a.sensors().imu)));
  }
  EXPECT_EQ(plant_model(a), plant_model(b)) << "copies share the const model";
  EXPECT_NE(plant_data(a), plant_data(b));
}

// The plant steps a control period's substeps before the last with MuJoCo's sensor stage off
// (mjDSBL_SENSOR): its readings are taken once per period, and mj_step evaluates the sensors at the
// start of each substep, so the last one's evaluation is the only one read. That rests on the sensor
// stage writing nothing the dynamics read: four steps of the walking twin (one control period,
// standing, in contact) the first three unsensed agree bit for bit with four sensed ones — the
// state, the solver's warm start and every sensor value.
TEST(HumanoidPlant, SkippingTheSensorStageOfUnreadSubstepsChangesNoBit) {
  HumanoidPlant plant(humanoid::RobotParams{}, default_plant());
  stand(plant, 0.5);
  const int substeps = plant.params().substeps();
  ASSERT_GT(substeps, 1);
  const mjModel* m = plant_model(plant);
  mjModel* unsensed = mj_copyModel(nullptr, m);
  unsensed->opt.disableflags |= mjDSBL_SENSOR;
  mjData* a = mj_copyData(nullptr, m, plant_data(plant));
  mjData* b = mj_copyData(nullptr, m, plant_data(plant));
  for (int k = 0; k < substeps; ++k) {
    mj_step(k + 1 < substeps ? unsensed : m, a);
    mj_step(m, b);
  }
  const auto same = [](const mjtNum* x, const mjtNum* y, int n) {
    return std::memcmp(x, y, sizeof(mjtNum) * static_cast<std::size_t>(n)) == 0;
  };
  EXPECT_GT(a->ncon, 0) << "standing: in contact";
  EXPECT_EQ(a->time, b->time);
  EXPECT_TRUE(same(a->qpos, b->qpos, m->nq));
  EXPECT_TRUE(same(a->qvel, b->qvel, m->nv));
  EXPECT_TRUE(same(a->qacc_warmstart, b->qacc_warmstart, m->nv));
  EXPECT_TRUE(same(a->sensordata, b->sensordata, m->nsensordata));
  mj_deleteData(a);
  mj_deleteData(b);
  mj_deleteModel(unsensed);
}

// The IMU's delta angle (humanoid::Imu::delta_angle) is its frame's turn since the last reading, in that frame: the
// delta angles of a pushed twin, composed, turn the first AHRS attitude (exact: no AHRS noise) into the last, to
// round-off (each is a quaternion's rotation vector; 100 compositions, ~1e-16 rad each). A delta in the world frame
// instead would be off by the pelvis's tilt times the turn (here > 1e-5 rad). A gyro bias b adds b T to each.
TEST(HumanoidPlant, TheDeltaAnglesComposeToTheAttitudesTurn) {
  PlantParams biased = default_plant();
  biased.imu.gyro_bias = 0.002;  // [rad/s]
  HumanoidPlant plant(humanoid::RobotParams{}, default_plant()), with_bias(humanoid::RobotParams{}, biased);
  stand(plant, 0.2);
  stand(with_bias, 0.2);
  const humanoid::JointVector pose = standing_pose(humanoid::RobotParams{}, kStandHeight);
  for (HumanoidPlant* p : {&plant, &with_bias})
    p->set_pushes({Push{.time = 0.2, .body = PushBody::kChest, .force = {60.0, 90.0, 0.0}, .duration = 0.15}});
  const auto matrix = [](const std::array<double, 4>& q) {
    return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  };
  const Eigen::Matrix3d first = matrix(plant.sensors().imu.quat);
  Eigen::Matrix3d composed = first;
  for (int i = 0; i < 100; ++i) {
    humanoid::JointVector command = pose;
    command[humanoid::kLeftHipRoll] += 0.05 * std::sin(0.1 * i);  // (a turn whose axis moves)
    plant.step(command);
    with_bias.step(command);
    const auto& d = plant.sensors().imu.delta_angle;
    const Eigen::Vector3d delta(d[0], d[1], d[2]);
    if (delta.norm() > 0) composed = composed * Eigen::AngleAxisd(delta.norm(), delta.normalized()).toRotationMatrix();
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(with_bias.sensors().imu.delta_angle[a] - d[a], biased.imu.gyro_bias * biased.control_period, 1e-15);
  }
  const Eigen::Matrix3d last = matrix(plant.sensors().imu.quat);
  EXPECT_GT(Eigen::AngleAxisd(Eigen::Matrix3d(first.transpose() * last)).angle(), 0.01) << "the twin turned";
  EXPECT_LT(Eigen::AngleAxisd(Eigen::Matrix3d(composed.transpose() * last)).angle(), 1e-12);
}

// The servos' torque from their current (humanoid::SensorReadings::motor_torque) is their mean over the control
// period: with one physics step per period, the servo torque of that step bit for bit; standing still, the gears'
// torque (the rotors at rest; measured: within 2e-4 Nm after 1 s).
TEST(HumanoidPlant, TheMotorTorqueIsTheServosMeanOverThePeriod) {
  PlantParams single = default_plant();
  single.control_period = single.physics_dt;
  HumanoidPlant one(humanoid::RobotParams{}, single);
  stand(one, 0.1);
  const GroundTruth g = one.truth();
  for (int j = 0; j < humanoid::kJoints; ++j) EXPECT_EQ(one.sensors().motor_torque[j], g.servo_torque[j]);
  HumanoidPlant plant(humanoid::RobotParams{}, default_plant());
  stand(plant, 1.0);
  const GroundTruth still = plant.truth();
  double largest = 0;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    EXPECT_NEAR(plant.sensors().motor_torque[j], still.gear_torque[j], 0.01) << humanoid::kJointNames[j];
    largest = std::max(largest, std::abs(still.gear_torque[j]));
  }
  EXPECT_GT(largest, 20.0) << "the legs carry the weight";
}

// Placed exactly on the floor, a sole's distance is a rounding residue of either sign, and MuJoCo's
// contact exists only below zero: some poses would start in free fall. reset() puts the lower sole 1 nm
// into the floor, so every standing pose starts with the floor pushing on both soles. 81 pelvis heights
// over 0.1 m: their residues take both signs (with the sole exactly on the floor, 44 of them start
// without contact, the nominal 0.75 m among them).
TEST(HumanoidPlant, ResetStartsEveryPoseOnTheFloor) {
  HumanoidPlant plant(humanoid::RobotParams{}, default_plant());
  for (int i = 0; i <= 80; ++i) {
    const double height = 0.70 + 0.00125 * i;
    plant.reset(standing_pose(humanoid::RobotParams{}, height));
    const GroundTruth t = plant.truth();
    EXPECT_TRUE(t.sole_contact[0] && t.sole_contact[1]) << "pelvis height " << height;
    EXPECT_GT(t.normal_force, 0.0) << "pelvis height " << height;
    EXPECT_NEAR(t.pelvis_pos[2], height, 2e-9) << "1 nm into the floor, not more";
  }
}

// reset() depends on the pose only: what the plant did before leaves no trace (the gear springs
// are forces of the drives' state, not a reference stored in the model), so the first readings
// after a reset are the same bytes whatever came before.
TEST(HumanoidPlant, ResetDependsOnThePoseOnly) {
  const humanoid::JointVector pose = standing_pose(humanoid::RobotParams{}, kStandHeight);
  HumanoidPlant fresh(humanoid::RobotParams{}, default_plant());
  fresh.reset(pose);
  HumanoidPlant used(humanoid::RobotParams{}, default_plant());
  used.reset(standing_pose(humanoid::RobotParams{}, 0.70));
  for (int i = 0; i < 50; ++i) used.step(standing_pose(humanoid::RobotParams{}, 0.72));
  used.reset(pose);
  const mjData* a = plant_data(fresh);
  const mjData* b = plant_data(used);
  const int n = plant_model(fresh)->nsensordata;
  EXPECT_EQ(0, std::memcmp(a->sensordata, b->sensordata, sizeof(mjtNum) * static_cast<std::size_t>(n)));
  EXPECT_EQ(0, std::memcmp(a->qacc, b->qacc, sizeof(mjtNum) * static_cast<std::size_t>(plant_model(fresh)->nv)));
  // At rest with no deflection, the gears carry no torque: the legs' joints have no spring force.
  for (int j = 0; j < humanoid::kJoints; ++j) EXPECT_EQ(fresh.truth().gear_torque[j], 0.0) << humanoid::kJointNames[j];
}

}  // namespace
}  // namespace flexgait::twin
