// The flexible wheel's invariants (spec rimless.md, "Checks that hold for any correct
// implementation"): energy balance, the friction cone, sticking feet that do not drift,
// no event re-fired at its restart point, determinism, and the I -> 0 limit.
#include "flexgait/rimless/flexible_wheel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include "flexgait/rimless/output.hpp"
#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

using testing::measured_wheel;
using testing::run_options;

struct Case {
  double mu;
  double I;
  bool walks = true;  ///< completes 20 steps (else it slides away or stalls; the invariants still hold)
};

// Each case with each integrator: CVODE's Adams (the default) and DOP853.
class FlexibleWheelInvariants : public ::testing::TestWithParam<std::tuple<Case, numerics::OdeMethod>> {};

// Energy: E(t) + W_damp(t) + W_fric(t) = E(0). At rtol 1e-10 the ledger closes to ~1e-9 of the
// energy that flowed; the spec's bound is 1e-8 over 20 steps.
TEST_P(FlexibleWheelInvariants, EnergyBalanceFrictionConeAndNoDrift) {
  const auto [mu, I, walks] = std::get<0>(GetParam());
  WheelParams w = measured_wheel(mu);
  w.I = I;
  SimulationOptions o = run_options(20);
  o.method = std::get<1>(GetParam());
  const SimulationResult r = simulate_flexible(w, InitialState{}, o);
  if (walks) {
    EXPECT_FALSE(r.failure.has_value()) << *r.failure;
    EXPECT_EQ(r.steps_completed, 20);
  } else {
    // μ < tan φ: the wheel slides away ever faster (spec rimless.md); with little inertia and
    // μ just above tan φ it slides on two feet without turning and stalls.
    ASSERT_TRUE(r.failure.has_value());
    const FailureReason why = r.failure->reason;
    const bool named = why == FailureReason::AtRest || why == FailureReason::NoLanding ||
                       why == FailureReason::SlidAway || why == FailureReason::BalancedAtVertical;
    EXPECT_TRUE(named) << *r.failure;
  }
  EXPECT_LE(r.energy_balance_error, 1e-8);
  const double scale = r.energy_initial + r.work_damping + r.work_friction;  // >= m g L0 here
  const double force_tol = 1e-9 * w.m * w.g;                                 // solver round-off on forces [N]
  const double power_tol = 1e-10 * w.m * w.g * std::sqrt(w.g * w.L0);        // [W]
  std::map<int, double> stick_anchor;  // leg -> c at the start of its stick interval
  for (const LogSample& s : r.samples) {
    EXPECT_LE(std::abs(s.energy.total() + s.w_damp + s.w_fric - r.energy_initial), 1e-8 * scale) << "t = " << s.t;
    std::map<int, double> still;
    for (const ContactSample& c : s.contact) {
      if (c.leg < 0) continue;
      EXPECT_GE(c.N, -force_tol) << "t = " << s.t;
      if (c.mode == FootMode::Stick) {
        EXPECT_LE(std::abs(c.T), w.mu_s * c.N + force_tol) << "stick outside the cone at t = " << s.t;
        // ċ = 0 holds to the velocity tolerance the mode selection itself uses (1e-8 sqrt(g L0)):
        // the stick constraint is imposed on accelerations, so ċ carries the integration error.
        EXPECT_LE(std::abs(c.cdot), 1e-8 * std::sqrt(w.g * w.L0)) << "sticking foot moves at t = " << s.t;
        const auto it = stick_anchor.find(c.leg);
        const double anchor = it == stick_anchor.end() ? c.c : it->second;
        EXPECT_LE(std::abs(c.c - anchor), 1e-9 * w.L0) << "sticking foot drifts at t = " << s.t;
        still[c.leg] = anchor;
      } else {
        // Friction power T ċ <= 0. On the samples taken at an event CVODE returns the state just past
        // the crossing, so ċ (slip->stick) or T (lift-off) may sit past 0 by round-off: up to 1e-10 m/s
        // in ċ and 1e-10 of the power scale m g sqrt(g L0).
        EXPECT_LE(c.T * c.cdot, 1e-10 * std::abs(c.T) + power_tol)
            << "friction does not oppose the slip at t = " << s.t;
      }
    }
    stick_anchor = still;
  }
}

INSTANTIATE_TEST_SUITE_P(MuAndInertia, FlexibleWheelInvariants,
                         ::testing::Combine(::testing::Values(Case{0.05, 0.3, false}, Case{0.105, 0.3}, Case{0.13, 0.3},
                                                              Case{0.2, 0.3}, Case{0.6, 0.3}, Case{1.5, 0.3},
                                                              Case{5.0, 0.3}, Case{100.0, 0.3}, Case{0.13, 0.05, false},
                                                              Case{0.6, 0.05}, Case{5.0, 0.05}, Case{0.13, 1.0},
                                                              Case{0.6, 1.0}, Case{100.0, 1.0}),
                                            ::testing::Values(numerics::OdeMethod::Adams, numerics::OdeMethod::Dop853)),
                         [](const auto& info) {
                           const Case& c = std::get<0>(info.param);
                           return "mu" + std::to_string(static_cast<int>(c.mu * 1000)) + "_I" +
                                  std::to_string(static_cast<int>(c.I * 100)) + "_" +
                                  std::string(name_of(std::get<1>(info.param)));
                         });

// Two independent integrators on the same model: CVODE Adams and DOP853 give the same events in
// the same order, at times that agree to 1e-8 s (each integrator's global error at rtol 1e-10 over
// ~8 s of walking, amplified by the stiff legs: measured ≤ 2e-9 s), the same energies to 1e-8 of
// the energy that flowed, and DOP853's run is as deterministic as CVODE's (same bytes twice).
TEST(FlexibleWheel, Dop853AgreesWithAdams) {
  for (double mu : {0.105, 0.13, 0.2, 0.6, 5.0}) {
    const WheelParams w = measured_wheel(mu);
    SimulationOptions o = run_options(20);
    const SimulationResult adams = simulate_flexible(w, InitialState{}, o);
    o.method = numerics::OdeMethod::Dop853;
    const SimulationResult dop = simulate_flexible(w, InitialState{}, o);
    ASSERT_FALSE(adams.failure.has_value()) << *adams.failure;
    ASSERT_FALSE(dop.failure.has_value()) << *dop.failure;
    ASSERT_EQ(adams.events.size(), dop.events.size()) << "mu = " << mu;
    double worst = 0.0;
    for (std::size_t k = 0; k < adams.events.size(); ++k) {
      EXPECT_EQ(adams.events[k].kind, dop.events[k].kind) << "mu = " << mu << ", event " << k;
      EXPECT_EQ(adams.events[k].leg, dop.events[k].leg) << "mu = " << mu << ", event " << k;
      worst = std::max(worst, std::abs(adams.events[k].t - dop.events[k].t));
    }
    EXPECT_LE(worst, 1e-8) << "mu = " << mu;
    const double scale = adams.energy_initial + adams.work_damping + adams.work_friction;
    EXPECT_NEAR(adams.energy_final, dop.energy_final, 1e-8 * scale) << "mu = " << mu;
    EXPECT_NEAR(adams.work_damping, dop.work_damping, 1e-8 * scale) << "mu = " << mu;
    EXPECT_NEAR(adams.work_friction, dop.work_friction, 1e-8 * scale) << "mu = " << mu;
    EXPECT_LE(dop.energy_balance_error, 1e-9) << "mu = " << mu;
    const SimulationResult again = simulate_flexible(w, InitialState{}, o);
    EXPECT_EQ(log_csv(dop), log_csv(again));
    EXPECT_EQ(events_csv(dop), events_csv(again));
  }
}

TEST(FlexibleWheel, NoEventFiresAgainAtItsRestartPoint) {
  for (double mu : {0.105, 0.13, 0.2, 0.6, 5.0}) {
    const SimulationResult r = simulate_flexible(measured_wheel(mu), InitialState{}, run_options(20));
    ASSERT_FALSE(r.failure.has_value()) << *r.failure;
    std::map<std::pair<int, RunEvent>, double> last;
    for (const EventRecord& e : r.events) {
      const auto key = std::make_pair(e.leg, e.kind);
      const auto it = last.find(key);
      if (it != last.end()) {
        EXPECT_GT(e.t - it->second, 1e-6) << run_event_name(e.kind) << " of leg " << e.leg << " at " << e.t;
      }
      last[key] = e.t;
    }
  }
}

TEST(FlexibleWheel, JamsAreResolvedByImpulsesAboveCotAlpha) {
  // μ >= cot|β| of the landing leg (≈ 3.08 for ten legs): every landing jams (spec rimless.md).
  const SimulationResult r = simulate_flexible(measured_wheel(5.0), InitialState{}, run_options(10));
  ASSERT_FALSE(r.failure.has_value()) << *r.failure;
  EXPECT_GE(r.jams, 10);
  EXPECT_GT(r.work_friction, 0.0);  // the impulses' energy is booked as friction work
  const SimulationResult below = simulate_flexible(measured_wheel(1.5), InitialState{}, run_options(10));
  EXPECT_EQ(below.jams, 0);
}

TEST(FlexibleWheel, IdenticalBytesOnRerun) {
  const SimulationResult a = simulate_flexible(measured_wheel(0.13), InitialState{}, run_options(8));
  const SimulationResult b = simulate_flexible(measured_wheel(0.13), InitialState{}, run_options(8));
  EXPECT_EQ(log_csv(a), log_csv(b));
  EXPECT_EQ(events_csv(a), events_csv(b));
  EXPECT_EQ(summary_json(a, "flexible"), summary_json(b, "flexible"));
}

TEST(FlexibleWheel, FourGaitBehavioursAppearAsMuVaries) {
  // The defaults are chosen so that the paper's four behaviours appear for μ in (0, 1.5).
  std::map<std::string, double> seen;
  for (double mu : {0.105, 0.11, 0.13, 0.2, 0.6}) {
    const SimulationResult r = simulate_flexible(measured_wheel(mu), InitialState{}, run_options(20));
    ASSERT_FALSE(r.failure.has_value()) << *r.failure;
    seen[gait_label(r.steps[18].single_support)] = mu;
  }
  EXPECT_TRUE(seen.count("stick")) << "no sticking gait";
  EXPECT_TRUE(seen.count("slip-stick")) << "no slip-stick gait";
  EXPECT_TRUE(seen.count("slip-stick-slip")) << "no slip-stick-slip gait";
  EXPECT_TRUE(seen.count("slip")) << "no sliding gait";
}

// Where every single-support phase sticks the point-mass wheel (I = 0) is well posed, and the
// wheel with inertia I approaches it as O(I).
TEST(FlexibleWheel, PointMassLimitConverges) {
  auto final_state = [](double I) {
    WheelParams w = measured_wheel(1.0);
    w.I = I;
    const SimulationResult r = simulate_flexible(w, InitialState{}, run_options(3));
    EXPECT_FALSE(r.failure.has_value()) << "I = " << I << ": " << *r.failure;
    return std::make_pair(r.t_final, r.final_state[StateIndex::xd]);
  };
  const auto p0 = final_state(0.0);
  double previous = INFINITY;
  for (double I : {1e-2, 1e-3, 1e-4}) {
    const auto p = final_state(I);
    const double err = std::abs(p.first - p0.first) + std::abs(p.second - p0.second);
    EXPECT_LT(err, 0.3 * previous) << "I = " << I;  // O(I): a tenfold smaller I, a much smaller gap
    previous = err;
  }
  EXPECT_LT(previous, 1e-3);
}

TEST(FlexibleWheel, PointMassSlipIsReportedAsIllPosed) {
  WheelParams w = measured_wheel(0.13);
  w.I = 0.0;
  const SimulationResult r = simulate_flexible(w, InitialState{}, run_options(5));
  ASSERT_TRUE(r.failure.has_value());
  EXPECT_TRUE(ill_posed_point_mass(r.failure->reason)) << *r.failure;
  EXPECT_LE(r.energy_balance_error, 1e-8);
}

}  // namespace
}  // namespace flexgait::rimless
