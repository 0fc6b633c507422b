// The event-locating integrator against analytic crossings.
#include "flexgait/numerics/ode_integrator.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

namespace flexgait::numerics {
namespace {

// Harmonic oscillator y = (cos t, -sin t); guard y0 - 0.5 crosses downward at t = π/3 + 2πk,
// upward at t = 5π/3 + 2πk.
class Oscillator final : public OdeSystem {
 public:
  bool rhs(double, std::span<const double> y, std::span<double> yd) override {
    yd[0] = y[1];
    yd[1] = -y[0];
    return true;
  }
  void guards(double, std::span<const double> y, std::span<double> g) override { g[0] = y[0] - 0.5; }
};

OdeOptions tight(OdeMethod method = OdeMethod::Adams, bool sensitivities = false) {
  OdeOptions o;
  o.rtol = 1e-12;
  o.atol = 1e-14;
  o.method = method;
  o.sensitivities = sensitivities;
  return o;
}

std::vector<double> crossings(OdeMethod method, int direction, double t_end) {
  Oscillator osc;
  OdeIntegrator integ(osc, 2, tight(method));
  const std::vector<double> y0{1.0, 0.0};
  const std::vector<int> dirs{direction};
  integ.restart(0.0, y0, dirs);
  std::vector<double> times;
  while (true) {
    const StepStatus st = integ.step(t_end);
    if (st == StepStatus::StopTime) break;
    if (st == StepStatus::Guard) {
      times.push_back(integ.time());
      EXPECT_EQ(integ.guards_fired()[0], integ.state()[1] < 0 ? -1 : 1);
    }
  }
  return times;
}

TEST(OdeIntegrator, LocatesCrossingsToAnalyticTimes) {
  for (OdeMethod method : {OdeMethod::Adams, OdeMethod::Bdf, OdeMethod::Dop853}) {
    const auto down = crossings(method, -1, 13.0);
    ASSERT_EQ(down.size(), 2u);
    // rtol 1e-12 over two periods: the crossing times agree to 1e-9 s.
    EXPECT_NEAR(down[0], std::numbers::pi / 3, 1e-9);
    EXPECT_NEAR(down[1], std::numbers::pi / 3 + 2 * std::numbers::pi, 1e-9);
    const auto both = crossings(method, 0, 13.0);
    ASSERT_EQ(both.size(), 4u);
    EXPECT_NEAR(both[1], 5 * std::numbers::pi / 3, 1e-9);
  }
}

// DOP853 locates the crossings on its dense output to ~1e-12 s (rtol 1e-12, two periods; the
// bracketing tolerance is 100 u |t| ≈ 3e-13 s).
TEST(OdeIntegrator, Dop853LocatesCrossingsTo1e12) {
  const auto both = crossings(OdeMethod::Dop853, 0, 13.0);
  ASSERT_EQ(both.size(), 4u);
  const double pi = std::numbers::pi;
  const std::array<double, 4> expected{pi / 3, 5 * pi / 3, pi / 3 + 2 * pi, 5 * pi / 3 + 2 * pi};
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(both[k], expected[k], 2e-12) << k;
}

// Two guards crossing in one step: the earlier fires alone, the later at its own time.
TEST(OdeIntegrator, EarliestOfTwoGuardsFiresFirst) {
  class TwoGuards final : public OdeSystem {
   public:
    bool rhs(double, std::span<const double>, std::span<double> yd) override {
      yd[0] = 1.0;
      return true;
    }
    void guards(double, std::span<const double> y, std::span<double> g) override {
      g[0] = y[0] - 0.30;
      g[1] = y[0] - 0.31;
    }
  } sys;
  for (OdeMethod method : {OdeMethod::Adams, OdeMethod::Dop853}) {
    OdeIntegrator integ(sys, 1, tight(method));
    integ.restart(0.0, std::vector<double>{0.0}, std::vector<int>{+1, +1});
    std::vector<std::pair<double, int>> hits;
    while (integ.step(1.0) != StepStatus::StopTime)
      if (integ.time() < 1.0 && integ.guards_fired()[0] + integ.guards_fired()[1] == 1)
        hits.emplace_back(integ.time(), integ.guards_fired()[0] == 1 ? 0 : 1);
    ASSERT_EQ(hits.size(), 2u);
    EXPECT_NEAR(hits[0].first, 0.30, 1e-12);
    EXPECT_EQ(hits[0].second, 0);
    EXPECT_NEAR(hits[1].first, 0.31, 1e-12);
    EXPECT_EQ(hits[1].second, 1);
  }
}

TEST(OdeIntegrator, GuardAtZeroOnRestartDoesNotFireThere) {
  for (OdeMethod method : {OdeMethod::Adams, OdeMethod::Dop853}) {
    Oscillator osc;
    OdeIntegrator integ(osc, 2, tight(method));
    // Start exactly on the guard (y0 = 0.5, moving down): CVODE must not report t = 0.
    const std::vector<double> y0{0.5, -std::sqrt(0.75)};
    const std::vector<int> dirs{0};
    integ.restart(0.0, y0, dirs);
    double first = -1;
    while (first < 0) {
      if (integ.step(10.0) == StepStatus::Guard) first = integ.time();
    }
    EXPECT_NEAR(first, 4 * std::numbers::pi / 3, 1e-9);  // the next crossing, upward
  }
}

TEST(OdeIntegrator, DenseOutputMatchesTheSolution) {
  for (OdeMethod method : {OdeMethod::Adams, OdeMethod::Dop853}) {
    Oscillator osc;
    OdeIntegrator integ(osc, 2, tight(method));
    const std::vector<double> y0{1.0, 0.0};
    integ.restart(0.0, y0, std::vector<int>{});
    std::vector<double> y(2);
    double t_prev = 0;
    while (integ.time() < 3.0) {
      integ.step(3.0);
      const double tm = 0.5 * (t_prev + integ.time());
      integ.interpolate(tm, y);
      EXPECT_NEAR(y[0], std::cos(tm), 1e-9);
      t_prev = integ.time();
    }
    EXPECT_GT(integ.stats().steps, 10);
  }
}

// Forward sensitivities of the oscillator: ∂y(t)/∂y(0) is the rotation by -t.
TEST(OdeIntegrator, SensitivitiesOfTheOscillatorAreARotation) {
  for (OdeMethod method : {OdeMethod::Adams, OdeMethod::Dop853}) {
    Oscillator osc;
    OdeIntegrator integ(osc, 2, tight(method, true));
    const std::vector<double> y0{0.3, -0.7};
    const std::vector<double> S0{1.0, 0.0, 0.0, 1.0};  // column-major identity
    integ.restart(0.0, y0, std::vector<int>{}, S0);
    while (integ.step(2.0) != StepStatus::StopTime) {
    }
    std::vector<double> S(4);
    integ.sensitivities(S);
    const double c = std::cos(2.0), s = std::sin(2.0);
    // y(t) = [[c, s], [-s, c]] y0; column-major S = (c, -s, s, c). Tolerance: rtol 1e-12 over a third of a period.
    EXPECT_NEAR(S[0], c, 1e-9);
    EXPECT_NEAR(S[1], -s, 1e-9);
    EXPECT_NEAR(S[2], s, 1e-9);
    EXPECT_NEAR(S[3], c, 1e-9);
  }
}

// A parameter column (OdeOptions::parameter_columns): the oscillator of frequency ω, ẏ = ω (y₁, -y₀),
// y(t) = (cos ωt, -sin ωt) from (1, 0), so ∂y/∂ω = -t (sin ωt, cos ωt); the state columns unchanged.
TEST(OdeIntegrator, ParameterColumnIsTheDerivativeInTheParameter) {
  class Tuned final : public OdeSystem {
   public:
    double omega = 1.3;
    bool rhs(double, std::span<const double> y, std::span<double> yd) override {
      yd[0] = omega * y[1];
      yd[1] = -omega * y[0];
      return true;
    }
    bool parameter_derivative(double, std::span<const double> y, int j, std::span<double> dfdp) override {
      EXPECT_EQ(j, 0);
      dfdp[0] = y[1];
      dfdp[1] = -y[0];
      return true;
    }
    void guards(double, std::span<const double>, std::span<double>) override {}
  };
  for (OdeMethod method : {OdeMethod::Adams, OdeMethod::Bdf, OdeMethod::Dop853}) {
    Tuned sys;
    OdeOptions o = tight(method, true);
    o.parameter_columns = 1;
    OdeIntegrator integ(sys, 2, o);
    const std::vector<double> y0{1.0, 0.0};
    const std::vector<double> S0{1.0, 0.0, 0.0, 1.0, 0.0, 0.0};  // [I | 0], column-major
    integ.restart(0.0, y0, std::vector<int>{}, S0);
    const double T = 2.0;
    while (integ.step(T) != StepStatus::StopTime) {
    }
    std::vector<double> S(6);
    integ.sensitivities(S);
    const double c = std::cos(sys.omega * T), s = std::sin(sys.omega * T);
    // rtol 1e-12 over under half a period: 1e-9 (BDF, of lower order, to 1e-7).
    const double tol = method == OdeMethod::Bdf ? 1e-7 : 1e-9;
    EXPECT_NEAR(S[0], c, tol) << name_of(method);
    EXPECT_NEAR(S[3], c, tol) << name_of(method);
    EXPECT_NEAR(S[4], -T * s, tol) << name_of(method);
    EXPECT_NEAR(S[5], -T * c, tol) << name_of(method);
  }
}

}  // namespace
}  // namespace flexgait::numerics
