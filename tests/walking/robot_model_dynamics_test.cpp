// Recursive Newton–Euler of the controller's model against MuJoCo's mj_rne (an independent
// implementation, in a different formulation: spatial algebra at the subtree COM) on the same
// pose, velocity and acceleration of the floating pelvis and every joint: the builtin robot (its
// model written as MJCF, point masses and with inertias) and the loaded test robot
// tests/humanoid/data/small_biped.xml (MuJoCo reads the file itself). At rest it is the legs'
// gravity torque, and with the ground's force given at the feet it is the full form of τ_g.
// The analytic derivatives ∂τ/∂q (inverse_dynamics_derivative, compensation::gravity_torque_derivative)
// against central differences, on the builtin robot and on loaded test robots whose legs have other joint
// orders and −y axes.
#include "flexgait/walking/robot_model_dynamics.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "flexgait/compensation/gravity_torque.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"

namespace flexgait::walking {
namespace {

using humanoid::JointVector;
using humanoid::kJoints;

// mj_rne and this RNE differ only by rounding: 1e-9 of the largest generalized force is the
// issue's bound (the forces are O(10-1000); double rounding leaves ~1e-13 relative).
constexpr double kRelative = 1e-9;

/// The model as MJCF: each body at its offset (frames parallel to the pelvis at zero angles), its
/// hinge at the origin, its inertial as given. Point masses get MuJoCo's smallest inertia bound
/// (1e-14 kg m², which moves a torque by < 1e-12 Nm here).
std::string mjcf_of(const RobotModel& model) {
  std::function<std::string(int)> body = [&](int i) {
    const auto& b = model.bodies[i];
    std::string s =
        fmt::format("<body name=\"b{}\" pos=\"{:.17g} {:.17g} {:.17g}\">", i, b.offset.x(), b.offset.y(), b.offset.z());
    if (i == 0)
      s += "<freejoint name=\"root\"/>";
    else if (b.joint >= 0)
      s += fmt::format("<joint name=\"j{}\" axis=\"{:.17g} {:.17g} {:.17g}\"/>", b.joint, b.axis.x(), b.axis.y(),
                       b.axis.z());
    const Matrix3d& I = b.inertia;
    s += fmt::format("<inertial pos=\"{:.17g} {:.17g} {:.17g}\" mass=\"{:.17g}\" ", b.com.x(), b.com.y(), b.com.z(),
                     b.mass);
    s += I.isZero() ? std::string("diaginertia=\"0 0 0\"/>")
                    : fmt::format("fullinertia=\"{:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\"/>", I(0, 0), I(1, 1),
                                  I(2, 2), I(0, 1), I(0, 2), I(1, 2));
    for (int k = i + 1; k < kBodies; ++k)
      if (model.bodies[k].parent == i) s += body(k);
    return s + "</body>";
  };
  return "<mujoco><compiler angle=\"radian\" boundinertia=\"1e-14\"/><option gravity=\"0 0 -9.81\"/><worldbody>" +
         body(0) + "</worldbody></mujoco>";
}

/// A MuJoCo model and which of its joints each flexgait joint is.
struct Reference {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  std::array<int, kJoints> joint{};
  Reference(mjModel* model, const std::function<std::string(int)>& name) : m(model), d(mj_makeData(model)) {
    for (int j = 0; j < kJoints; ++j) {
      joint[j] = mj_name2id(m, mjOBJ_JOINT, name(j).c_str());
      EXPECT_GE(joint[j], 0) << name(j);
    }
  }
  ~Reference() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  Reference(const Reference&) = delete;
  Reference& operator=(const Reference&) = delete;
};

/// Compares this RNE with mj_rne on random states; returns the largest relative difference.
double compare_with_mj_rne(const RobotModel& model, Reference& ref, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Pose pelvis{Vector3d(u(rng), u(rng), 0.7 + 0.1 * u(rng)),
                Eigen::Quaterniond(1, 0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)).normalized().toRotationMatrix()};
    JointVector q{}, qd{}, qdd{};
    for (int j = 0; j < kJoints; ++j) q[j] = 0.6 * u(rng), qd[j] = 3 * u(rng), qdd[j] = 30 * u(rng);
    BaseMotion base;
    Eigen::Matrix<double, 6, 1> base_qvel, base_qacc;
    for (int i = 0; i < 6; ++i) base_qvel(i) = u(rng), base_qacc(i) = 5 * u(rng);
    // MuJoCo's free joint: linear velocity of the body origin in the world, angular in the body frame.
    base.velocity = base_qvel.head<3>();
    base.angular_velocity = pelvis.R * base_qvel.tail<3>();
    base.acceleration = base_qacc.head<3>();
    base.angular_acceleration = pelvis.R * base_qacc.tail<3>();

    mj_resetData(ref.m, ref.d);
    for (int i = 0; i < 3; ++i) ref.d->qpos[i] = pelvis.p(i);
    const Eigen::Quaterniond quat(pelvis.R);
    ref.d->qpos[3] = quat.w(), ref.d->qpos[4] = quat.x(), ref.d->qpos[5] = quat.y(), ref.d->qpos[6] = quat.z();
    for (int i = 0; i < 6; ++i) ref.d->qvel[i] = base_qvel(i);
    for (int j = 0; j < kJoints; ++j) {
      ref.d->qpos[ref.m->jnt_qposadr[ref.joint[j]]] = q[j];
      ref.d->qvel[ref.m->jnt_dofadr[ref.joint[j]]] = qd[j];
    }
    mj_forward(ref.m, ref.d);
    for (int i = 0; i < 6; ++i) ref.d->qacc[i] = base_qacc(i);
    for (int j = 0; j < kJoints; ++j) ref.d->qacc[ref.m->jnt_dofadr[ref.joint[j]]] = qdd[j];
    std::vector<mjtNum> expected(static_cast<std::size_t>(ref.m->nv));
    mj_rne(ref.m, ref.d, 1, expected.data());

    RobotModelData kin;
    forward_kinematics(model, kin, pelvis, q);
    RobotDynamicsData dyn;
    inverse_dynamics(model, kin, base, qd, qdd, dyn);
    Eigen::Matrix<double, 6 + kJoints, 1> ours, theirs;
    ours.head<3>() = dyn.joint_wrench[0].force;
    ours.segment<3>(3) = pelvis.R.transpose() * dyn.joint_wrench[0].moment;  // about the pelvis origin, body frame
    for (int i = 0; i < 6; ++i) theirs(i) = expected[static_cast<std::size_t>(i)];
    for (int j = 0; j < kJoints; ++j) {
      ours(6 + j) = dyn.tau[j];
      theirs(6 + j) = expected[static_cast<std::size_t>(ref.m->jnt_dofadr[ref.joint[j]])];
    }
    const double scale = theirs.lpNorm<Eigen::Infinity>();
    worst = std::max(worst, (ours - theirs).lpNorm<Eigen::Infinity>() / scale);
    EXPECT_LE((ours - theirs).lpNorm<Eigen::Infinity>(), kRelative * scale)
        << "trial " << trial << "\nours   " << ours.transpose() << "\ntheirs " << theirs.transpose();
  }
  return worst;
}

RobotModel builtin() {
  return make_robot_model(humanoid::RobotParams{});
}

/// MuJoCo stores a full inertia as its principal moments and axes (an iterative eigensolver, good
/// to ~1e-9 relative): the model's inertias set to the ones MuJoCo simulates.
void use_simulated_inertias(RobotModel& model, const Reference& ref) {
  for (int i = 0; i < kBodies; ++i) {
    const int id = mj_name2id(ref.m, mjOBJ_BODY, fmt::format("b{}", i).c_str());
    const mjtNum* q = ref.m->body_iquat + 4 * id;
    const Matrix3d R = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
    model.bodies[i].inertia = R * Vector3d(ref.m->body_inertia + 3 * id).asDiagonal() * R.transpose();
  }
}

/// Joint angles uniform in ±amplitude [rad].
JointVector random_angles(unsigned seed, double amplitude) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  JointVector q{};
  for (double& v : q) v = u(rng);
  return q;
}

TEST(RobotModelDynamics, BuiltinRobotMatchesMjRne) {
  RobotModel model = builtin();  // THORMANG3's inertias (builtin_inertials.hpp)
  Reference ref(twin::load_mjcf(mjcf_of(model)), [](int j) { return fmt::format("j{}", j); });
  use_simulated_inertias(model, ref);
  RecordProperty("relative_difference", std::to_string(compare_with_mj_rne(model, ref, 1)));
}

TEST(RobotModelDynamics, BuiltinRobotWithInertiasMatchesMjRne) {
  RobotModel model = builtin();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto& b : model.bodies) {  // a box of random sides (0.05-0.35 m) at a random attitude: a physical inertia
    const Vector3d side = Vector3d(0.2, 0.2, 0.2) + 0.15 * Vector3d(u(rng), u(rng), u(rng));
    const Vector3d s2 = side.cwiseProduct(side);
    const Vector3d diagonal = b.mass / 12 * Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
    const Matrix3d R = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    b.inertia = R * diagonal.asDiagonal() * R.transpose();
  }
  Reference ref(twin::load_mjcf(mjcf_of(model)), [](int j) { return fmt::format("j{}", j); });
  use_simulated_inertias(model, ref);
  RecordProperty("relative_difference", std::to_string(compare_with_mj_rne(model, ref, 2)));
}

TEST(RobotModelDynamics, LoadedRobotMatchesMjRneOnItsOwnFile) {
  const char* dir = std::getenv("FLEXGAIT_TEST_DATA");
  const std::filesystem::path data = dir ? dir : "tests/humanoid/data";
  const experiments::WalkRunParams w =
      experiments::walk_run_from_config(resolve_config(experiments::walk_run_schema(), data / "small_biped.yaml", {}));
  const RobotModel model = experiments::walk_controller_model(w);
  char error[1000] = "";
  mjModel* m = mj_loadXML((data / "small_biped.xml").string().c_str(), nullptr, error, sizeof error);
  ASSERT_NE(m, nullptr) << error;
  Reference ref(m, [&](int j) { return w.description.joints[static_cast<std::size_t>(j)]; });
  RecordProperty("relative_difference", std::to_string(compare_with_mj_rne(model, ref, 3)));
}

TEST(RobotModelDynamics, AtRestTheLegTorquesAreTheirGravityTorques) {
  const RobotModel model = builtin();
  const JointVector q = random_angles(4, 0.6);
  RobotModelData kin;
  forward_kinematics(model, kin,
                     Pose{Vector3d(0, 0, 0.7), Matrix3d(Eigen::AngleAxisd(0.2, Vector3d(1, 2, 0).normalized()))}, q);
  RobotDynamicsData dyn;
  inverse_dynamics(model, kin, BaseMotion{}, JointVector{}, JointVector{}, dyn);
  for (int side = 0; side < 2; ++side) {
    const LegTorque g = leg_gravity_torque(model, kin, side);
    for (int i = 0; i < humanoid::kLegJoints; ++i)
      EXPECT_NEAR(dyn.tau[humanoid::leg_first_joint(side) + i], g(i),
                  1e-12 * model.total_mass * humanoid::kDefaultGravity);  // rounding
  }
}

TEST(RobotModelDynamics, WithTheGroundForceGivenAtTheFeetItIsTheFullGravityTorque) {
  const RobotModel model = builtin();
  const JointVector q = random_angles(5, 0.4);
  RobotModelData kin;
  forward_kinematics(model, kin, Pose{Vector3d(0, 0, 0.7), Matrix3d::Identity()}, q);
  compensation::FootLoads loads;
  loads.share = {0.3, 0.7};
  loads.cop = {Eigen::Vector2d(0.02, -0.01), Eigen::Vector2d(-0.03, 0.015)};
  const JointVector expected = compensation::gravity_torque(model, kin, loads, compensation::GravityForm::kFull);
  // The leg's wrench on each foot: the foot's weight held up less the ground's push at its CoP.
  FootWrenches feet;
  for (int side = 0; side < 2; ++side) {
    const Pose& foot = kin.frame[model.foot[side]];
    const Pose sole = sole_pose(model, kin, side);
    const Vector3d cop = sole.p + sole.R * Vector3d(loads.cop[side].x(), loads.cop[side].y(), 0);
    const Vector3d ground(0, 0, loads.share[side] * model.total_mass * humanoid::kDefaultGravity);
    const auto& b = model.bodies[model.foot[side]];
    const Vector3d weight(0, 0, -b.mass * humanoid::kDefaultGravity);
    feet.given[side] = true;
    feet.wrench[side].force = -weight - ground;
    feet.wrench[side].moment = -(foot.R * b.com).cross(weight) - (cop - foot.p).cross(ground);
  }
  RobotDynamicsData dyn;
  inverse_dynamics(model, kin, BaseMotion{}, JointVector{}, JointVector{}, dyn, feet);
  for (int j = humanoid::kLeftHipYaw; j < kJoints; ++j)
    EXPECT_NEAR(dyn.tau[j], expected[j], 1e-10) << j;  // rounding on O(100) Nm
}

// ---- ∂τ/∂q against central differences ----

/// The robots the derivatives are checked on: the builtin and loaded test robots (hips pitch-roll-yaw
/// from the pelvis; knees and ankles about −y).
std::vector<std::pair<std::string, RobotModel>> derivative_robots() {
  const char* dir = std::getenv("FLEXGAIT_TEST_DATA");
  const std::filesystem::path data = dir ? dir : "tests/humanoid/data";
  std::vector<std::pair<std::string, RobotModel>> out{{"builtin", builtin()}};
  for (const char* name : {"pitch_roll_yaw_hips.yaml", "minus_y_knee.yaml"}) {
    const experiments::WalkRunParams w =
        experiments::walk_run_from_config(resolve_config(experiments::walk_run_schema(), data / name, {}));
    out.emplace_back(name, experiments::walk_controller_model(w));
  }
  return out;
}

/// Central differences of one leg's six torques in its six joints (role order), step h.
LegTorqueDerivative central_difference(const JointVector& q, int side, double h,
                                       const std::function<JointVector(const JointVector&)>& torque) {
  LegTorqueDerivative G;
  const int first = humanoid::leg_first_joint(side);
  for (int c = 0; c < humanoid::kLegJoints; ++c) {
    JointVector plus = q, minus = q;
    plus[first + c] += h;
    minus[first + c] -= h;
    const JointVector tp = torque(plus), tm = torque(minus);
    for (int r = 0; r < humanoid::kLegJoints; ++r) G(r, c) = (tp[first + r] - tm[first + r]) / (2 * h);
  }
  return G;
}

// Central differences with h = 1e-5 rad: truncation h^2 |tau'''| / 6 ~ 1e-11 of G's scale (tau''' ~ tau),
// rounding eps |tau| / h ~ 1e-10 of it (|tau| within 10 |G| here); 1e-7 of the largest entry is the bound.
constexpr double kStep = 1e-5, kDerivativeRelative = 1e-7;

void expect_derivative_near(const LegTorqueDerivative& analytic, const LegTorqueDerivative& numeric,
                            const std::string& what) {
  const double scale = numeric.lpNorm<Eigen::Infinity>();
  ASSERT_GT(scale, 1.0) << what;  // a derivative of O(10-100) Nm/rad is checked, not zeros
  EXPECT_LE((analytic - numeric).lpNorm<Eigen::Infinity>(), kDerivativeRelative * scale)
      << what << "\nanalytic\n"
      << analytic << "\ncentral differences\n"
      << numeric;
}

TEST(RobotModelDynamics, InverseDynamicsDerivativeMatchesCentralDifferences) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto& [name, model] : derivative_robots())
    for (int trial = 0; trial < 4; ++trial) {
      const Pose pelvis{
          Vector3d(u(rng), u(rng), 0.7),
          Eigen::Quaterniond(1, 0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)).normalized().toRotationMatrix()};
      const BaseMotion base{Vector3d(u(rng), u(rng), u(rng)), Vector3d(u(rng), u(rng), u(rng)),
                            5 * Vector3d(u(rng), u(rng), u(rng)), 5 * Vector3d(u(rng), u(rng), u(rng))};
      JointVector q{}, qd{}, qdd{};
      for (int j = 0; j < kJoints; ++j) q[j] = 0.6 * u(rng), qd[j] = 3 * u(rng), qdd[j] = 30 * u(rng);
      // The left foot's wrench is a reading fixed in the foot (it turns with it); the right foot's is computed.
      const Wrench reading{Vector3d(20 * u(rng), 20 * u(rng), 300 + 50 * u(rng)),
                           Vector3d(10 * u(rng), 10 * u(rng), 2 * u(rng))};
      auto evaluate = [&](const JointVector& angles, RobotModelData& kin, RobotDynamicsData& dyn, FootWrenches& feet) {
        forward_kinematics(model, kin, pelvis, angles);
        const Matrix3d& R = kin.frame[model.foot[0]].R;
        feet.given = {true, false};
        feet.wrench[0] = {R * reading.force, R * reading.moment};
        inverse_dynamics(model, kin, base, qd, qdd, dyn, feet);
      };
      RobotModelData kin;
      RobotDynamicsData dyn;
      FootWrenches feet;
      evaluate(q, kin, dyn, feet);
      for (int side = 0; side < 2; ++side) {
        const LegTorqueDerivative G = inverse_dynamics_derivative(model, kin, dyn, feet, side);
        const LegTorqueDerivative numeric = central_difference(q, side, kStep, [&](const JointVector& angles) {
          RobotModelData k;
          RobotDynamicsData d;
          FootWrenches f;
          evaluate(angles, k, d, f);
          return d.tau;
        });
        expect_derivative_near(G, numeric, name + " trial " + std::to_string(trial) + " side " + std::to_string(side));
      }
    }
}

/// A random floating pelvis pose and motion and joint angles, rates and accelerations.
struct RandomMotion {
  Pose pelvis;
  BaseMotion base;
  JointVector q{}, qd{}, qdd{};
};
RandomMotion random_motion(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  RandomMotion m;
  m.pelvis = {Vector3d(u(rng), u(rng), 0.7),
              Eigen::Quaterniond(1, 0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)).normalized().toRotationMatrix()};
  m.base = {Vector3d(u(rng), u(rng), u(rng)), Vector3d(u(rng), u(rng), u(rng)), 5 * Vector3d(u(rng), u(rng), u(rng)),
            5 * Vector3d(u(rng), u(rng), u(rng))};
  for (int j = 0; j < kJoints; ++j) m.q[j] = 0.6 * u(rng), m.qd[j] = 3 * u(rng), m.qdd[j] = 30 * u(rng);
  return m;
}

// The backward pass alone with other feet after a full pass (the input compensator's plan Newton–Euler, then its
// feet) is the full pass with those feet: the same operations on the same numbers, so equal in every bit (==).
TEST(RobotModelDynamics, BackwardPassWithOtherFeetIsTheFullPass) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto& [name, model] : derivative_robots()) {
    const auto [pelvis, base, q, qd, qdd] = random_motion(rng);
    RobotModelData kin;
    forward_kinematics(model, kin, pelvis, q);
    FootWrenches feet;
    feet.given = {true, true};
    for (Wrench& w : feet.wrench) w = {Vector3d(20 * u(rng), 20 * u(rng), 300), Vector3d(10 * u(rng), 10 * u(rng), 2)};
    RobotDynamicsData full, split;
    inverse_dynamics(model, kin, base, qd, qdd, full, feet);
    inverse_dynamics(model, kin, base, qd, qdd, split);  // no foot given
    const JointVector free_feet = split.tau;
    inverse_dynamics_with_feet(model, kin, split, feet);
    for (int j = 0; j < kJoints; ++j) EXPECT_EQ(split.tau[j], full.tau[j]) << name << " joint " << j;
    for (int i = 0; i < kBodies; ++i) {
      EXPECT_EQ(split.joint_wrench[i].force, full.joint_wrench[i].force) << name << " body " << i;
      EXPECT_EQ(split.joint_wrench[i].moment, full.joint_wrench[i].moment) << name << " body " << i;
    }
    EXPECT_NE(free_feet, full.tau) << name;  // the feet's wrenches changed the torques: the case is not empty
  }
}

// After a whole pass, a change of the legs' angles alone recomputed from the first leg body on (the output
// compensator's Newton iterates) is the whole pass at the new angles: the same operations on the same numbers (==).
TEST(RobotModelDynamics, LegsAloneAfterAWholePassAreTheWholePass) {
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto& [name, model] : derivative_robots()) {
    const auto [pelvis, base, q, qd, qdd] = random_motion(rng);
    FootWrenches feet;
    feet.given = {true, false};
    feet.wrench[0] = {Vector3d(20 * u(rng), 20 * u(rng), 300), Vector3d(10 * u(rng), 10 * u(rng), 2)};
    RobotModelData kin;
    RobotDynamicsData legs;
    forward_kinematics(model, kin, pelvis, q);
    inverse_dynamics(model, kin, base, qd, qdd, legs, feet);
    JointVector moved = q;
    for (int j = 0; j < kJoints; ++j)
      if (j != humanoid::kWaistYaw) moved[j] += 0.1 * u(rng);
    forward_kinematics(model, kin, pelvis, moved, kFirstLegBody);
    inverse_dynamics(model, kin, base, qd, qdd, legs, feet, 1.0, kFirstLegBody);
    RobotModelData kin_whole;
    RobotDynamicsData whole;
    forward_kinematics(model, kin_whole, pelvis, moved);
    inverse_dynamics(model, kin_whole, base, qd, qdd, whole, feet);
    for (int j = 0; j < kJoints; ++j) EXPECT_EQ(legs.tau[j], whole.tau[j]) << name << " joint " << j;
    for (int i = kFirstLegBody; i < kBodies; ++i) {
      EXPECT_EQ(kin.frame[i].p, kin_whole.frame[i].p) << name << " body " << i;
      EXPECT_EQ(kin.frame[i].R, kin_whole.frame[i].R) << name << " body " << i;
      EXPECT_EQ(legs.joint_wrench[i].moment, whole.joint_wrench[i].moment) << name << " body " << i;
    }
  }
}

TEST(RobotModelDynamics, GravityTorqueDerivativeMatchesCentralDifferencesAndIsSymmetric) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto& [name, model] : derivative_robots())
    for (const auto form : {compensation::GravityForm::kFull, compensation::GravityForm::kThesis})
      for (int trial = 0; trial < 4; ++trial) {
        const Pose pelvis{
            Vector3d::Zero(),
            Eigen::Quaterniond(1, 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng)).normalized().toRotationMatrix()};
        JointVector q{};
        for (int j = 0; j < kJoints; ++j) q[j] = 0.6 * u(rng);
        compensation::FootLoads loads;
        const double left = 0.5 + 0.5 * u(rng);
        loads.share = {left, 1 - left};
        loads.cop = {Eigen::Vector2d(0.05 * u(rng), 0.03 * u(rng)), Eigen::Vector2d(0.05 * u(rng), 0.03 * u(rng))};
        auto torque = [&](const JointVector& angles) {
          RobotModelData k;
          forward_kinematics(model, k, pelvis, angles);
          return compensation::gravity_torque(model, k, loads, form);
        };
        RobotModelData kin;
        forward_kinematics(model, kin, pelvis, q);
        for (int side = 0; side < 2; ++side) {
          const LegTorqueDerivative G = compensation::gravity_torque_derivative(model, kin, loads, form, side);
          const std::string what = name + " " + std::string(name_of(form)) + " trial " + std::to_string(trial);
          expect_derivative_near(G, central_difference(q, side, kStep, torque), what);
          // The Hessian of the loads' potential: symmetric up to rounding.
          EXPECT_LE((G - G.transpose()).lpNorm<Eigen::Infinity>(), 1e-12 * G.lpNorm<Eigen::Infinity>()) << what;
        }
      }
}

TEST(RobotModelDynamics, AtRestTheTwoDerivativesAgree) {
  // A leg at rest with nothing given at its foot: the inverse dynamics' derivative is the closed form of the
  // legs' weight.
  for (const auto& [name, model] : derivative_robots()) {
    const JointVector q = random_angles(6, 0.5);
    RobotModelData kin;
    forward_kinematics(model, kin, Pose{Vector3d::Zero(), Matrix3d(Eigen::AngleAxisd(0.1, Vector3d::UnitX()))}, q);
    RobotDynamicsData dyn;
    inverse_dynamics(model, kin, BaseMotion{}, JointVector{}, JointVector{}, dyn);
    compensation::FootLoads none;
    none.share = {0, 0};
    for (int side = 0; side < 2; ++side) {
      const LegTorqueDerivative a = inverse_dynamics_derivative(model, kin, dyn, {}, side);
      const LegTorqueDerivative b =
          compensation::gravity_torque_derivative(model, kin, none, compensation::GravityForm::kFull, side);
      EXPECT_LE((a - b).lpNorm<Eigen::Infinity>(), 1e-12 * b.lpNorm<Eigen::Infinity>())  // rounding
          << name << " side " << side;
    }
  }
}

}  // namespace
}  // namespace flexgait::walking
