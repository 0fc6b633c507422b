// Event times of the flexible wheel against an independent location: each segment is integrated
// again with no guards given to CVODE; the guards are evaluated after every step and a sign change
// is bisected on the dense output.
#include <gtest/gtest.h>

#include <cmath>

#include "flexgait/numerics/ode_integrator.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/flow.hpp"
#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

class Segment final : public numerics::OdeSystem {
 public:
  Segment(const WheelParams& w, const ContactSet& c) : w_(w), c_(c) {}
  bool rhs(double, std::span<const double> y, std::span<double> yd) override { return flow_derivative(w_, c_, y, yd); }
  void guards(double, std::span<const double>, std::span<double>) override {}

 private:
  const WheelParams& w_;
  ContactSet c_;
};

// First downward crossing of any guard after t0, by bisection on the dense output [s].
double bisect_next_event(const WheelParams& w, const SimulationOptions& options, const Restart& start, double t_limit) {
  Segment seg(w, start.contacts);
  // The same integrator settings as the run (its error weights included): only the location of
  // the root differs.
  numerics::OdeIntegrator integ(seg, state_size(w), integrator_options(w, options));
  integ.restart(start.t, start.state, std::vector<int>{});
  const std::size_t n = static_cast<std::size_t>(guard_count(w));
  std::vector<double> g0(n), g1(n), gm(n), y(start.state.size());
  guard_values(w, start.contacts, start.state, g0);
  double t0 = start.t;
  while (t0 < t_limit) {
    integ.step(t_limit);
    const double t1 = integ.time();
    guard_values(w, start.contacts, integ.state(), g1);
    for (std::size_t i = 0; i < n; ++i) {
      // A guard that starts at round-off zero (the event just handled) counts once it moved away.
      if (!(g0[i] > 1e-12 && g1[i] <= 0)) continue;
      double lo = t0, hi = t1;
      for (int it = 0; it < 200 && hi - lo > 1e-14; ++it) {
        const double tm = 0.5 * (lo + hi);
        integ.interpolate(tm, y);
        guard_values(w, start.contacts, y, gm);
        (gm[i] > 0 ? lo : hi) = tm;
      }
      return hi;
    }
    g0 = g1;
    t0 = t1;
  }
  return INFINITY;
}

TEST(EventLocation, AgreesWithBisectionOnDenseOutput) {
  for (double mu : {0.105, 0.13, 0.2, 0.6}) {
    const WheelParams w = testing::measured_wheel(mu);
    SimulationOptions o = testing::run_options(4);
    o.log = false;
    const SimulationResult r = simulate_flexible(w, InitialState{}, o);
    ASSERT_FALSE(r.failure.has_value()) << *r.failure;
    ASSERT_GE(r.restarts.size(), 8u);
    for (std::size_t i = 0; i + 1 < r.restarts.size(); ++i) {
      const double t_event = r.restarts[i + 1].t;
      const double t_bisect = bisect_next_event(w, o, r.restarts[i], t_event + 0.5);
      // CVODE's root and the bisection agree to 1e-9 s (the bound).
      EXPECT_NEAR(t_bisect, t_event, 1e-9) << "mu = " << mu << ", segment " << i;
    }
  }
}

}  // namespace
}  // namespace flexgait::rimless
