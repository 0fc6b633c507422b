// ∂P/∂p by sensitivity (issue 18): the parameter column of the variational equations
// (flexible_wheel.hpp, ParameterDirection) against central differences of the whole map.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <string>
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
  if (std::string(p.key) == "rimless.mu") out.mu_s = out.mu_k = value;
  else p.field(out) = value;
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
TEST(ParameterSensitivity, MatchesCentralDifferencesOfTheMapForEveryParameterAndBehaviour) {
  for (double mu : {0.105, 0.13, 0.2, 0.6}) {
    const WheelParams w = testing::measured_wheel(mu);
    const SimulationOptions sim = testing::run_options(1);
    const FixedPointReport r = find_fixed_point(w, sim, AnalysisOptions{}, Model::Flexible, Section::Touchdown, {});
    ASSERT_TRUE(r.converged) << r.failure;
    const Eigen::VectorXd scale = r.point.scale(w);
    for (const Parameter& p : parameters()) {
      const double value = std::string(p.key) == "rimless.mu" ? w.mu_k : p.field(const_cast<WheelParams&>(w));
      SimulationOptions map_opt = sim;
      map_opt.rtol = AnalysisOptions{}.rtol;
      map_opt.atol = AnalysisOptions{}.atol;
      PoincareMap map(w, map_opt, Model::Flexible, Section::Touchdown);
      const double h = 6e-6 * std::abs(value);
      map.set_parameter(ParameterDirection{with(w, p, value + h), with(w, p, value - h), h});
      Eigen::MatrixXd J;
      Eigen::VectorXd J_p;
      const auto e = map.jacobian_and_parameter_derivative(r.point, J, J_p);
      ASSERT_FALSE(e.has_value()) << p.key << ": " << *e;
      EXPECT_LE((J - r.jacobian).lpNorm<Eigen::Infinity>(), 1e-6) << p.key;  // the state columns as before

      SimulationOptions fine = sim;
      fine.rtol = 1e-13;
      fine.atol = 1e-16;
      const double H = 3e-5 * std::abs(value);
      PoincareMap up(with(w, p, value + H), fine, Model::Flexible, Section::Touchdown);
      PoincareMap down(with(w, p, value - H), fine, Model::Flexible, Section::Touchdown);
      const MapStep a = up.apply(r.point), b = down.apply(r.point);
      ASSERT_FALSE(a.failure || b.failure) << p.key << ": " << a.failure.value_or("") << b.failure.value_or("");
      const Eigen::VectorXd reference = (a.next.z - b.next.z) / (2 * H);
      const double error = ((J_p - reference) * std::abs(value)).cwiseQuotient(scale).lpNorm<Eigen::Infinity>();
      EXPECT_LE(error, 2e-8) << "mu = " << mu << ", " << p.key << ": dP/dp " << J_p.transpose() << " vs "
                             << reference.transpose();
      std::ostringstream at, err;
      at << "mu" << mu << "_" << p.key;
      err << std::scientific << error;
      RecordProperty(at.str(), err.str());
    }
  }
}

}  // namespace
}  // namespace flexgait::rimless
