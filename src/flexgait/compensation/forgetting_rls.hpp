#pragma once
/// \file forgetting_rls.hpp
/// Recursive least squares with exponential forgetting on N parameters x, one scalar measurement
/// at a time: y = hᵀx + v, var(v) = r (docs/guide/compensation.md, online stiffness identification).
///   P ← P / λ                                  (once per sample time: forget)
///   K = P h / (r + hᵀ P h),  x ← x + K (y − hᵀx),  P ← P − K hᵀ P
/// With P₀ the prior covariance of x and r the measurement variance, P is x's posterior covariance
/// (λ = 1, white noise): after n samples of regressor h_i, P ≈ r (Σ h_i h_iᵀ)⁻¹ — for N = 1 the
/// standard deviation of x is σ / sqrt(Σ h_i²), the count of samples the convergence takes.
/// Fixed size, allocation-free.
#include <cmath>

#include <Eigen/Core>

namespace flexgait::compensation {

template <int N>
class ForgettingRls {
 public:
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;

  ForgettingRls() = default;
  /// \param lambda forgetting factor ∈ (0, 1] (1: none)
  ForgettingRls(const Vector& x0, const Matrix& P0, double lambda) : x_(x0), P_(P0), lambda_(lambda) {}

  /// Once per sample time, before that time's measurements.
  void forget() { P_ /= lambda_; }

  /// Parameter i forgets what it was: no correlation with the others, prior variance `variance` (a nuisance
  /// parameter that starts anew, e.g. an offset per stance).
  void restart(int i, double variance) {
    P_.row(i).setZero();
    P_.col(i).setZero();
    P_(i, i) = variance;
  }

  /// One scalar measurement y = hᵀx + v, var(v) = r > 0. Non-finite h, y or r: no change, false.
  bool update(const Vector& h, double y, double r) {
    if (!h.allFinite() || !std::isfinite(y) || !(r > 0) || !std::isfinite(r)) return false;
    const Vector Ph = P_ * h;
    const double s = r + h.dot(Ph);
    const Vector K = Ph / s;
    x_ += K * (y - h.dot(x_));
    P_ -= K * Ph.transpose();
    P_ = 0.5 * (P_ + P_.transpose());  // keep it symmetric against round-off
    return true;
  }

  const Vector& x() const { return x_; }
  Vector& x() { return x_; }
  const Matrix& P() const { return P_; }

 private:
  Vector x_ = Vector::Zero();
  Matrix P_ = Matrix::Identity();
  double lambda_ = 1.0;
};

}  // namespace flexgait::compensation
