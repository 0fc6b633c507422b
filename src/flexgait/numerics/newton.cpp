#include "flexgait/numerics/newton.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace flexgait::numerics {

std::string newton_failure_text(NewtonFailure reason, std::string_view detail) {
  return reason_text(kNewtonFailureTable, reason, detail);
}

std::string NewtonResult::failure() const {
  return failure_reason ? newton_failure_text(*failure_reason, failure_detail) : std::string();
}

namespace {

// Stops `r` with `reason` and its detail.
void fail(NewtonResult& r, NewtonFailure reason, std::string detail = {}) {
  r.failure_reason = reason;
  r.failure_detail = std::move(detail);
}

}  // namespace

std::optional<std::string> central_difference_jacobian(const VectorMap& P, const Eigen::VectorXd& z,
                                                       const Eigen::VectorXd& h, Eigen::MatrixXd& J) {
  const Eigen::Index n = z.size();
  J.resize(n, n);
  Eigen::VectorXd zp = z, zm = z, fp(n), fm(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    zp(i) = z(i) + h(i);
    zm(i) = z(i) - h(i);
    if (auto e = P(zp, fp)) return "Jacobian column " + std::to_string(i) + ": " + *e;
    if (auto e = P(zm, fm)) return "Jacobian column " + std::to_string(i) + ": " + *e;
    J.col(i) = (fp - fm) / (zp(i) - zm(i));
    zp(i) = zm(i) = z(i);
  }
  return std::nullopt;
}

NewtonResult newton_fixed_point(const VectorMap& P, const Eigen::VectorXd& z0, const Eigen::VectorXd& scale,
                                const NewtonOptions& opt) {
  NewtonResult r;
  r.z = z0;
  const Eigen::Index n = z0.size();
  Eigen::VectorXd pz(n);
  if (auto e = P(r.z, pz)) {
    fail(r, NewtonFailure::MapAtGuess, *e);
    return r;
  }
  Eigen::VectorXd F = pz - r.z;
  r.residual = F.lpNorm<Eigen::Infinity>();
  Eigen::VectorXd h(n);
  for (int it = 0;; ++it) {
    for (Eigen::Index i = 0; i < n; ++i) h(i) = opt.fd_relative_step * std::max(std::abs(r.z(i)), scale(i));
    if (auto e = central_difference_jacobian(P, r.z, h, r.jacobian)) {
      fail(r, NewtonFailure::DifferenceStep, *e);
      return r;
    }
    if (r.residual <= opt.tolerance) {
      r.converged = true;
      r.iterations = it;
      return r;
    }
    if (it >= opt.max_iterations) {
      fail(r, NewtonFailure::NoConvergence,
           std::to_string(opt.max_iterations) + " iterations (residual " + std::to_string(r.residual) + ")");
      r.iterations = it;
      return r;
    }
    const Eigen::MatrixXd A = r.jacobian - Eigen::MatrixXd::Identity(n, n);
    // J - I is singular when a multiplier is 1 (relative to the Jacobian's own size).
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A);
    const double jnorm = std::max(1.0, r.jacobian.lpNorm<Eigen::Infinity>());
    Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    if (svd.singularValues().minCoeff() < 1e-10 * jnorm) {
      fail(r, NewtonFailure::Singular);
      r.iterations = it;
      return r;
    }
    const Eigen::VectorXd dz = lu.solve(-F);
    // Backtracking: accept the first λ with a sufficient decrease of ||F||.
    double lambda = 1.0;
    std::string last_error;
    bool accepted = false;
    Eigen::VectorXd z_new, F_new;
    while (lambda >= opt.min_damping) {
      z_new = r.z + lambda * dz;
      if (auto e = P(z_new, pz)) {
        last_error = *e;
      } else {
        F_new = pz - z_new;
        if (F_new.lpNorm<Eigen::Infinity>() <= (1.0 - 1e-4 * lambda) * r.residual) {
          accepted = true;
          break;
        }
      }
      lambda *= 0.5;
    }
    if (!accepted) {
      fail(r, last_error.empty() ? NewtonFailure::NoDecrease : NewtonFailure::LeftBasin, last_error);
      r.iterations = it;
      return r;
    }
    r.history.push_back({it, r.residual, (lambda * dz).lpNorm<Eigen::Infinity>(), lambda});
    r.z = z_new;
    F = F_new;
    r.residual = F.lpNorm<Eigen::Infinity>();
  }
}

std::vector<std::complex<double>> floquet_multipliers(const Eigen::MatrixXd& J) {
  Eigen::EigenSolver<Eigen::MatrixXd> es(J, false);
  std::vector<std::complex<double>> ev(es.eigenvalues().data(), es.eigenvalues().data() + es.eigenvalues().size());
  std::sort(ev.begin(), ev.end(), [](const auto& a, const auto& b) {
    if (std::abs(a) != std::abs(b)) return std::abs(a) > std::abs(b);
    if (a.real() != b.real()) return a.real() > b.real();
    return a.imag() > b.imag();
  });
  return ev;
}

}  // namespace flexgait::numerics
