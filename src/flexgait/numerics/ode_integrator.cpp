#include "flexgait/numerics/ode_integrator.hpp"

#include <stdexcept>

#include "flexgait/numerics/ode_backend.hpp"

namespace flexgait::numerics {

OdeIntegrator::OdeIntegrator(OdeSystem& system, int n, const OdeOptions& options)
    : backend_(options.method == OdeMethod::Dop853 ? make_dop853_backend(system, n, options)
                                                   : make_cvode_backend(system, n, options)),
      n_(n),
      columns_(n + options.parameter_columns),
      sensitivities_(options.sensitivities) {}

OdeIntegrator::~OdeIntegrator() = default;

void OdeIntegrator::restart(double t, std::span<const double> y, std::span<const int> directions) {
  if (static_cast<int>(y.size()) != n_) throw std::invalid_argument("OdeIntegrator::restart: wrong state size");
  backend_->restart(t, y, directions, {});
}

void OdeIntegrator::restart(double t, std::span<const double> y, std::span<const int> directions,
                            std::span<const double> S) {
  if (!sensitivities_) throw std::logic_error("OdeIntegrator: sensitivities were not enabled");
  if (static_cast<int>(y.size()) != n_) throw std::invalid_argument("OdeIntegrator::restart: wrong state size");
  if (S.size() != static_cast<std::size_t>(n_) * static_cast<std::size_t>(columns_))
    throw std::invalid_argument("OdeIntegrator::restart: sensitivities must be n x (n + parameter_columns)");
  backend_->restart(t, y, directions, S);
}

void OdeIntegrator::sensitivities(std::span<double> S) const {
  if (!sensitivities_) throw std::logic_error("OdeIntegrator: sensitivities were not enabled");
  backend_->sensitivities(S);
}

StepStatus OdeIntegrator::step(double t_stop) {
  return backend_->step(t_stop);
}
double OdeIntegrator::time() const {
  return backend_->time();
}
std::span<const double> OdeIntegrator::state() const {
  return backend_->state();
}
void OdeIntegrator::interpolate(double t, std::span<double> y) const {
  backend_->interpolate(t, y);
}
std::span<const int> OdeIntegrator::guards_fired() const {
  return backend_->guards_fired();
}
OdeStats OdeIntegrator::stats() const {
  return backend_->stats();
}

}  // namespace flexgait::numerics
