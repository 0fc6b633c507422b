#include "flexgait/numerics/riccati.hpp"

#include <cmath>
#include <stdexcept>

namespace flexgait::numerics {
namespace {

using Eigen::MatrixXd;

MatrixXd riccati_map(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R, const MatrixXd& P) {
  const MatrixXd BtPA = B.transpose() * P * A;
  return A.transpose() * P * A - BtPA.transpose() * (R + B.transpose() * P * B).ldlt().solve(BtPA) + Q;
}

MatrixXd symmetric(const MatrixXd& M) {
  return 0.5 * (M + M.transpose());
}

}  // namespace

double dare_residual(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R, const MatrixXd& P) {
  return (P - riccati_map(A, B, Q, R, P)).cwiseAbs().maxCoeff();
}

DareResult solve_dare(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R) {
  const auto n = A.rows();
  if (A.cols() != n || B.rows() != n || Q.rows() != n || Q.cols() != n || R.rows() != B.cols() || R.cols() != B.cols())
    throw std::invalid_argument("solve_dare: matrix dimensions do not match");
  const MatrixXd I = MatrixXd::Identity(n, n);
  // Structured doubling: A_{k+1} = A_k (I + G_k H_k)⁻¹ A_k,
  //                      G_{k+1} = G_k + A_k (I + G_k H_k)⁻¹ G_k A_kᵀ,
  //                      H_{k+1} = H_k + A_kᵀ H_k (I + G_k H_k)⁻¹ A_k,   H_k → P.
  MatrixXd Ak = A, Gk = B * R.ldlt().solve(B.transpose()), Hk = Q;
  DareResult out;
  constexpr int kMaxDoubling = 100;
  for (out.iterations = 1; out.iterations <= kMaxDoubling; ++out.iterations) {
    const Eigen::PartialPivLU<MatrixXd> W(I + Gk * Hk);
    const MatrixXd WA = W.solve(Ak);
    const MatrixXd Hn = symmetric(Hk + Ak.transpose() * Hk * WA);
    Gk = symmetric(Gk + Ak * W.solve(Gk) * Ak.transpose());
    Ak = Ak * WA;
    const double change = (Hn - Hk).cwiseAbs().maxCoeff();
    Hk = Hn;
    if (!Hk.allFinite()) break;
    if (change <= 1e-15 * std::max(1.0, Hk.cwiseAbs().maxCoeff())) break;
  }
  if (out.iterations > kMaxDoubling || !Hk.allFinite())
    throw std::runtime_error("solve_dare: the doubling did not converge (no stabilising solution)");
  // Newton-Kleinman refinement: with K from P, solve the Stein equation
  // P' = (A − BK)ᵀ P' (A − BK) + Q + KᵀRK by Kronecker vectorisation (small n only).
  MatrixXd P = Hk;
  double best = dare_residual(A, B, Q, R, P);
  for (int step = 0; step < 3 && n <= 12; ++step) {
    const MatrixXd K = (R + B.transpose() * P * B).ldlt().solve(B.transpose() * P * A);
    const MatrixXd Ac = A - B * K;
    const MatrixXd rhs = Q + K.transpose() * R * K;
    // vec(Acᵀ P Ac) = (Acᵀ ⊗ Acᵀ) vec(P), column-major vec: (i, j) ↦ i + n j.
    MatrixXd M = MatrixXd::Identity(n * n, n * n);
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j)
        for (Eigen::Index k = 0; k < n; ++k)
          for (Eigen::Index l = 0; l < n; ++l) M(i + n * j, k + n * l) -= Ac(k, i) * Ac(l, j);
    const Eigen::VectorXd vec_p = M.partialPivLu().solve(Eigen::Map<const Eigen::VectorXd>(rhs.data(), n * n));
    const MatrixXd next = symmetric(Eigen::Map<const MatrixXd>(vec_p.data(), n, n));
    const double r = dare_residual(A, B, Q, R, next);
    if (!(r < best)) break;
    best = r;
    P = next;
  }
  out.P = P;
  out.K = (R + B.transpose() * P * B).ldlt().solve(B.transpose() * P * A);
  out.residual = best;
  return out;
}

}  // namespace flexgait::numerics
