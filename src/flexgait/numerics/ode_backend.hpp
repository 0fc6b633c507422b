#pragma once
/// \file ode_backend.hpp
/// The methods behind OdeIntegrator (ode_integrator.hpp, whose functions these mirror): CVODE's
/// Adams and BDF (cvode_backend.cpp) and DOP853 (dop853_backend.cpp). Internal to numerics.
#include <memory>
#include <span>

#include "flexgait/numerics/ode_integrator.hpp"

namespace flexgait::numerics {

class OdeBackend {
 public:
  virtual ~OdeBackend() = default;
  /// S: column-major n×n sensitivities at t, or empty without sensitivities.
  virtual void restart(double t, std::span<const double> y, std::span<const int> directions,
                       std::span<const double> S) = 0;
  virtual void sensitivities(std::span<double> S) const = 0;
  virtual StepStatus step(double t_stop) = 0;
  virtual double time() const = 0;
  virtual std::span<const double> state() const = 0;
  virtual void interpolate(double t, std::span<double> y) const = 0;
  virtual std::span<const int> guards_fired() const = 0;
  virtual OdeStats stats() const = 0;
};

std::unique_ptr<OdeBackend> make_cvode_backend(OdeSystem& system, int n, const OdeOptions& options);
std::unique_ptr<OdeBackend> make_dop853_backend(OdeSystem& system, int n, const OdeOptions& options);

}  // namespace flexgait::numerics
