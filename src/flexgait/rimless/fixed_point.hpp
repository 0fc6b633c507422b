#pragma once
/// \file fixed_point.hpp
/// Periodic gaits of the rimless wheel: a fixed point of the Poincaré map by Newton-Raphson,
/// its Floquet multipliers (eigenvalues of the map's Jacobian) and a stability verdict.
#include <complex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/numerics/newton.hpp"
#include "flexgait/rimless/poincare.hpp"

namespace flexgait::rimless {

/// How fixed points are searched (config keys `analysis.*`).
struct AnalysisOptions {
  int transient_steps = 20;  ///< steps simulated from the initial state before Newton starts
  double rtol = 1e-12;       ///< CVODE tolerance of every map evaluation
  double atol = 1e-15;
  numerics::NewtonOptions newton;  ///< tolerance 1e-10, 30 iterations

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("analysis.transient_steps", s.transient_steps,
      {.doc = "steps simulated from the initial state before the Newton iteration starts",
       .bounds = closed(0, 100000)});
    v("analysis.rtol", s.rtol,
      {.doc = "CVODE relative tolerance of every Poincare-map evaluation", .bounds = closed(1e-14, 1e-4)});
    v("analysis.atol", s.atol,
      {.doc = "CVODE absolute tolerance of every Poincare-map evaluation", .bounds = closed(1e-17, 1e-4)});
    v("analysis.newton_tol", s.newton.tolerance,
      {.doc = "Newton convergence: max-norm of P(z) - z", .bounds = closed(1e-15, 1e-2)});
    v("analysis.max_iterations", s.newton.max_iterations,
      {.doc = "Newton iterations allowed", .bounds = closed(1, 1000)});
  }
};
inline Schema analysis_schema() {
  return schema_of<AnalysisOptions>();
}
inline AnalysisOptions analysis_from_config(const Config& config) {
  return record_from_config<AnalysisOptions>(config);
}
/// The simulation options of a Poincaré-map evaluation: the analysis tolerances, no log.
SimulationOptions map_options(const SimulationOptions& sim, const AnalysisOptions& opt);

/// The outcome of a fixed-point search. Every member has a defined value in every outcome: when
/// the search failed (`converged` false, `failure()` says why) the Jacobians and multipliers are
/// empty and gait, period, speed and dissipated keep their zero defaults; `point` holds the last
/// Newton iterate, or an empty z when the transient never reached the section.
struct FixedPointReport {
  bool converged = false;
  std::optional<Failure> transient_failure;               ///< why the transient gave Newton no initial guess
  std::optional<numerics::NewtonFailure> newton_failure;  ///< else why Newton found no fixed point
  std::string newton_failure_detail;                      ///< ... and its detail (NewtonResult::failure_detail)
  int iterations = 0;
  double residual = 0;  ///< ||P(z) - z||_inf at `point` (0 when there is no iterate)
  std::vector<numerics::NewtonIteration> history;
  SectionState point;               ///< the fixed point (or the last iterate; z empty: none)
  Eigen::MatrixXd jacobian;         ///< ∂P/∂z: variational (exact) when available, else central differences
  bool jacobian_exact = false;      ///< from forward sensitivities and saltation matrices
  Eigen::MatrixXd jacobian_fd;      ///< ∂P/∂z by central differences (Newton's)
  double jacobian_difference = -1;  ///< max |exact - central differences| (-1: no exact Jacobian)
  std::string jacobian_note;        ///< why there is no exact Jacobian
  std::vector<std::complex<double>> multipliers;     ///< eigenvalues of `jacobian`, largest modulus first
  std::vector<std::complex<double>> multipliers_fd;  ///< eigenvalues of jacobian_fd
  bool stable = false;                               ///< every multiplier strictly inside the unit circle
  std::string gait;                                  ///< stance-foot phases of the periodic step
  double period = 0;                                 ///< [s]
  double speed = 0;                                  ///< mean hub speed along the slope [m/s]
  double dissipated = 0;                             ///< energy dissipated per cycle [J]

  /// "" when converged; else why not, as files show it: "no initial guess: " and the transient's
  /// failure, or Newton's (numerics::newton_failure_text).
  std::string failure() const;
};

/// Settles on the section from `initial`, then runs Newton from there.
FixedPointReport find_fixed_point(const WheelParams& w, const SimulationOptions& sim, const AnalysisOptions& opt,
                                  Model model, Section section, const InitialState& initial);

/// Newton from a given section point.
FixedPointReport find_fixed_point_from(const WheelParams& w, const SimulationOptions& sim, const AnalysisOptions& opt,
                                       const SectionState& guess);

/// The report as a record (keys: converged, iterations, residual, state, state_names, mode, multipliers
/// as [re, im] pairs, stable, gait, period, speed, dissipated_per_cycle, history, failure). A failed
/// search has null state, multipliers, gait, period, speed and dissipated_per_cycle, and its last
/// Newton iterate (if any) under last_iterate.
nlohmann::ordered_json fixed_point_record(const FixedPointReport& report);
/// fixed_point.json: fixed_point_record's text.
std::string fixed_point_json(const FixedPointReport& report);

}  // namespace flexgait::rimless
