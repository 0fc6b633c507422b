// ∂P/∂p by sensitivity: the parameter column of the variational equations
// (flexible_wheel.hpp, ParameterDirection) against central differences of the whole map.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/poincare.hpp"
#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

struct Parameter {
  const char* key;
  std::function<double&(WheelParams&)> field;  // μ: both coefficients (rimless.mu)
};

WheelParams with(const WheelParams& w, const Parameter& p, double value) {
  WheelParams out = w;
  if (std::string(p.key) == "rimless.mu")
    out.mu_s = out.mu_k = value;
  else
    p.field(out) = value;
  return out;
}

const std::vector<Parameter>& parameters() {
  static const std::vector<Parameter> all{
      {"rimless.mu", [](WheelParams& w) -> double& { return w.mu_k; }},
      {"rimless.slope", [](WheelParams& w) -> double& { return w.slope; }},
      {"rimless.K", [](WheelParams& w) -> double& { return w.K; }},
      {"rimless.C", [](WheelParams& w) -> double& { return w.C; }},
      {"rimless.I", [](WheelParams& w) -> double& { return w.I; }},
      {"rimless.L0", [](WheelParams& w) -> double& { return w.L0; }},
      {"rimless.m", [](WheelParams& w) -> double& { return w.m; }},
      {"rimless.g", [](WheelParams& w) -> double& { return w.g; }},
  };
  return all;
}

// For each behaviour's gait and each parameter, ∂P/∂p from one variational run (the state
// integrated at rtol 1e-12, ∂f/∂p, ∂g/∂p and ∂R/∂p by ε^(1/3) central differences of algebraic
// functions) equals central differences of the map integrated at rtol 1e-13 with a step of
// 3e-5 |p|. Compared per unit relative change of p, in units of z's scale: that reference's
// error is the integration noise over the step plus its curvature term (~1e-9 (H / 3e-5 |p|)²);
// measured, the largest difference over the 32 cases is 3.8e-9: bound 2e-8.
/// max over z's components of |∂P/∂p (sensitivity) - central differences (step H |p|)| |p| / scale,
/// for the fixed point of wheel w on `section` integrated with `sim`'s method (as described below).
double sensitivity_error(const WheelParams& w, SimulationOptions sim, Section section, const Parameter& p,
                         double H_relative = 3e-5) {
  const FixedPointReport r = find_fixed_point(w, sim, AnalysisOptions{}, Model::Flexible, section, {});
  EXPECT_TRUE(r.converged) << r.failure();
  if (!r.converged) return INFINITY;
  const double value = std::string(p.key) == "rimless.mu" ? w.mu_k : p.field(const_cast<WheelParams&>(w));
  SimulationOptions map_opt = sim;
  map_opt.rtol = AnalysisOptions{}.rtol;
  map_opt.atol = AnalysisOptions{}.atol;
  PoincareMap map(w, map_opt, Model::Flexible, section);
  const double h = 6e-6 * std::abs(value);
  map.set_parameter(ParameterDirection{with(w, p, value + h), with(w, p, value - h), h});
  Eigen::MatrixXd J;
  Eigen::VectorXd J_p;
  const auto e = map.jacobian_and_parameter_derivative(r.point, J, J_p);
  EXPECT_FALSE(e.has_value()) << p.key << ": " << e.value_or("");
  if (e) return INFINITY;
  EXPECT_LE((J - r.jacobian).lpNorm<Eigen::Infinity>(), 1e-6) << p.key;  // the state columns as before

  SimulationOptions fine = sim;
  fine.rtol = 1e-13;
  fine.atol = 1e-16;
  const double H = H_relative * std::abs(value);
  PoincareMap up(with(w, p, value + H), fine, Model::Flexible, section);
  PoincareMap down(with(w, p, value - H), fine, Model::Flexible, section);
  const MapStep a = up.apply(r.point), b = down.apply(r.point);
  EXPECT_FALSE(a.failure || b.failure) << p.key << ": " << text_of(a.failure) << text_of(b.failure);
  if (a.failure || b.failure) return INFINITY;
  const Eigen::VectorXd reference = (a.next.z - b.next.z) / (2 * H);
  return ((J_p - reference) * std::abs(value)).cwiseQuotient(r.point.scale(w)).lpNorm<Eigen::Infinity>();
}

// For each behaviour's gait and each parameter, ∂P/∂p from one variational run (the state
// integrated at rtol 1e-12, ∂f/∂p, ∂g/∂p and ∂R/∂p by ε^(1/3) central differences of algebraic
// functions) equals central differences of the map integrated at rtol 1e-13 with a step of
// 3e-5 |p|. Compared per unit relative change of p, in units of z's scale: that reference's
// error is the integration noise over the step plus its curvature term (~1e-9 (H / 3e-5 |p|)²);
// measured, the largest difference over the 32 cases is 3.8e-9: bound 2e-8.
TEST(ParameterSensitivity, MatchesCentralDifferencesOfTheMapForEveryParameterAndBehaviour) {
  for (double mu : {0.105, 0.13, 0.2, 0.6}) {
    for (const Parameter& p : parameters()) {
      const double error =
          sensitivity_error(testing::measured_wheel(mu), testing::run_options(1), Section::Touchdown, p);
      EXPECT_LE(error, 2e-8) << "mu = " << mu << ", " << p.key;
      std::ostringstream at, err;
      at << "mu" << mu << "_" << p.key;
      err << std::scientific << error;
      RecordProperty(at.str(), err.str());
    }
  }
}

// The same on the upright section (its guard, sin β, holds no parameter; y = z₀ there) and with
// CVODE's Adams method carrying the parameter column (staggered sensitivities) instead of DOP853's
// augmented steps (slip-stick-slip, μ = 0.13). The upright map bends more in L0: its reference's
// curvature term is 3.6e-8 at H = 3e-5 |p| (4.0e-7 at 1e-4: as H²), so H = 1e-5 |p| there
// (measured 4.3e-9).
TEST(ParameterSensitivity, HoldsOnTheUprightSectionAndWithAdams) {
  SimulationOptions adams = testing::run_options(1);
  adams.method = numerics::OdeMethod::Adams;
  for (const auto& [sim, section] :
       {std::pair{testing::run_options(1), Section::Upright}, std::pair{adams, Section::Touchdown}})
    for (const Parameter& p : parameters()) {
      const double error =
          sensitivity_error(testing::measured_wheel(0.13), sim, section, p, section == Section::Upright ? 1e-5 : 3e-5);
      EXPECT_LE(error, 2e-8) << p.key << ", " << name_of(section) << ", " << name_of(sim.method);
      std::ostringstream at, err;
      at << name_of(section) << "_" << name_of(sim.method) << "_" << p.key;
      err << std::scientific << error;
      RecordProperty(at.str(), err.str());
    }
}

}  // namespace
}  // namespace flexgait::rimless
