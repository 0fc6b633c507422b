#pragma once
/// \file ode_system.hpp
/// What an event-driven integrator needs from a model: a smooth flow ẏ = f(t, y) valid in
/// the current mode, and guard functions g(t, y) whose zero crossings end the mode.
#include <span>

namespace flexgait::numerics {

/// A guard's crossing direction: +1 upward only, -1 downward only, 0 both, or kNoGuard: the slot
/// holds no guard in the current mode. A model with a fixed layout of guard slots, some of them
/// unused in some modes, writes a finite nonzero constant into an unused slot (it never crosses);
/// with kNoGuard the integrator's guard watch does not look at it at all (its crossing checks
/// cost what the mode's own guards cost) and never fires it.
inline constexpr int kNoGuard = 2;

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  /// ẏ = f(t, y). \param[in] y state (dim n) \param[out] ydot derivative (dim n).
  /// \return false if the state is outside the model's domain (the solver then retries smaller).
  virtual bool rhs(double t, std::span<const double> y, std::span<double> ydot) = 0;
  /// The flow whose derivative the sensitivities follow (default: rhs). A system whose rhs holds a
  /// stabilising term that vanishes on every nearby solution may drop it here.
  virtual bool linearization_rhs(double t, std::span<const double> y, std::span<double> ydot) {
    return rhs(t, y, ydot);
  }
  /// ∂f/∂p_j at (t, y) for OdeOptions::parameter_columns (default: 0, f does not depend on it).
  virtual bool parameter_derivative(double, std::span<const double>, int, std::span<double> dfdp) {
    for (double& v : dfdp) v = 0.0;
    return true;
  }
  /// Guard values g(t, y) (dim = number of guards given to the integrator's restart).
  virtual void guards(double t, std::span<const double> y, std::span<double> g) = 0;
  /// Guard i alone, the same number guards() writes to g[i] (root finding asks for one guard at
  /// a time; a system whose guards are costly together may compute one cheaply). `scratch` has
  /// the dim of g. Default: all guards into scratch.
  virtual double guard(double t, std::span<const double> y, int i, std::span<double> scratch) {
    guards(t, y, scratch);
    return scratch[static_cast<std::size_t>(i)];
  }
};

}  // namespace flexgait::numerics
