#pragma once
/// \file riccati.hpp
/// The discrete algebraic Riccati equation (DARE)
///
///   P = Aᵀ P A − Aᵀ P B (R + Bᵀ P B)⁻¹ Bᵀ P A + Q
///
/// solved by the structured doubling algorithm (Chu, Fan, Lin 2005), which converges
/// quadratically to the stabilising solution, followed by Newton-Kleinman refinement steps
/// (Hewer 1971) that bring the residual down to rounding. Used by the ZMP preview controller
/// (docs/theory/humanoid.md, "The walking controller": gains from the DARE at start-up).
#include <Eigen/Dense>

namespace flexgait::numerics {

struct DareResult {
  Eigen::MatrixXd P;    ///< stabilising solution (n x n), symmetric
  Eigen::MatrixXd K;    ///< optimal gain (m x n): u = −K x, K = (R + BᵀPB)⁻¹ BᵀPA
  double residual = 0;  ///< ||P − (AᵀPA − AᵀPB(R+BᵀPB)⁻¹BᵀPA + Q)||_max
  int iterations = 0;   ///< doubling iterations
};

/// Solves the DARE for A (n x n), B (n x m), Q (n x n, symmetric ≥ 0), R (m x m, symmetric > 0).
/// Throws std::invalid_argument on mismatched dimensions and std::runtime_error when the doubling
/// does not converge (no stabilising solution: (A, B) not stabilisable or (A, Q) not detectable).
DareResult solve_dare(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                      const Eigen::MatrixXd& R);

/// The residual of P in the DARE, max-norm.
double dare_residual(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                     const Eigen::MatrixXd& R, const Eigen::MatrixXd& P);

}  // namespace flexgait::numerics
