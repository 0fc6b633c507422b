// Event times of the flexible wheel against an independent location: each segment is integrated
// again with no guards given to the integrator; the guards are evaluated on a fine grid of each
// step's dense output and a sign change is bisected there. Run with both CVODE Adams and DOP853.
#include <gtest/gtest.h>

#include <cmath>

#include "flexgait/numerics/ode_integrator.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/flow.hpp"
#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

using testing::Segment;

constexpr int kSamplesPerStep = 64;  // grid of the dense output on which the guards are watched

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
  double t_prev = start.t;  // the last grid point
  double t0 = start.t;
  while (t0 < t_limit) {
    integ.step(t_limit);
    const double t1 = integ.time();
    // The guards on a grid of the dense output (a step may be long: a guard that starts at
    // round-off zero, the event just handled, can rise and fall again within one step).
    for (int sample = 1; sample <= kSamplesPerStep; ++sample) {
      const double ts = sample == kSamplesPerStep ? t1 : t0 + (t1 - t0) * sample / kSamplesPerStep;
      integ.interpolate(ts, y);
      guard_values(w, start.contacts, y, g1);
      for (std::size_t i = 0; i < n; ++i) {
        // A guard that starts at round-off zero counts once it moved away.
        if (!(g0[i] > 1e-12 && g1[i] <= 0)) continue;
        double lo = t_prev, hi = ts;
        for (int it = 0; it < 200 && hi - lo > 1e-14; ++it) {
          const double tm = 0.5 * (lo + hi);
          integ.interpolate(tm, y);
          guard_values(w, start.contacts, y, gm);
          (gm[i] > 0 ? lo : hi) = tm;
        }
        return hi;
      }
      g0 = g1;
      t_prev = ts;
    }
    t0 = t1;
  }
  return INFINITY;
}

// The start of every smooth segment of a run.
struct Restarts final : RunSink {
  void on_restart(double t, std::span<const double> state, const ContactSet& contacts) override {
    all.push_back({t, std::vector<double>(state.begin(), state.end()), contacts});
  }
  std::vector<Restart> all;
};

class EventLocation : public ::testing::TestWithParam<numerics::OdeMethod> {};

TEST_P(EventLocation, AgreesWithBisectionOnDenseOutput) {
  for (double mu : {0.105, 0.13, 0.2, 0.6}) {
    const WheelParams w = testing::measured_wheel(mu);
    SimulationOptions o = testing::run_options(4);
    o.method = GetParam();
    o.log = false;
    Restarts restarts;
    const SimulationResult r = simulate_flexible(w, InitialState{}, o, restarts);
    ASSERT_FALSE(r.failure.has_value()) << *r.failure;
    const std::vector<Restart>& starts = restarts.all;
    ASSERT_GE(starts.size(), 8u);
    for (std::size_t i = 0; i + 1 < starts.size(); ++i) {
      const double t_event = starts[i + 1].t;
      const double t_bisect = bisect_next_event(w, o, starts[i], t_event + 0.5);
      // The integrator's root and the bisection agree to 1e-9 s (the bound).
      EXPECT_NEAR(t_bisect, t_event, 1e-9) << "mu = " << mu << ", segment " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, EventLocation,
                         ::testing::Values(numerics::OdeMethod::Adams, numerics::OdeMethod::Dop853),
                         [](const auto& info) { return std::string(name_of(info.param)); });

}  // namespace
}  // namespace flexgait::rimless
