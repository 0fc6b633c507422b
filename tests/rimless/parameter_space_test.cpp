// The flexible wheel walks wherever the model walks: the reproducers of each
// class of premature stop, and a seeded random sample of the parameter space in which every run
// either completes its steps or ends for a named physical reason that the test checks is real.
// Every completed or stopped run closes its energy ledger to 1e-8 (spec rimless.md, checks).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "flexgait/rimless/analyses.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/wheel_setup.hpp"
#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

struct Wheel {
  double mu, I, C, K;
  int legs;
  double slope, omega0;
};

WheelParams params_of(const Wheel& s) {
  WheelParams w;
  w.mu_s = w.mu_k = s.mu;
  w.I = s.I;
  w.C = s.C;
  w.K = s.K;
  w.legs = s.legs;
  w.slope = s.slope;
  return w;
}

SimulationOptions events_only(int steps) {
  SimulationOptions o = testing::run_options(steps);
  o.log = false;
  o.sample_dt = 10.0;
  o.max_step_time = 60.0;  // a slide to rest on two feet can take tens of seconds
  return o;
}

// Each step's stance leg lies ahead of the previous one (k -> k-1, or further after a flight in
// which the wheel turned by more than a leg's spacing): a re-landing of the stance leg or of a
// leg behind it is not a step.
void expect_steps_advance(const SimulationResult& r, int legs) {
  for (std::size_t i = 1; i < r.steps.size(); ++i) {
    const int ahead = (r.steps[i - 1].stance_leg - r.steps[i].stance_leg + legs) % legs;
    EXPECT_GE(ahead, 1) << "step " << i + 1;
    EXPECT_LT(2 * ahead, legs) << "step " << i + 1;
  }
}

// A stop is acceptable only if it names a physical outcome and the state shows it:
//  - "slid away": translating without turning, which speeds up exactly when μ_k < tan φ
//    (on a rigid translation Σ N = m g cos φ and m ẍ = m g sin φ - μ_k Σ N);
//  - a slide to rest that outlasts sim.max_step_time: the same translation with μ_k > tan φ;
//  - "came to rest": the kinetic energy is gone;
//  - "rolled back": the wheel turns backwards.
void expect_physical_stop(const WheelParams& w, const SimulationResult& r) {
  ASSERT_TRUE(r.failure.has_value());
  const Failure& why = *r.failure;
  const double ke = 0.5 * w.m * (r.final_state[3] * r.final_state[3] + r.final_state[4] * r.final_state[4]) +
                    0.5 * w.I * r.final_state[5] * r.final_state[5];
  if (why.reason == FailureReason::SlidAway) {
    EXPECT_LT(w.mu_k, std::tan(w.slope)) << why;
  } else if (why.reason == FailureReason::NoLanding) {
    // Sliding without turning: neither turning nor rising, to the translation test's 1e-6 in
    // units of sqrt(g / L0) and sqrt(g L0) (flexible_wheel.cpp, is_translation).
    EXPECT_LT(std::abs(r.final_state[5]), 1e-6 * std::sqrt(w.g / w.L0)) << why;
    EXPECT_LT(std::abs(r.final_state[4]), 1e-6 * std::sqrt(w.g * w.L0)) << why;
    EXPECT_GT(w.mu_k, std::tan(w.slope)) << why;
  } else if (why.reason == FailureReason::BalancedAtVertical) {
    EXPECT_EQ(r.final_contacts.count, 1) << why;  // one foot down: the inverted pendulum's equilibrium
    EXPECT_LE(std::abs(r.final_state[5]), 1e-3 * std::sqrt(w.g / w.L0)) << why;
  } else if (why.reason == FailureReason::AtRest) {
    EXPECT_LT(ke, 1e-12 * w.m * w.g * w.L0) << why;
  } else if (why.reason == FailureReason::RolledBack) {
    EXPECT_LT(r.final_state[5], 0.0) << why;
  } else {
    ADD_FAILURE() << "not a physical stop: " << why;
  }
}

// The issue's reproducers, one per class. Each walks its steps now.
struct Reproducer {
  const char* name;
  Wheel wheel;
  int steps;
};
void PrintTo(const Reproducer& r, std::ostream* os) {
  *os << r.name;
}

class Reproducers : public ::testing::TestWithParam<Reproducer> {};

TEST_P(Reproducers, WalkAllStepsWithTheLedgerClosed) {
  const Reproducer& c = GetParam();
  const WheelParams w = params_of(c.wheel);
  const SimulationResult r = simulate_flexible(w, InitialState{c.wheel.omega0}, events_only(c.steps));
  EXPECT_FALSE(r.failure.has_value()) << *r.failure;
  EXPECT_EQ(r.steps_completed, c.steps);
  EXPECT_LE(r.energy_balance_error, 1e-8);
  expect_steps_advance(r, w.legs);
}

INSTANTIATE_TEST_SUITE_P(
    Issue21, Reproducers,
    ::testing::Values(
        // 1. A foot that lifted off while slipping "landed" again on round-off 4e-11 s later.
        Reproducer{"relanding_on_roundoff", {2.21014, 0.074, 17.732, 435.9, 8, 0.1358, 2.5405}, 20},
        // 2. After a jam impulse the landing leg pulls (f = -10.3 N): leaving was the only choice.
        Reproducer{"landing_foot_leaves", {2.98769, 0.1215, 45.702, 7921.9, 6, 0.1723, 2.1536}, 20},
        // 3. At stick->slip a noise-level incipient acceleration rejected the only valid mode.
        Reproducer{"incipient_slip_noise", {1.10047, 0.3597, 11.796, 3686.7, 11, 0.1632, 2.6464}, 20},
        // 4. With stiff slip, slip->stick sent the foot into reverse slip by a velocity tolerance.
        Reproducer{"stiff_slip_to_stick", {2.98, 0.3, 30, 1000, 10, 0.1, 1.5}, 60},
        Reproducer{"tiny_inertia", {2.0, 1e-4, 30, 1000, 10, 0.1, 1.4}, 12},
        // 8. The ledger reached 3.5e-8 of the initial energy at the default tolerance.
        Reproducer{"energy_ledger", {0.56925, 0.2637, 19.83, 8514.6, 6, 0.1268, 2.114}, 20}));

// μ in [2.96, 3.00] and I = 1e-4 with μ = 1 and 2 failed for most values.
TEST(ParameterSpace, HighFrictionBandAndTinyInertiaWalk) {
  for (int i = 0; i <= 8; ++i) {
    const double mu = 2.96 + 0.005 * i;
    const WheelParams w = testing::measured_wheel(mu);
    const SimulationResult r = simulate_flexible(w, InitialState{}, events_only(20));
    EXPECT_FALSE(r.failure.has_value()) << "mu = " << mu << ": " << *r.failure;
    EXPECT_LE(r.energy_balance_error, 1e-8) << "mu = " << mu;
  }
  for (double mu : {1.0, 2.0}) {
    WheelParams w = testing::measured_wheel(mu);
    w.I = 1e-4;
    const SimulationResult r = simulate_flexible(w, InitialState{}, events_only(20));
    EXPECT_FALSE(r.failure.has_value()) << "I = 1e-4, mu = " << mu << ": " << *r.failure;
    EXPECT_LE(r.energy_balance_error, 1e-8);
  }
}

// 5. μ = 0.093 < tan φ: the wheel rocks back onto leg 0 after leg 9 landed (stance legs were
// counted 0, 9, 0, 9, ...); now a re-landing is no step, and the run ends as the wheel slides
// away on two feet.
TEST(ParameterSpace, RelandingsAreNotStepsAndASlideAwayIsNamed) {
  const WheelParams w = testing::measured_wheel(0.093);
  const SimulationResult r = simulate_flexible(w, InitialState{1.5}, events_only(60));
  expect_physical_stop(w, r);
  EXPECT_EQ(r.failure->reason, FailureReason::SlidAway) << *r.failure;
  expect_steps_advance(r, w.legs);
  EXPECT_LE(r.energy_balance_error, 1e-8);
}

// 5. The fixed-point search took a bounce of the stance foot for the touchdown section and
// ended in "flight"; the stick orbit exists (θ̇ = 1.872458 rad/s at touchdown).
TEST(ParameterSpace, FixedPointSectionIsTheNextLegNotABounce) {
  WheelParams w = testing::measured_wheel(1.0);
  w.I = 0.1;
  w.K = 1e5;
  w.C = 632.4555;
  SimulationOptions sim;
  AnalysisOptions opt;
  const FixedPointReport rep = find_fixed_point(w, sim, opt, Model::Flexible, Section::Touchdown, InitialState{1.5395});
  ASSERT_TRUE(rep.converged) << rep.failure();
  EXPECT_FALSE(rep.point.flight);
  EXPECT_NEAR(rep.point.z(rep.point.z.size() - 1), 1.872458, 1e-6);  // θ̇, the last section coordinate
  EXPECT_TRUE(rep.stable);
}

// 7. gait-vs-friction: at μ = 0.1085 the 20-step transient from ω0 = 1.4 is still slip-stick and
// Newton, held to that mode, found nothing; at μ = 0.102 the start rocks back although a stable
// sliding orbit exists (largest multiplier 0.917). Both now have their fixed point: the first
// after a longer transient, the second continued from a neighbour's.
TEST(ParameterSpace, GaitAgainstFrictionFindsTheFixedPointThatExists) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {});
  const PaperAnalysisOptions o = paper_analysis_from_config(base);
  const FrictionGait transient = friction_gait(base, 0.1085, Section::Touchdown, o);
  EXPECT_TRUE(transient.converged) << transient.gait;
  EXPECT_EQ(transient.gait, "slip");
  EXPECT_TRUE(transient.source.starts_with("start, ")) << transient.source;  // a longer transient found it
  // analysis.friction.transient_factors = [1]: the configured transient alone, which does not reach it.
  PaperAnalysisOptions short_transient = o;
  short_transient.transient_factors = {1};
  EXPECT_FALSE(friction_gait(base, 0.1085, Section::Touchdown, short_transient).converged);
  const FrictionGait neighbour = friction_gait(base, 0.104, Section::Touchdown, o);
  ASSERT_TRUE(neighbour.converged) << neighbour.gait;
  const FrictionGait alone = friction_gait(base, 0.102, Section::Touchdown, o);
  EXPECT_FALSE(alone.converged) << "the start from omega0 = 1.4 reaches it now: " << alone.source;
  const FrictionGait continued = friction_gait(base, 0.102, Section::Touchdown, o, {&neighbour});
  ASSERT_TRUE(continued.converged) << continued.gait;
  EXPECT_TRUE(continued.stable);
  EXPECT_NEAR(continued.max_multiplier, 0.917, 5e-3);
  EXPECT_TRUE(continued.source.starts_with("continued")) << continued.source;
}

// A genuine Painlevé case is named as one: leg 11 lands moving on a wheel with μ_s = 4.4 while
// leg 12 sticks; no impulse inside the cone stops both, and every mode without one slips with
// D <= 0 or breaks a contact condition (Stribeck friction with a viscous rise, μ(v) > cot β).
TEST(ParameterSpace, APainleveParadoxIsNamed) {
  WheelParams w = params_of(
      {4.448006436149931, 0.4832002941178817, 33.35890942087118, 2643.943475057392, 14, 0.1104403197580766, 0});
  w.mu_k = 3.247251534215311;
  w.friction = Friction::Stribeck;
  w.stribeck_velocity = 1.1418969380024793;
  w.viscous = 0.6307593035212784;
  w.stribeck_exponent = 3;
  const SimulationResult r = simulate_flexible(w, InitialState{2.5427552639673783}, events_only(20));
  ASSERT_TRUE(r.failure.has_value());
  EXPECT_EQ(r.failure->reason, FailureReason::PainleveParadox) << *r.failure;
  EXPECT_LE(r.energy_balance_error, 1e-8);
}

// The seeded random sample of the issue: μ 0.05–5 (log-uniform), I 0.02–1, C 5–60, K 300–1e4
// (log-uniform), N 6–14, φ 0.03–0.2, ω0 1–3; m = L0 = 1; 20 steps each (test_support.hpp).
using testing::SplitMix64;

// With both integrators: DOP853's first step after a restart is long, and set 197 (a foot that
// starts to slip and reverses within that step) once ended as a "missed event" with it.
class RandomWheels : public ::testing::TestWithParam<numerics::OdeMethod> {};

TEST_P(RandomWheels, WalkOrStopForANamedPhysicalReason) {
  SplitMix64 rng{20261123};
  int walked = 0;
  for (int i = 0; i < 200; ++i) {
    const testing::RandomWheel s = testing::RandomWheel::draw(rng);
    const WheelParams w = s.params();
    SCOPED_TRACE(::testing::Message() << "set " << i << ": mu " << s.mu << " I " << s.I << " C " << s.C << " K " << s.K
                                      << " N " << s.legs << " slope " << s.slope << " omega0 " << s.omega0);
    SimulationOptions o = events_only(20);
    o.method = GetParam();
    const SimulationResult r = simulate_flexible(w, InitialState{s.omega0}, o);
    if (r.failure) {
      expect_physical_stop(w, r);
    } else {
      EXPECT_EQ(r.steps_completed, 20);
      ++walked;
    }
    EXPECT_LE(r.energy_balance_error, 1e-8);
    expect_steps_advance(r, w.legs);
  }
  RecordProperty("walked", walked);
  EXPECT_GT(walked, 120);  // about 80 % of the sample walks (157 of 200 with this seed when written)
}

INSTANTIATE_TEST_SUITE_P(Methods, RandomWheels,
                         ::testing::Values(numerics::OdeMethod::Adams, numerics::OdeMethod::Dop853),
                         [](const auto& info) { return std::string(name_of(info.param)); });

}  // namespace
}  // namespace flexgait::rimless
