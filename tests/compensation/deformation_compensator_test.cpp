// The deformation compensator (compensation/deformation_compensator.hpp; its gear damping, loads,
// field baselines and the twin's statics have test files of their own). The output compensator
// (spec eqs. 10-13): Newton's method recovers the link angles that the
// encoders imply through the deformation model to 1e-12 rad in at most 5 iterations (8 with G
// reused, the default), on the single-joint bench (τ_g = −m g l cos θ) and on both legs; the one-step form (12) is
// second order in the deflection; a bounded, non-converged solve says so and falls back; and the compensators allocate
// nothing.
#include "flexgait/compensation/deformation_compensator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include "../support/count_allocations.hpp"

using flexgait::testing::g_allocations;

namespace flexgait::compensation {
namespace {

using walking::Matrix3d;
using walking::Pose;
using walking::Vector3d;

// The solver's own convergence is tested to rounding: 1e-12 rad, not the default's 1e-9 (a ten-thousandth of an
// encoder count, enough for the robot, too loose to tell the methods apart).
constexpr double kTightTolerance = 1e-12;
constexpr NewtonSettings kNewton{.tolerance = kTightTolerance, .jacobian = NewtonJacobian::kEachIteration};

// K + G block diagonal (each leg's torques on its own joints): the factors of the two blocks, put together, solve
// as the whole matrix's partial-pivoting LU does, in every bit (==), and as Eigen's own solve.
TEST(LinkAngleNewton, TwoBlockFactorSolvesAsTheWhole) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  using M = Eigen::Matrix<double, 12, 12>;
  using V = Eigen::Matrix<double, 12, 1>;
  for (int trial = 0; trial < 20; ++trial) {
    M A = M::Zero();
    for (int b = 0; b < 2; ++b)
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) A(6 * b + i, 6 * b + j) = (i == j ? 1000.0 : 0.0) + 300 * u(rng);
    V rhs;
    for (int i = 0; i < 12; ++i) rhs(i) = u(rng);
    LinkAngleFactor<12> whole, blocks;
    whole.compute(A, false);
    blocks.compute(A, true);
    const V x = whole.solve(rhs), y = blocks.solve(rhs), eigen = Eigen::PartialPivLU<M>(A).solve(rhs);
    for (int i = 0; i < 12; ++i) {
      EXPECT_EQ(y(i), x(i)) << "trial " << trial << " row " << i;
      EXPECT_EQ(x(i), eigen(i)) << "trial " << trial << " row " << i;
    }
  }
}

TEST(LinkAngleNewton, SolvesTheBenchToMachinePrecisionInAtMostFiveIterations) {
  // The thesis's bench: a 13.6 kg load on a 0.3 m arm (±40 Nm), k = 1000 Nm/rad; the gear
  // carries τ_g = −m g l cos θ (θ from horizontal, positive down), so θ_enc = θ + τ_g(θ)/k.
  const double w = 13.6 * 9.81 * 0.3, k = 1000.0;
  using V = Eigen::Matrix<double, 1, 1>;
  auto torque = [&](const V& q, V& tau) { tau(0) = -w * std::cos(q(0)); };
  auto jacobian = [&](const V& q, const V&, Eigen::Matrix<double, 1, 1>& G) { G(0, 0) = w * std::sin(q(0)); };
  for (double link = 0.0; link <= M_PI; link += M_PI / 40) {
    const V encoder = V::Constant(link - w * std::cos(link) / k);
    const LinkAngleEstimate<1> e = solve_link_angles<1>(encoder, V::Constant(k), torque, jacobian, kNewton);
    ASSERT_TRUE(e.converged) << link;
    EXPECT_LE(e.iterations, 5);
    EXPECT_LE(e.residual, 1e-12);
    EXPECT_NEAR(e.newton(0), link, 1e-12);
    // The one-step form (12) is Newton's first step: its error is second order in the
    // deflection e0, |e1| <= max|τ''| e0² / (2 min(k + G)) with |τ''| <= w, |G| <= w.
    const double e0 = std::abs(encoder(0) - link);
    EXPECT_LE(std::abs(e.one_step(0) - link), w * e0 * e0 / (2 * (k - w)) + 1e-15) << link;
    // One joint: the per-joint form is the one-step form (the same formula, other rounding).
    EXPECT_NEAR(e.per_joint(0), e.one_step(0), 1e-15) << link;
  }
}

// The per-joint form (the thesis's Fig. 15) is eq. 12 with G's diagonal alone, by hand on two
// coupled joints (τ = A sin θ with a full A): θ_enc,j − τ_j(θ_enc) / (k_j + G_jj(θ_enc)), and it
// differs from the coupled one-step form where G's off-diagonal terms act.
TEST(LinkAngleNewton, PerJointFormIsEquationTwelveWithTheDiagonalAlone) {
  using V = Eigen::Vector2d;
  Eigen::Matrix2d A;
  A << 40.0, 25.0, -15.0, 30.0;  // [Nm]
  auto torque = [&](const V& q, V& tau) { tau = A * q.array().sin().matrix(); };
  auto jacobian = [&](const V& q, const V&, Eigen::Matrix2d& G) { G = A * q.array().cos().matrix().asDiagonal(); };
  const V encoder(0.3, -0.2), k(800.0, 1200.0);
  const LinkAngleEstimate<2> e = solve_link_angles<2>(encoder, k, torque, jacobian, {.tolerance = kTightTolerance});
  ASSERT_TRUE(e.converged);
  V tau;
  torque(encoder, tau);
  for (int j = 0; j < 2; ++j) {
    const double by_hand = encoder(j) - tau(j) / (k(j) + A(j, j) * std::cos(encoder(j)));
    EXPECT_NEAR(e.per_joint(j), by_hand, 1e-15) << j;
    EXPECT_GT(std::abs(e.per_joint(j) - e.one_step(j)), 1e-5) << j;  // the coupling is real here
  }
}

// The chord method (G reused while a step cuts the residual a hundredfold) reaches Newton's
// solution to the tolerance with fewer G: on two coupled joints (τ = A sin θ) at the legs' size
// of deflection (k ≈ 1000 Nm/rad, ~0.01 rad) one G serves; at 3 % of the stiffness (~0.3 rad,
// where ΔG/(K + G) is ~1000× larger) the refresh forms G again and it still converges.
TEST(LinkAngleNewton, ReusedJacobianReachesNewtonsSolutionWithFewerJacobians) {
  using V = Eigen::Vector2d;
  Eigen::Matrix2d A;
  A << 40.0, 25.0, -15.0, 30.0;  // [Nm]
  auto torque = [&](const V& q, V& tau) { tau = A * q.array().sin().matrix(); };
  for (const double scale : {1.0, 0.03}) {
    const V k = scale * V(800.0, 1200.0), link(0.3, -0.2);
    V tau;
    torque(link, tau);
    const V encoder = link + tau.cwiseQuotient(k);  // θ_enc = θ + τ(θ)/k
    int formed[2] = {0, 0};
    LinkAngleEstimate<2> e[2];
    for (int m = 0; m < 2; ++m) {
      auto jacobian = [&](const V& q, const V&, Eigen::Matrix2d& G) {
        ++formed[m];
        G = A * q.array().cos().matrix().asDiagonal();
      };
      NewtonSettings settings{.tolerance = kTightTolerance};
      settings.jacobian = m == 0 ? NewtonJacobian::kEachIteration : NewtonJacobian::kReused;
      e[m] = solve_link_angles<2>(encoder, k, torque, jacobian, settings);
      ASSERT_TRUE(e[m].converged) << scale << " " << m;
      EXPECT_LE(e[m].residual, 1e-12);
      EXPECT_LE((e[m].newton - link).lpNorm<Eigen::Infinity>(), 1e-11) << scale << " " << m;
    }
    EXPECT_LT(formed[1], formed[0]) << scale;
    if (scale == 1.0) {
      EXPECT_EQ(formed[1], 1);
    } else {
      EXPECT_GT(formed[1], 1);
    }
    // The diagnostic forms use the G at θ_enc in both.
    EXPECT_EQ(e[1].one_step, e[0].one_step);
    EXPECT_EQ(e[1].per_joint, e[0].per_joint);
  }
}

/// kKept carries the factorisation of K + G from one solve to the next, as the control loop's periods follow one
/// another: along a slowly moving sequence of link angles it reaches the same solutions (1e-11, the tolerance's
/// order) forming G far less often than kReused's once per solve; the one-step and per-joint forms, when asked for,
/// are kReused's bit for bit (G at θ_enc), and asking for them changes no bit of Newton's iterates.
TEST(LinkAngleNewton, KeptFactorCarriesAcrossSolvesAndTheFormsChangeNoIterate) {
  using V = Eigen::Vector2d;
  Eigen::Matrix2d A;
  A << 40.0, 25.0, -15.0, 30.0;  // [Nm]
  auto torque = [&](const V& q, V& tau) { tau = A * q.array().sin().matrix(); };
  const V k(800.0, 1200.0);
  int formed[3] = {0, 0, 0};
  LinkAngleFactor<2> kept[2];  // kKept without and with the forms
  for (int n = 0; n < 200; ++n) {
    const double t = 0.004 * n;  // a 4 ms period
    const V link(0.3 + 0.2 * std::sin(2 * t), -0.2 + 0.1 * std::cos(3 * t));
    V tau;
    torque(link, tau);
    const V encoder = link + tau.cwiseQuotient(k);
    LinkAngleEstimate<2> e[3];
    for (int m = 0; m < 3; ++m) {
      auto jacobian = [&](const V& q, const V&, Eigen::Matrix2d& G) {
        ++formed[m];
        G = A * q.array().cos().matrix().asDiagonal();
      };
      NewtonSettings settings{.tolerance = kTightTolerance};
      settings.jacobian = m == 0 ? NewtonJacobian::kReused : NewtonJacobian::kKept;
      e[m] = m == 0 ? solve_link_angles<2>(encoder, k, torque, jacobian, settings)
                    : solve_link_angles<2>(encoder, k, torque, jacobian, settings, false, &kept[m - 1], m == 2);
      ASSERT_TRUE(e[m].converged) << n << " " << m;
      EXPECT_LE((e[m].newton - link).lpNorm<Eigen::Infinity>(), 1e-11) << n << " " << m;
    }
    EXPECT_EQ(e[2].newton, e[1].newton) << n;
    EXPECT_EQ(e[2].iterations, e[1].iterations) << n;
    EXPECT_EQ(e[2].one_step, e[0].one_step) << n;
    EXPECT_EQ(e[2].per_joint, e[0].per_joint) << n;
    EXPECT_TRUE(e[1].one_step.array().isNaN().all()) << n;
    EXPECT_TRUE(e[1].per_joint.array().isNaN().all()) << n;
  }
  EXPECT_EQ(formed[0], 200);              // one G per solve
  EXPECT_LT(formed[1], 200 / 10);         // kept: formed again only when a step contracts less than 100×
  EXPECT_EQ(formed[2], formed[1] + 199);  // the forms' own G at each later θ_enc (the first serves Newton too)
}

/// kKept's test on the predicted residual (link_angle_newton.hpp): along the same moving sequence, Newton starting
/// from the parabola through the last three solutions (as the output compensator does), the default tolerance 1e-9.
/// A solve that ends on a predicted residual returns a point whose true residual meets the tolerance, its torque the
/// chord's own K (θ_enc − θ), within K times the tolerance of τ_g there; it evaluates τ_g less often than every step
/// evaluated, and never more than kMaxPredictedSolves solves in a row end so.
TEST(LinkAngleNewton, APredictedResidualEndsASolveOnlyWhereTheTrueOneMeetsTheTolerance) {
  using V = Eigen::Vector2d;
  Eigen::Matrix2d A;
  A << 40.0, 25.0, -15.0, 30.0;  // [Nm]
  int evaluations[2] = {0, 0};
  auto torque_of = [&](const V& q) { return V(A * q.array().sin().matrix()); };
  const V k(800.0, 1200.0);
  LinkAngleFactor<2> kept[2];  // predicted convergence off, on
  std::array<std::array<V, 3>, 2> history{};
  int predicted = 0, in_a_row = 0, most_in_a_row = 0;
  for (int n = 0; n < 400; ++n) {
    const double t = 0.004 * n;
    const V link(0.3 + 0.2 * std::sin(2 * t), -0.2 + 0.1 * std::cos(3 * t));
    const V encoder = link + torque_of(link).cwiseQuotient(k);
    for (int m = 0; m < 2; ++m) {
      auto torque = [&](const V& q, V& tau) {
        ++evaluations[m];
        tau = torque_of(q);
      };
      auto jacobian = [&](const V& q, const V&, Eigen::Matrix2d& G) { G = A * q.array().cos().matrix().asDiagonal(); };
      const NewtonSettings settings{.jacobian = NewtonJacobian::kKept, .predicted_convergence = m == 1};
      const auto& h = history[static_cast<std::size_t>(m)];
      const V start = n >= 3 ? V(3 * h[0] - 3 * h[1] + h[2]) : encoder;
      const LinkAngleEstimate<2> e =
          solve_link_angles<2>(encoder, k, torque, jacobian, settings, false, &kept[m], false, &start);
      ASSERT_TRUE(e.converged) << n << " " << m;
      const V residual = encoder - torque_of(e.newton).cwiseQuotient(k) - e.newton;
      EXPECT_LE(residual.lpNorm<Eigen::Infinity>(), settings.tolerance) << n << " " << m;
      EXPECT_LE((e.torque - torque_of(e.newton)).lpNorm<Eigen::Infinity>(), k.maxCoeff() * settings.tolerance) << n;
      if (e.predicted) {
        EXPECT_EQ(e.torque, V(k.cwiseProduct(encoder - e.newton))) << n;
      }
      EXPECT_TRUE(m == 1 || !e.predicted);
      if (m == 1) {
        predicted += e.predicted;
        in_a_row = e.predicted ? in_a_row + 1 : (e.iterations > 0 ? 0 : in_a_row);
        most_in_a_row = std::max(most_in_a_row, in_a_row);
      }
      auto& hm = history[static_cast<std::size_t>(m)];
      hm = {e.newton, hm[0], hm[1]};
    }
  }
  EXPECT_GT(predicted, 100);
  EXPECT_LE(most_in_a_row, kMaxPredictedSolves);
  EXPECT_LE(evaluations[1] + predicted, evaluations[0]);
  RecordProperty("evaluations_every_step", evaluations[0]);
  RecordProperty("evaluations_predicted", evaluations[1]);
}

/// A standing-like pose with the legs bent.
humanoid::JointVector bent_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  humanoid::JointVector q{};
  for (int side = 0; side < 2; ++side) {
    const int j = humanoid::leg_first_joint(side);
    q[j] = u(rng);
    q[j + 1] = u(rng);
    q[j + 2] = -0.4 + u(rng);
    q[j + 3] = 0.8 + u(rng);
    q[j + 4] = -0.4 + u(rng);
    q[j + 5] = u(rng);
  }
  return q;
}

class OutputCompensatorLegs : public ::testing::TestWithParam<std::tuple<WeightSplit, GravityForm>> {};

TEST_P(OutputCompensatorLegs, RecoversTheLinkAnglesThatTheModelDeflects) {
  const walking::RobotModel model = walking::make_robot_model(humanoid::RobotParams{});
  CompensationParams p;
  p.newton.tolerance = kTightTolerance;
  p.split = std::get<0>(GetParam());
  p.gravity = std::get<1>(GetParam());
  DeformationCompensator truth(model, p), compensator(model, p);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> tilt(-0.05, 0.05), k(600, 1400);
  for (int trial = 0; trial < 40; ++trial) {
    const Matrix3d R = walking::rot_x(tilt(rng)) * walking::rot_y(tilt(rng));
    SupportPlan plan;
    plan.swinging = {trial % 3 == 1, trial % 3 == 2};  // double, left swing, right swing
    plan.soles = {Pose{Vector3d(0.05, 0.093, 0), Matrix3d::Identity()},
                  Pose{Vector3d(0, -0.093, 0), Matrix3d::Identity()}};
    plan.zmp_ref = Eigen::Vector2d(0.02, tilt(rng));
    p.k_joint = 1.0;
    for (auto& kj : p.k_scale) kj = k(rng);
    truth = DeformationCompensator(model, p);
    compensator = DeformationCompensator(model, p);
    const humanoid::JointVector link = bent_pose(rng);
    // What the encoders read when the gears carry the model's torque: θ_enc = θ + τ_g(θ)/k.
    const humanoid::JointVector tau = truth.torque(link, R, plan);
    humanoid::JointVector encoder = link;
    double deflection = 0;
    for (int j = 0; j < humanoid::kJoints; ++j) {
      encoder[j] += tau[j] / p.k_scale[j];
      deflection = std::max(deflection, std::abs(tau[j] / p.k_scale[j]));
    }
    ASSERT_GT(deflection, 0.01);  // a real test: centiradians of sag
    const OutputEstimate& e = compensator.output(encoder, R, plan);
    ASSERT_TRUE(e.converged) << trial;
    EXPECT_LE(e.iterations, 8);  // the chord method (the default): linear, ~1e-2 per step from the one-step form
    EXPECT_LE(e.residual, 1e-12);
    double newton = 0;
    for (int j = 0; j < humanoid::kJoints; ++j) newton = std::max(newton, std::abs(e.newton[j] - link[j]));
    EXPECT_LE(newton, 1e-11) << trial;
  }
}

INSTANTIATE_TEST_SUITE_P(SplitsAndForms, OutputCompensatorLegs,
                         ::testing::Combine(::testing::Values(WeightSplit::kCom, WeightSplit::kZmpReference),
                                            ::testing::Values(GravityForm::kThesis, GravityForm::kFull)));

/// The tests below: the soles apart, the left ahead, the reference ZMP between them (both feet down), and the
/// link angles' motion about a bent pose (0.05 rad, 2 rad/s, a phase per joint).
SupportPlan standing_plan() {
  SupportPlan plan;
  plan.soles = {Pose{Vector3d(0.05, 0.093, 0), Matrix3d::Identity()},
                Pose{Vector3d(0, -0.093, 0), Matrix3d::Identity()}};
  plan.zmp_ref = Eigen::Vector2d(0.02, 0.03);
  return plan;
}
/// Their compensators' parameters: split about the reference ZMP, Newton to kTightTolerance with `jacobian`.
CompensationParams moving_pose_params(NewtonJacobian jacobian) {
  CompensationParams p;
  p.newton.tolerance = kTightTolerance;
  p.split = WeightSplit::kZmpReference;
  p.newton.jacobian = jacobian;
  return p;
}
humanoid::JointVector moving_link(const humanoid::JointVector& base, double t) {
  humanoid::JointVector link = base;
  for (int j = 0; j < humanoid::kJoints; ++j) link[j] += 0.05 * std::sin(2.0 * t + j);
  return link;
}

/// Period after period along a moving pose (a support change halfway), the kept factorisation and the extrapolated
/// start find the link angles as newton_jacobian = reused does (1e-11 rad, the tolerance's order); asking for the
/// one-step and per-joint forms changes no bit of Newton's estimate, and the forms equal reused's bit for bit.
TEST(OutputCompensator, KeptFactorAndPredictedStartAgreeWithReusedAndTheFormsChangeNothing) {
  const walking::RobotModel model = walking::make_robot_model(humanoid::RobotParams{});
  const CompensationParams p = moving_pose_params(NewtonJacobian::kReused);
  DeformationCompensator truth(model, p), reused(model, p);
  const CompensationParams q = moving_pose_params(NewtonJacobian::kKept);
  DeformationCompensator kept(model, q), kept_forms(model, q);
  kept_forms.estimate_forms(true);
  std::mt19937 rng(21);
  const humanoid::JointVector base = bent_pose(rng);
  SupportPlan plan = standing_plan();
  int iterations[2] = {0, 0};
  for (int n = 0; n < 250; ++n) {
    const double t = 0.004 * n;
    plan.swinging = {false, n >= 125};
    const humanoid::JointVector link = moving_link(base, t);
    const humanoid::JointVector tau = truth.torque(link, Matrix3d::Identity(), plan);
    humanoid::JointVector encoder = link;
    for (int j = 0; j < humanoid::kJoints; ++j) encoder[j] += tau[j] / 1000.0;
    const OutputEstimate r = reused.output(encoder, Matrix3d::Identity(), plan);
    const OutputEstimate k = kept.output(encoder, Matrix3d::Identity(), plan);
    const OutputEstimate f = kept_forms.output(encoder, Matrix3d::Identity(), plan);
    ASSERT_TRUE(r.converged && k.converged) << n;
    iterations[0] += r.iterations;
    iterations[1] += k.iterations;
    EXPECT_EQ(f.newton, k.newton) << n;
    EXPECT_EQ(f.iterations, k.iterations) << n;
    EXPECT_EQ(f.one_step, r.one_step) << n;
    EXPECT_EQ(f.per_joint, r.per_joint) << n;
    EXPECT_EQ(f.conventional, r.conventional) << n;
    for (int j = 0; j < humanoid::kJoints; ++j) {
      EXPECT_NEAR(k.newton[j], r.newton[j], 1e-11) << n << " " << j;
      EXPECT_NEAR(k.newton[j], link[j], 1e-11) << n << " " << j;
    }
  }
  // (gravity loads: G moves with the pose, so the chord needs its refreshes; the count is a sanity bound)
  EXPECT_LE(iterations[1], 2 * iterations[0]);
}

/// The stiffness changing under the kept factorisation (k estimation: a drift each period, then the jump of the
/// compensators taking a confident estimate): the chord's residual holds the new K, so every period still meets the
/// tolerance at the link angles the new stiffness deflects (1e-11 rad), as a compensator built with that stiffness
/// (reused, G formed afresh) finds them; the stale factor only costs steps (at most twice reused's).
TEST(OutputCompensator, KeptFactorOutlivesAStiffnessChangeAndFindsTheNewRoot) {
  const walking::RobotModel model = walking::make_robot_model(humanoid::RobotParams{});
  DeformationCompensator kept(model, moving_pose_params(NewtonJacobian::kKept));
  const CompensationParams p = moving_pose_params(NewtonJacobian::kReused);
  DeformationCompensator truth(model, p), reused(model, p);
  std::mt19937 rng(33);
  const humanoid::JointVector base = bent_pose(rng);
  const SupportPlan plan = standing_plan();
  int iterations[2] = {0, 0};
  for (int n = 0; n < 200; ++n) {
    const double t = 0.004 * n;
    humanoid::JointVector k{};
    for (int j = 0; j < humanoid::kJoints; ++j) k[j] = (n < 100 ? 1000.0 + 0.5 * n : 1180.0) + 10.0 * j;
    kept.set_stiffness(k);
    reused.set_stiffness(k);
    const humanoid::JointVector link = moving_link(base, t);
    const humanoid::JointVector tau = truth.torque(link, Matrix3d::Identity(), plan);
    humanoid::JointVector encoder = link;
    for (int j = 0; j < humanoid::kJoints; ++j) encoder[j] += tau[j] / k[j];
    const OutputEstimate r = reused.output(encoder, Matrix3d::Identity(), plan);
    const OutputEstimate e = kept.output(encoder, Matrix3d::Identity(), plan);
    ASSERT_TRUE(r.converged && e.converged) << n;
    iterations[0] += r.iterations;
    iterations[1] += e.iterations;
    for (int j = 0; j < humanoid::kJoints; ++j) {
      EXPECT_NEAR(e.newton[j], link[j], 1e-11) << n << " " << j;
      EXPECT_NEAR(e.newton[j], r.newton[j], 1e-11) << n << " " << j;
    }
  }
  EXPECT_LE(iterations[1], 2 * iterations[0]);
}

TEST(OutputCompensator, FlagsAndFallsBackWhenTheIterationsRunOut) {
  const walking::RobotModel model = walking::make_robot_model(humanoid::RobotParams{});
  CompensationParams p;
  p.newton.max_iterations = 1;
  DeformationCompensator c(model, p);
  std::mt19937 rng(9);
  SupportPlan plan;
  plan.swinging = {false, true};
  plan.soles = {Pose{Vector3d(0, 0.093, 0), Matrix3d::Identity()},
                Pose{Vector3d(0, -0.093, 0.05), Matrix3d::Identity()}};
  humanoid::JointVector encoder = bent_pose(rng);
  encoder[humanoid::kLeftHipRoll] += 0.04;
  const OutputEstimate& e = c.output(encoder, Matrix3d::Identity(), plan);
  EXPECT_FALSE(e.converged);
  EXPECT_EQ(e.iterations, 1);
  EXPECT_GT(e.residual, 1e-12);
  EXPECT_TRUE(std::isfinite(e.newton[humanoid::kLeftHipRoll]));
}

TEST(DeformationCompensator, InputIsDesiredPlusTorqueOverStiffnessAndOffPassesThrough) {
  const walking::RobotModel model = walking::make_robot_model(humanoid::RobotParams{});
  CompensationParams p;
  DeformationCompensator on(model, p);
  p.mode = CompensationMode::kOff;
  DeformationCompensator off(model, p);
  std::mt19937 rng(13);
  const humanoid::JointVector desired = bent_pose(rng);
  SupportPlan plan;
  plan.soles = {Pose{Vector3d(0, 0.093, 0), Matrix3d::Identity()}, Pose{Vector3d(0, -0.093, 0), Matrix3d::Identity()}};
  const humanoid::JointVector command = on.input(desired, Matrix3d::Identity(), plan);
  const humanoid::JointVector tau = on.input_torque();
  for (int j = 0; j < humanoid::kJoints; ++j) {
    EXPECT_NEAR(command[j], desired[j] + tau[j] / 1000.0, 1e-15);  // eq. 9
    EXPECT_EQ(off.input(desired, Matrix3d::Identity(), plan)[j], desired[j]);
  }
}

TEST(DeformationCompensator, AllocatesNothing) {
  const walking::RobotModel model = walking::make_robot_model(humanoid::RobotParams{});
  for (const WeightSplit split : {WeightSplit::kCom, WeightSplit::kZmpReference}) {
    CompensationParams p;
    p.split = split;
    DeformationCompensator c(model, p);
    std::mt19937 rng(17);
    const humanoid::JointVector q = bent_pose(rng);
    SupportPlan plan;
    plan.soles = {Pose{Vector3d(0, 0.093, 0), Matrix3d::Identity()},
                  Pose{Vector3d(0, -0.093, 0), Matrix3d::Identity()}};
    const long before = g_allocations.load();
    for (int k = 0; k < 100; ++k) {
      c.input(q, Matrix3d::Identity(), plan);
      c.output(q, Matrix3d::Identity(), plan);
    }
    EXPECT_EQ(g_allocations.load() - before, 0);
  }
}

}  // namespace
}  // namespace flexgait::compensation
