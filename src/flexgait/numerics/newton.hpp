#pragma once
/// \file newton.hpp
/// Fixed points of maps z ↦ P(z) by Newton-Raphson on F(z) = P(z) - z, with a central-difference
/// Jacobian and a backtracking line search; Floquet multipliers as the eigenvalues of ∂P/∂z.
#include <Eigen/Dense>

#include <array>
#include <complex>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/numerics/reason_table.hpp"

namespace flexgait::numerics {

/// P: writes P(z) into `out` (same dimension as z), or returns why it cannot be evaluated there
/// (a simulation that failed, a different gait, ...).
using VectorMap = std::function<std::optional<std::string>(const Eigen::VectorXd& z, Eigen::VectorXd& out)>;

struct NewtonOptions {
  double tolerance = 1e-10;  ///< converged when ||P(z) - z||_inf <= tolerance (state units)
  int max_iterations = 30;
  /// Central-difference step h_i = this · max(|z_i|, scale_i). 3e-5 balances the map's integration
  /// noise (~1e-11 at rtol 1e-12) against the truncation error (measured ~170 h² on the wheel).
  double fd_relative_step = 3e-5;
  double min_damping = 1.0 / 1024;  ///< smallest line-search factor before giving up
};

struct NewtonIteration {
  int iteration = 0;
  double residual = 0;   ///< ||P(z) - z||_inf at the start of the iteration
  double step_norm = 0;  ///< ||Δz||_inf of the accepted step
  double damping = 1;    ///< line-search factor of the accepted step
};

/// Why Newton stopped without a fixed point (NewtonResult::failure_reason, with failure_detail;
/// failure() says it in words, reason_table.hpp).
enum class NewtonFailure {
  MapAtGuess,      ///< the map cannot be evaluated at the initial guess (detail: the map's message)
  DifferenceStep,  ///< a finite-difference step of the Jacobian left the map's domain (detail: which column, why)
  NoConvergence,   ///< max_iterations without reaching the tolerance (detail: the iterations and the residual)
  Singular,        ///< J − I singular: a multiplier equals 1, no isolated fixed point
  NoDecrease,      ///< the line search found no decrease along the Newton direction (no root nearby)
  LeftBasin,       ///< every damped step left the map's domain (detail: the map's last message)
};

inline constexpr std::array<ReasonEntry<NewtonFailure>, 6> kNewtonFailureTable{{
    {NewtonFailure::MapAtGuess, "map_at_guess", "the map cannot be evaluated at the initial guess: {}"},
    {NewtonFailure::DifferenceStep, "difference_step", "a finite-difference step left the basin ({})"},
    {NewtonFailure::NoConvergence, "no_convergence", "no convergence in {}"},
    {NewtonFailure::Singular, "singular", "singular Newton matrix (a multiplier equals 1): no isolated fixed point"},
    {NewtonFailure::NoDecrease, "no_decrease",
     "line search failed: no decrease along the Newton direction (no root nearby)"},
    {NewtonFailure::LeftBasin, "left_basin", "left the basin: {}"},
}};
constexpr std::array<EnumName<NewtonFailure>, kNewtonFailureTable.size()> enum_names(NewtonFailure) {
  return reason_names(kNewtonFailureTable);
}

/// The words of a Newton failure (kNewtonFailureTable's sentence with the detail).
std::string newton_failure_text(NewtonFailure reason, std::string_view detail);

struct NewtonResult {
  bool converged = false;
  Eigen::VectorXd z;    ///< last iterate (the fixed point when converged)
  double residual = 0;  ///< ||P(z) - z||_inf at z
  int iterations = 0;
  std::vector<NewtonIteration> history;
  Eigen::MatrixXd jacobian;                     ///< ∂P/∂z at z (central differences)
  std::optional<NewtonFailure> failure_reason;  ///< empty when converged
  std::string failure_detail;                   ///< the numbers or the map's message behind the reason

  /// Why it did not converge, in words ("" when it did): newton_failure_text(reason, detail).
  std::string failure() const;
};

/// ∂P/∂z by central differences with steps h (dim z). Returns the failure of a map evaluation.
std::optional<std::string> central_difference_jacobian(const VectorMap& P, const Eigen::VectorXd& z,
                                                       const Eigen::VectorXd& h, Eigen::MatrixXd& J);

/// Newton-Raphson from z0. `scale` (dim z, > 0) sets the finite-difference steps.
NewtonResult newton_fixed_point(const VectorMap& P, const Eigen::VectorXd& z0, const Eigen::VectorXd& scale,
                                const NewtonOptions& options = {});

/// Eigenvalues of J sorted by modulus, largest first (ties: by real part, then imaginary).
std::vector<std::complex<double>> floquet_multipliers(const Eigen::MatrixXd& J);

}  // namespace flexgait::numerics
