// DOP853 behind OdeIntegrator (numerics/dop853_backend.cpp): the same ODE as CVODE gives the same
// solution and the same guard crossing, its sensitivities equal finite differences of the flow,
// a restart without S carries S on, and max_step/max_steps act as on CVODE.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "flexgait/numerics/ode_integrator.hpp"

namespace flexgait::numerics {
namespace {

// Van der Pol, μ = 1: nonlinear, no closed form; the guard y0 = 0 (both directions).
class VanDerPol final : public OdeSystem {
 public:
  bool rhs(double, std::span<const double> y, std::span<double> yd) override {
    yd[0] = y[1];
    yd[1] = (1.0 - y[0] * y[0]) * y[1] - y[0];
    return true;
  }
  void guards(double, std::span<const double> y, std::span<double> g) override { g[0] = y[0]; }
};

OdeOptions options(OdeMethod method, bool sensitivities = false) {
  OdeOptions o;
  o.method = method;
  o.rtol = 1e-12;
  o.atol = 1e-14;
  o.sensitivities = sensitivities;
  return o;
}

struct Solution {
  std::vector<double> y;
  std::vector<double> crossings;
};

Solution run(OdeMethod method, const std::vector<double>& y0, double t_end) {
  VanDerPol vdp;
  OdeIntegrator integ(vdp, 2, options(method));
  integ.restart(0.0, y0, std::vector<int>{0});
  Solution r;
  for (StepStatus s; (s = integ.step(t_end)) != StepStatus::StopTime;) {
    if (s != StepStatus::Guard) continue;
    r.crossings.push_back(integ.time());
    integ.restart(integ.time(), std::vector<double>(integ.state().begin(), integ.state().end()), std::vector<int>{0});
  }
  r.y.assign(integ.state().begin(), integ.state().end());
  return r;
}

TEST(Dop853Backend, AgreesWithCvodeOnTheSameOdeAndCrossings) {
  const std::vector<double> y0{2.0, 0.0};
  const Solution dop = run(OdeMethod::Dop853, y0, 10.0);
  const Solution adams = run(OdeMethod::Adams, y0, 10.0);
  // Two methods at rtol 1e-12 over 10 s (about 1.5 periods of the limit cycle, where nearby
  // solutions neither grow nor shrink much): their global errors are ≲ 1e-9; bound 1e-8.
  ASSERT_EQ(dop.crossings.size(), adams.crossings.size());
  ASSERT_GE(dop.crossings.size(), 2u);
  for (std::size_t k = 0; k < dop.crossings.size(); ++k) EXPECT_NEAR(dop.crossings[k], adams.crossings[k], 1e-8) << k;
  EXPECT_NEAR(dop.y[0], adams.y[0], 1e-8);
  EXPECT_NEAR(dop.y[1], adams.y[1], 1e-8);
}

TEST(Dop853Backend, SensitivitiesEqualCentralDifferencesOfTheFlow) {
  const std::vector<double> y0{1.5, -0.5};
  const double T = 3.0;
  VanDerPol vdp;
  OdeIntegrator integ(vdp, 2, options(OdeMethod::Dop853, true));
  integ.restart(0.0, y0, std::vector<int>{}, std::vector<double>{1.0, 0.0, 0.0, 1.0});
  while (integ.step(T) != StepStatus::StopTime) {
  }
  std::vector<double> S(4);
  integ.sensitivities(S);
  // Central differences with h = 1e-5: truncation h²·|y'''| ≈ 1e-10, the integration error
  // (rtol 1e-12, its step sequence changing with y0) over 2h about 1e-7. Bound 1e-6.
  const double h = 1e-5;
  for (int j = 0; j < 2; ++j) {
    auto plus = y0, minus = y0;
    plus[static_cast<std::size_t>(j)] += h;
    minus[static_cast<std::size_t>(j)] -= h;
    const auto yp = run(OdeMethod::Dop853, plus, T).y;
    const auto ym = run(OdeMethod::Dop853, minus, T).y;
    for (int i = 0; i < 2; ++i) {
      const double fd = (yp[static_cast<std::size_t>(i)] - ym[static_cast<std::size_t>(i)]) / (2 * h);
      EXPECT_NEAR(S[static_cast<std::size_t>(2 * j + i)], fd, 1e-6) << i << ", " << j;
    }
  }
}

TEST(Dop853Backend, RestartWithoutSensitivitiesCarriesThemOn) {
  // Integrating to 1.5, restarting there without S, then to 3 gives the S of one run to 3.
  auto sensitivities = [](bool split) {
    VanDerPol vdp;
    OdeIntegrator integ(vdp, 2, options(OdeMethod::Dop853, true));
    integ.restart(0.0, std::vector<double>{1.5, -0.5}, std::vector<int>{}, std::vector<double>{1.0, 0.0, 0.0, 1.0});
    if (split) {
      while (integ.step(1.5) != StepStatus::StopTime) {
      }
      integ.restart(1.5, std::vector<double>(integ.state().begin(), integ.state().end()), std::vector<int>{});
    }
    while (integ.step(3.0) != StepStatus::StopTime) {
    }
    std::vector<double> S(4);
    integ.sensitivities(S);
    return S;
  };
  const auto whole = sensitivities(false);
  const auto split = sensitivities(true);
  // Different step sequences at rtol 1e-12 (the sensitivities ride on y's steps): 1e-8.
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(split[k], whole[k], 1e-8) << k;
}

TEST(Dop853Backend, MaxStepBoundsEveryStepAndMaxStepsStopsTheRun) {
  VanDerPol vdp;
  OdeOptions o = options(OdeMethod::Dop853);
  o.max_step = 0.02;
  OdeIntegrator integ(vdp, 2, o);
  integ.restart(0.0, std::vector<double>{2.0, 0.0}, std::vector<int>{});
  double t_prev = 0.0;
  while (integ.step(1.0) != StepStatus::StopTime) {
    EXPECT_LE(integ.time() - t_prev, 0.02 * (1 + 1e-12));
    t_prev = integ.time();
  }
  EXPECT_GE(integ.stats().steps, 50);
}

TEST(Dop853Backend, ARightHandSideThatKeepsFailingEndsInAnError) {
  // ẏ = 1 outside the model's domain beyond y = 0.5: every step across it is rejected and retried
  // smaller (max_steps is DOP853's allowance of rejected attempts per step) until the run throws.
  class Walled final : public OdeSystem {
   public:
    bool rhs(double, std::span<const double> y, std::span<double> yd) override {
      yd[0] = 1.0;
      return y[0] <= 0.5;
    }
    void guards(double, std::span<const double>, std::span<double>) override {}
  } walled;
  OdeOptions o = options(OdeMethod::Dop853);
  o.max_steps = 3;
  OdeIntegrator integ(walled, 1, o);
  integ.restart(0.0, std::vector<double>{0.0}, std::vector<int>{});
  EXPECT_THROW(
      {
        for (int k = 0; k < 1000; ++k) integ.step(1.0);
      },
      std::runtime_error);
}

// The harmonic oscillator x'' = −x from x = cos(−1): x = cos(t − 1), at most 1 at t = 1. The
// guard 1 − 1e-4 − x (direction −1) is below 0 only while |t − 1| < acos(1 − 1e-4) ≈ 0.01414 s,
// 2.8 % of a DOP853 step of this smooth flow at rtol 1e-10 (~1 s): a crossing and its return
// inside one step, both ends of which are above 0. The same for CVODE's Adams steps, which CVODE's
// own root finding (step ends only) does not see either.
class PeakedOscillator final : public OdeSystem {
 public:
  bool rhs(double, std::span<const double> y, std::span<double> yd) override {
    yd[0] = y[1];
    yd[1] = -y[0];
    return true;
  }
  void guards(double, std::span<const double> y, std::span<double> g) override { g[0] = 1.0 - 1e-4 - y[0]; }
};

class CrossAndReturn : public ::testing::TestWithParam<OdeMethod> {};

TEST_P(CrossAndReturn, IsFoundWithinOneStep) {
  PeakedOscillator f;
  OdeOptions o;
  o.method = GetParam();
  o.rtol = 1e-10;
  o.atol = 1e-12;
  OdeIntegrator integ(f, 2, o);
  integ.restart(0.0, std::vector<double>{std::cos(-1.0), std::sin(1.0)}, std::vector<int>{-1});
  StepStatus s = StepStatus::Step;
  double step_before = 0.0, t_before = 0.0;
  while ((s = integ.step(3.0)) == StepStatus::Step) {
    step_before = integ.time() - t_before;
    t_before = integ.time();
  }
  ASSERT_EQ(s, StepStatus::Guard);
  // The step that held the dip is longer than the dip (the point of the test): the steps before it
  // are (checked on the one just before).
  EXPECT_GT(step_before, 2 * std::acos(1.0 - 1e-4));
  // x = cos(t − 1) to the global error of rtol 1e-10 over ~1 s; at the root dx/dt = sin(0.01414)
  // ≈ 0.0141, so the time is within ~1e-10 / 0.0141 ≈ 7e-9 s; bound 1e-7.
  EXPECT_NEAR(integ.time(), 1.0 - std::acos(1.0 - 1e-4), 1e-7);
  EXPECT_EQ(integ.guards_fired()[0], -1);
}

INSTANTIATE_TEST_SUITE_P(Methods, CrossAndReturn, ::testing::Values(OdeMethod::Dop853, OdeMethod::Adams),
                         [](const auto& info) { return std::string(name_of(info.param)); });

}  // namespace
}  // namespace flexgait::numerics
