#pragma once
/// \file ode_integrator.hpp
/// Event-locating integrator for hybrid systems: SUNDIALS CVODE (variable-order Adams or BDF,
/// cvode_backend.cpp) or DOP853 (Dormand–Prince 8(5,3), dop853_backend.cpp), each with root
/// finding on its dense output. SUNDIALS stays behind this interface.
///
/// Use: restart() at the start of every mode (after every reset map, with the mode's guard
/// directions), then step() until it reports a guard.
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/numerics/ode_system.hpp"

namespace flexgait::numerics {

/// Adams, Bdf: CVODE's variable-order linear multistep methods (orders 1–12 and 1–5). Dop853: the
/// explicit Runge–Kutta pair of order 8 (dop853.hpp), restarted cheaply after every event.
enum class OdeMethod { Adams, Bdf, Dop853 };
constexpr std::array<EnumName<OdeMethod>, 3> enum_names(OdeMethod) {
  return {{{OdeMethod::Adams, "adams"}, {OdeMethod::Bdf, "bdf"}, {OdeMethod::Dop853, "dop853"}}};
}

struct OdeOptions {
  double rtol = 1e-10;    ///< relative tolerance
  double atol = 1e-12;    ///< absolute tolerance (state units)
  double max_step = 0.0;  ///< largest internal step [s]; 0: no limit
  OdeMethod method = OdeMethod::Adams;
  std::int64_t max_steps = 1'000'000;  ///< internal steps allowed per step() call
  int max_order = 0;                   ///< largest method order (CVODE only); 0: CVODE's default (12 Adams, 5 BDF)
  /// Integrate the variational equation Ṡ = (∂f/∂y) S as well, one column per state, outside the
  /// error test (CVODES forward sensitivities with the staggered corrector; DOP853: the same
  /// Runge–Kutta steps on the augmented state). ∂f/∂y·s comes from centered directional
  /// differences of OdeSystem::linearization_rhs.
  bool sensitivities = false;
  /// With sensitivities: this many parameter columns after the n state columns (S is then
  /// n×(n + m)): column n + j follows ṡ = (∂f/∂y) s + ∂f/∂p_j (OdeSystem::parameter_derivative),
  /// the sensitivity to a parameter treated as a state with ṗ = 0.
  int parameter_columns = 0;
  /// Per component (empty: none), the size the relative tolerance refers to: where > 0, the
  /// error weight of component i is 1 / (rtol · error_scale[i] + atol) instead of
  /// 1 / (rtol · |y_i| + atol). For quadratures that only grow (dissipated work): measured
  /// against their own size their error allowance would grow with the run, and so would the
  /// error of every balance they enter.
  std::vector<double> error_scale;
};

struct OdeStats {
  std::int64_t steps = 0;        ///< internal solver steps
  std::int64_t rhs_evals = 0;    ///< right-hand-side evaluations
  std::int64_t guard_evals = 0;  ///< guard evaluations
  std::int64_t restarts = 0;     ///< restarts (mode changes)
};

enum class StepStatus {
  Step,      ///< one internal step taken; no guard crossed
  Guard,     ///< a guard crossed; time() is the crossing, guards_fired() says which
  StopTime,  ///< reached the stop time
};

class OdeBackend;

class OdeIntegrator {
 public:
  /// \param system the flow and guards (must outlive the integrator) \param n state dimension
  OdeIntegrator(OdeSystem& system, int n, const OdeOptions& options);
  ~OdeIntegrator();
  OdeIntegrator(const OdeIntegrator&) = delete;
  OdeIntegrator& operator=(const OdeIntegrator&) = delete;

  /// Starts a new smooth segment at (t, y) with guards of the given crossing directions
  /// (+1 upward only, -1 downward only, 0 both). Guards that are exactly zero at t are
  /// ignored until they move away (CVODE's rule).
  void restart(double t, std::span<const double> y, std::span<const int> directions);
  /// As restart(), with the sensitivities S = ∂y/∂(y_ref, p) at t given column-major (n×(n + m),
  /// m = OdeOptions::parameter_columns); needs OdeOptions::sensitivities.
  void restart(double t, std::span<const double> y, std::span<const int> directions, std::span<const double> S);
  /// Sensitivities ∂y(time())/∂(y_ref, p), column-major n×(n + m) (after a step; at the guard
  /// crossing after StepStatus::Guard).
  void sensitivities(std::span<double> S) const;
  /// Takes one internal step, never past t_stop. After a guard crossing the step ends at the
  /// crossing. Throws std::runtime_error with the solver's message if it fails.
  StepStatus step(double t_stop);
  double time() const;
  /// State at time() (dim n).
  std::span<const double> state() const;
  /// Dense-output interpolant over the last step: writes y(t) for t in [time()-h, time()]
  /// (CVODE: its last internal step, which may reach past a guard crossing).
  void interpolate(double t, std::span<double> y) const;
  /// Per guard, after StepStatus::Guard: +1 crossed upward, -1 downward, 0 not crossed.
  std::span<const int> guards_fired() const;
  OdeStats stats() const;

 private:
  std::unique_ptr<OdeBackend> backend_;
  int n_;               // state dimension
  int columns_;         // sensitivity columns: n + OdeOptions::parameter_columns
  bool sensitivities_;  // OdeOptions::sensitivities
};

}  // namespace flexgait::numerics
