// The DARE solver: the scalar case against its closed form, random stabilisable systems by their
// residual and the closed loop's stability, and bad input.
#include "flexgait/numerics/riccati.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace flexgait::numerics {
namespace {

using Eigen::MatrixXd;

TEST(Riccati, ScalarClosedForm) {
  // p = a²p − a²b²p²/(r + b²p) + q  ⇔  b²p² + (r − a²r − qb²) p − qr = 0, the positive root.
  for (double a : {0.5, 1.0, 1.5}) {
    const double b = 0.7, q = 2.0, r = 0.3;
    const double B = r - a * a * r - q * b * b;
    const double p = (-B + std::sqrt(B * B + 4 * b * b * q * r)) / (2 * b * b);
    const DareResult s = solve_dare(MatrixXd::Constant(1, 1, a), MatrixXd::Constant(1, 1, b),
                                    MatrixXd::Constant(1, 1, q), MatrixXd::Constant(1, 1, r));
    EXPECT_NEAR(s.P(0, 0), p, 1e-13 * p);  // both exact up to rounding
  }
}

TEST(Riccati, RandomSystemsHaveTinyResidualsAndStableClosedLoops) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const int dim = 2 + trial % 5, inputs = 1 + trial % 2;
    MatrixXd A(dim, dim), B(dim, inputs), C(dim, dim);
    for (auto* M : {&A, &B, &C})
      for (Eigen::Index i = 0; i < M->size(); ++i) M->data()[i] = n(rng);
    const MatrixXd Q = C.transpose() * C + 1e-3 * MatrixXd::Identity(dim, dim);
    const MatrixXd R = MatrixXd::Identity(inputs, inputs);
    const DareResult s = solve_dare(A, B, Q, R);
    // Relative residual at rounding level: 1e-9 of ||P|| is the bound (measured ≤ 1e-13).
    EXPECT_LE(s.residual, 1e-9 * std::max(1.0, s.P.cwiseAbs().maxCoeff())) << "trial " << trial;
    EXPECT_LT((s.P - s.P.transpose()).cwiseAbs().maxCoeff(), 1e-12 * s.P.cwiseAbs().maxCoeff());
    // The stabilising solution: A − BK has its eigenvalues inside the unit circle.
    const Eigen::VectorXcd ev = (A - B * s.K).eigenvalues();
    EXPECT_LT(ev.cwiseAbs().maxCoeff(), 1.0) << "trial " << trial;
  }
}

TEST(Riccati, RejectsMismatchedDimensions) {
  EXPECT_THROW(
      solve_dare(MatrixXd::Identity(2, 2), MatrixXd::Ones(3, 1), MatrixXd::Identity(2, 2), MatrixXd::Identity(1, 1)),
      std::invalid_argument);
}

}  // namespace
}  // namespace flexgait::numerics
