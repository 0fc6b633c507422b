// CVODE's Adams and BDF behind OdeIntegrator (numerics/cvode_backend.cpp): a Kepler orbit against
// its invariants and period, the step options (max_step, max_steps, max_order, error_scale), and
// its failure as an exception naming CVODE.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "flexgait/numerics/ode_integrator.hpp"

namespace flexgait::numerics {
namespace {

// The Kepler problem (μ = 1) from the pericentre of an orbit of eccentricity e and semi-major axis
// 1: period 2π, energy −1/2, angular momentum √(1 − e²).
class Kepler final : public OdeSystem {
 public:
  bool rhs(double, std::span<const double> y, std::span<double> yd) override {
    const double r3 = std::pow(y[0] * y[0] + y[1] * y[1], 1.5);
    yd[0] = y[2];
    yd[1] = y[3];
    yd[2] = -y[0] / r3;
    yd[3] = -y[1] / r3;
    return true;
  }
  void guards(double, std::span<const double>, std::span<double>) override {}
  static std::vector<double> pericentre(double e) { return {1.0 - e, 0.0, 0.0, std::sqrt((1.0 + e) / (1.0 - e))}; }
  static double energy(std::span<const double> y) {
    return 0.5 * (y[2] * y[2] + y[3] * y[3]) - 1.0 / std::hypot(y[0], y[1]);
  }
  static double momentum(std::span<const double> y) { return y[0] * y[3] - y[1] * y[2]; }
};

OdeOptions options(OdeMethod method) {
  OdeOptions o;
  o.method = method;
  o.rtol = 1e-11;
  o.atol = 1e-13;
  return o;
}

std::vector<double> run(OdeIntegrator& integ, const std::vector<double>& y0, double t_end) {
  integ.restart(0.0, y0, std::vector<int>{});
  while (integ.step(t_end) != StepStatus::StopTime) {
  }
  return {integ.state().begin(), integ.state().end()};
}

TEST(CvodeBackend, KeplerOrbitKeepsItsInvariantsAndCloses) {
  const double e = 0.5;
  for (OdeMethod method : {OdeMethod::Adams, OdeMethod::Bdf}) {
    Kepler kepler;
    OdeIntegrator integ(kepler, 4, options(method));
    const auto y0 = Kepler::pericentre(e);
    const auto y = run(integ, y0, 2 * std::numbers::pi);
    // rtol 1e-11 over one period with the pericentre's speed √3: the local errors add up to about
    // 1e-9 (Adams); BDF, of order ≤ 5 on a non-stiff problem, to about 1e-7. Bounds with a margin of 10.
    const double tol = method == OdeMethod::Adams ? 1e-8 : 1e-6;
    EXPECT_NEAR(Kepler::energy(y), -0.5, tol) << name_of(method);
    EXPECT_NEAR(Kepler::momentum(y), std::sqrt(1 - e * e), tol) << name_of(method);
    for (int i = 0; i < 4; ++i)
      EXPECT_NEAR(y[static_cast<std::size_t>(i)], y0[static_cast<std::size_t>(i)], 10 * tol) << i;
  }
}

TEST(CvodeBackend, MaxStepBoundsEveryInternalStep) {
  Kepler kepler;
  OdeOptions o = options(OdeMethod::Adams);
  o.max_step = 0.01;
  OdeIntegrator integ(kepler, 4, o);
  integ.restart(0.0, Kepler::pericentre(0.1), std::vector<int>{});
  double t_prev = 0.0;
  int steps = 0;
  while (integ.step(1.0) != StepStatus::StopTime) {
    EXPECT_LE(integ.time() - t_prev, 0.01 * (1 + 1e-12));
    t_prev = integ.time();
    ++steps;
  }
  EXPECT_GE(steps + 1, 100);  // 1 s in steps of at most 0.01 s
}

TEST(CvodeBackend, FirstOrderAdamsTakesManyMoreSteps) {
  // max_order 1 (forward/backward Euler pair): its steps shrink as rtol^(1/2) instead of rtol^(1/12).
  auto steps = [](int max_order) {
    Kepler kepler;
    OdeOptions o = options(OdeMethod::Adams);
    o.rtol = 1e-6;
    o.atol = 1e-8;
    o.max_order = max_order;
    OdeIntegrator integ(kepler, 4, o);
    run(integ, Kepler::pericentre(0.1), 1.0);
    return integ.stats().steps;
  };
  EXPECT_GT(steps(1), 10 * steps(0));
}

// (OdeOptions::max_steps cannot be tested here: the backend asks CVODE for one step per call,
// CV_ONE_STEP, so CVodeSetMaxNumSteps never binds.)
TEST(CvodeBackend, ARightHandSideThatKeepsFailingThrowsNamingCvode) {
  // ẏ = 1, whose evaluation fails at every t > 0: CVODE retries smaller steps until it gives up.
  class Walled final : public OdeSystem {
   public:
    bool rhs(double t, std::span<const double>, std::span<double> yd) override {
      yd[0] = 1.0;
      return t == 0.0;
    }
    void guards(double, std::span<const double>, std::span<double>) override {}
  } walled;
  for (OdeMethod method : {OdeMethod::Adams, OdeMethod::Bdf}) {
    OdeIntegrator integ(walled, 1, options(method));
    integ.restart(0.0, std::vector<double>{0.0}, std::vector<int>{});
    try {
      integ.step(1.0);
      ADD_FAILURE() << "no exception, t = " << integ.time();
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find("CVODE"), std::string::npos) << error.what();
      EXPECT_EQ(integ.time(), 0.0);
    }
  }
}

TEST(CvodeBackend, ErrorScaleOfTheWrongSizeIsRejected) {
  Kepler kepler;
  OdeOptions o = options(OdeMethod::Adams);
  o.error_scale = {1.0, 1.0};
  EXPECT_THROW(OdeIntegrator(kepler, 4, o), std::invalid_argument);
}

TEST(CvodeBackend, ErrorScaleLoosensTheTestOfAComponentMeasuredAgainstIt) {
  // A quadrature q̇ = 1 + 1e3·y₀² beside an oscillator, from q = 0: measured against itself its
  // allowance starts at atol; with error_scale 1e6 it is rtol·1e6 throughout, so CVODE takes
  // fewer steps, and q stays within that allowance of its closed form.
  class WithQuadrature final : public OdeSystem {
   public:
    bool rhs(double, std::span<const double> y, std::span<double> yd) override {
      yd[0] = y[1];
      yd[1] = -y[0];
      yd[2] = 1.0 + 1e3 * y[0] * y[0];
      return true;
    }
    void guards(double, std::span<const double>, std::span<double>) override {}
  };
  auto run_with = [](std::vector<double> scale) {
    WithQuadrature sys;
    OdeOptions o = options(OdeMethod::Adams);
    o.rtol = 1e-8;
    o.atol = 1e-10;
    o.error_scale = std::move(scale);
    OdeIntegrator integ(sys, 3, o);
    const auto y = run(integ, {1.0, 0.0, 0.0}, 10.0);
    return std::make_pair(y[2], integ.stats().steps);
  };
  const auto [q_tight, steps_tight] = run_with({});
  const auto [q_loose, steps_loose] = run_with({0.0, 0.0, 1e6});
  EXPECT_LT(steps_loose, steps_tight);
  // q(10) = 10 + 1e3 (5 + sin 20 / 4): both within their allowance (rtol·scale over the run, ×10).
  const double q = 10.0 + 1e3 * (5.0 + std::sin(20.0) / 4.0);
  EXPECT_NEAR(q_tight, q, 1e-8 * q * 10);
  EXPECT_NEAR(q_loose, q, 1e-8 * 1e6 * 10);
}

}  // namespace
}  // namespace flexgait::numerics
