// Newton-Raphson fixed points, finite-difference Jacobians and multipliers on maps with known answers.
#include "flexgait/numerics/newton.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flexgait::numerics {
namespace {

TEST(Newton, AffineMapFixedPointJacobianAndMultipliers) {
  Eigen::Matrix3d A;
  A << 0.5, 0.2, 0.0, -0.1, 0.3, 0.4, 0.0, 0.0, -0.6;
  const Eigen::Vector3d b(1.0, -2.0, 0.5);
  const VectorMap P = [&](const Eigen::VectorXd& z, Eigen::VectorXd& out) -> std::optional<std::string> {
    out = A * z + b;
    return std::nullopt;
  };
  NewtonOptions tight;
  tight.tolerance = 1e-13;
  const NewtonResult r = newton_fixed_point(P, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), tight);
  ASSERT_TRUE(r.converged) << r.failure();
  const Eigen::Vector3d exact = (Eigen::Matrix3d::Identity() - A).lu().solve(b);
  EXPECT_LE((r.z - exact).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_LE(r.iterations, 2);                                   // exact Jacobian up to round-off: one step
  EXPECT_LE((r.jacobian - A).lpNorm<Eigen::Infinity>(), 1e-9);  // central differences are exact on affine maps
  const auto mult = floquet_multipliers(r.jacobian);
  ASSERT_EQ(mult.size(), 3u);
  EXPECT_NEAR(std::abs(mult[0]), 0.6, 1e-9);  // eigenvalue -0.6 of the lower block is the largest
  for (std::size_t i = 1; i < mult.size(); ++i) EXPECT_LE(std::abs(mult[i]), std::abs(mult[i - 1]));
}

TEST(Newton, NonlinearMapConvergesQuadratically) {
  // P(z) = cos(z): fixed point 0.7390851332151607 (the Dottie number).
  const VectorMap P = [](const Eigen::VectorXd& z, Eigen::VectorXd& out) -> std::optional<std::string> {
    out = z.array().cos();
    return std::nullopt;
  };
  const NewtonResult r = newton_fixed_point(P, Eigen::VectorXd::Constant(1, 0.2), Eigen::VectorXd::Ones(1));
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.z(0), 0.7390851332151607, 1e-12);
  EXPECT_NEAR(r.jacobian(0, 0), -std::sin(r.z(0)), 1e-9);
  ASSERT_GE(r.history.size(), 3u);
  // Quadratic convergence: each residual is at most a constant times the square of the previous.
  for (std::size_t i = 2; i < r.history.size(); ++i)
    EXPECT_LE(r.history[i].residual, 10.0 * r.history[i - 1].residual * r.history[i - 1].residual);
}

TEST(Newton, ReportsMapsWithoutFixedPoints) {
  const VectorMap shift = [](const Eigen::VectorXd& z, Eigen::VectorXd& out) -> std::optional<std::string> {
    out = z.array() + 1.0;  // P(z) = z + 1: Jacobian identity, no fixed point
    return std::nullopt;
  };
  const NewtonResult r = newton_fixed_point(shift, Eigen::VectorXd::Zero(2), Eigen::VectorXd::Ones(2));
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.failure_reason, NewtonFailure::Singular) << r.failure();
  EXPECT_EQ(r.failure_detail, "");
  // The words files show, made from the reason (the bytes of before).
  EXPECT_EQ(r.failure(), "singular Newton matrix (a multiplier equals 1): no isolated fixed point");

  const VectorMap partial = [](const Eigen::VectorXd& z, Eigen::VectorXd& out) -> std::optional<std::string> {
    if (z(0) > 0.5) return std::string("fell over");
    out = Eigen::VectorXd::Constant(1, 2.0 * z(0) - 1.0);  // fixed point at 1, outside the domain
    return std::nullopt;
  };
  const NewtonResult r2 = newton_fixed_point(partial, Eigen::VectorXd::Constant(1, 0.1), Eigen::VectorXd::Ones(1));
  EXPECT_FALSE(r2.converged);
  EXPECT_EQ(r2.failure_reason, NewtonFailure::LeftBasin) << r2.failure();
  EXPECT_EQ(r2.failure_detail, "fell over");  // the map's own words, passed on
  EXPECT_EQ(r2.failure(), "left the basin: fell over");
}

// Every reason has a sentence, a name and its words; a converged result has none.
TEST(Newton, FailureWordsComeFromTheReasonTable) {
  for (const ReasonEntry<NewtonFailure>& e : kNewtonFailureTable) {
    EXPECT_EQ(name_of(e.reason), e.name);
    EXPECT_FALSE(newton_failure_text(e.reason, "x").empty());
  }
  EXPECT_EQ(newton_failure_text(NewtonFailure::NoConvergence, "30 iterations (residual 0.000001)"),
            "no convergence in 30 iterations (residual 0.000001)");
  EXPECT_EQ(newton_failure_text(NewtonFailure::DifferenceStep, "Jacobian column 0: fell"),
            "a finite-difference step left the basin (Jacobian column 0: fell)");
  EXPECT_EQ(sentence_with_detail("no detail here", "d"), "no detail here (d)");
  EXPECT_EQ(sentence_with_detail("no detail here", ""), "no detail here");
  EXPECT_EQ(NewtonResult{}.failure(), "");
}

}  // namespace
}  // namespace flexgait::numerics
