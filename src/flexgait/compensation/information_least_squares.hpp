#pragma once
/// \file information_least_squares.hpp
/// Least squares on N parameters x with a Gaussian prior, in information form (docs/guide/compensation.md,
/// control.k_estimation = calibrate): scalar measurements y = hᵀx + v, var(v) = r, accumulate
///     A = P₀⁻¹ + Σ h hᵀ / r,   b = P₀⁻¹ x₀ + Σ h y / r,   x = A⁻¹ b,   P = A⁻¹
/// (the posterior's mean and covariance; what forgetting_rls.hpp gives with λ = 1). Why a second form: the
/// covariance form updates P by subtraction, P ← P − K hᵀP, and with parameters of very different scales
/// (gear compliances ≈ 1e-3 rad/Nm beside tilt offsets) and thousands of samples P loses positive definiteness
/// to round-off and x diverges — on the twin's calibration it did, to the estimate's bounds, in 4 of 10 runs. A
/// only adds positive semi-definite terms; x comes from its LDLᵀ factorisation. A parameter with prior
/// variance 0 is held at its prior (its row and column are left out). Fixed size, allocation-free.
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace flexgait::compensation {

template <int N>
class InformationLeastSquares {
 public:
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;

  InformationLeastSquares() { solve(); }
  /// \param x0 the prior mean; \param prior_variance the prior covariance's diagonal (a zero: the parameter is
  /// held at x0)
  InformationLeastSquares(const Vector& x0, const Vector& prior_variance) : x_(x0), x0_(x0) {
    A_.setZero();
    for (int i = 0; i < N; ++i) {
      held_[i] = !(prior_variance[i] > 0);
      A_(i, i) = held_[i] ? 1.0 : 1.0 / prior_variance[i];
      b_[i] = A_(i, i) * x0[i];
    }
    solve();
  }
  /// One scalar measurement; non-finite h, y or r, or r ≤ 0: no change, false. (x is solved for by solve().)
  bool add(const Vector& h_in, double y, double r) {
    if (!h_in.allFinite() || !std::isfinite(y) || !(r > 0) || !std::isfinite(r)) return false;
    Vector h = h_in;
    for (int i = 0; i < N; ++i)
      if (held_[i]) {
        y -= h[i] * x0_[i];  // (a held parameter's known part moves to the measurement)
        h[i] = 0;
      }
    A_.noalias() += h * h.transpose() / r;
    b_.noalias() += h * (y / r);
    return true;
  }
  /// x = A⁻¹ b (A's LDLᵀ factorisation, kept for variance()).
  void solve() {
    ldlt_.compute(A_);
    x_ = ldlt_.solve(b_);
  }
  const Vector& x() const { return x_; }
  /// Parameter i's posterior variance P_ii = (A⁻¹)_ii as of the last solve() (0 for a held one).
  double variance(int i) const {
    if (held_[i]) return 0.0;
    Vector e = Vector::Zero();
    e[i] = 1;
    return ldlt_.solve(e)[i];
  }

 private:
  Matrix A_ = Matrix::Identity();
  Vector b_ = Vector::Zero(), x_ = Vector::Zero(), x0_ = Vector::Zero();
  Eigen::Matrix<bool, N, 1> held_ = Eigen::Matrix<bool, N, 1>::Constant(false);
  Eigen::LDLT<Matrix> ldlt_;
};

}  // namespace flexgait::compensation
