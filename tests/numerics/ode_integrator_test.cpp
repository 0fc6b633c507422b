// The event-locating integrator against analytic crossings.
#include "flexgait/numerics/ode_integrator.hpp"

#include <gtest/gtest.h>

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
  for (OdeMethod method : {OdeMethod::Adams, OdeMethod::Bdf}) {
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

TEST(OdeIntegrator, GuardAtZeroOnRestartDoesNotFireThere) {
  Oscillator osc;
  OdeIntegrator integ(osc, 2, tight());
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

TEST(OdeIntegrator, DenseOutputMatchesTheSolution) {
  Oscillator osc;
  OdeIntegrator integ(osc, 2, tight());
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

// Forward sensitivities of the oscillator: ∂y(t)/∂y(0) is the rotation by -t.
TEST(OdeIntegrator, SensitivitiesOfTheOscillatorAreARotation) {
  Oscillator osc;
  OdeIntegrator integ(osc, 2, tight(OdeMethod::Adams, true));
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

}  // namespace
}  // namespace flexgait::numerics
