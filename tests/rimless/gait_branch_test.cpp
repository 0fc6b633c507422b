// Continuation of the wheel's gait: the rigid wheel's branch over the slope against its
// closed form, and bad input refused before anything runs.
#include "flexgait/rimless/gait_branch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "flexgait/core/text.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "flexgait/rimless/sweep.hpp"
#include "flexgait/rimless/wheel_setup.hpp"

namespace flexgait::rimless {
namespace {

// The rigid wheel's touchdown map ω⁺ ↦ r sqrt(ω⁺² + a) (rigid_wheel.hpp) has the fixed point
// ω* = r sqrt(a/(1 - r²)) and multiplier r² at every slope. Each map evaluation integrates the
// stance to rtol 1e-12 and the corrector stops at ||F|| <= 1e-10, so ω* (about 1 rad/s, with
// 1/(1 - r²) ~ 2 amplifying the residual) is within 1e-9; the Jacobian is analytic.
TEST(GaitBranch, RigidWheelOverTheSlopeIsTheClosedForm) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid", "rimless.I=0.01"});
  GaitContinuationSpec spec;
  spec.param = "rimless.slope";
  spec.from = 0.05;
  spec.to = 0.15;
  spec.step = 0.01;
  const GaitBranch b = continue_gait(base, spec);
  ASSERT_TRUE(b.failure.empty()) << b.failure;
  EXPECT_TRUE(b.branch.reached_end) << b.branch.stop_reason;
  EXPECT_TRUE(b.exact_jacobian);
  ASSERT_GE(b.rows.size(), 6u);
  EXPECT_DOUBLE_EQ(b.rows.front().p, 0.05);
  EXPECT_NEAR(b.rows.back().p, 0.15, 1e-12);
  for (const GaitBranchRow& r : b.rows) {
    const WheelParams w = wheel_from_config(sweep_point_config(base, SweepSpec{"rimless.slope", r.p, r.p, 1}, 0));
    const RigidStepMap exact = rigid_step_map(w);
    EXPECT_NEAR(r.point.z(0), exact.fixed_point(), 1e-9) << "slope " << r.p;
    ASSERT_EQ(r.point.multipliers.size(), 1u);
    EXPECT_NEAR(r.point.multipliers[0].real(), exact.r * exact.r, 1e-9) << "slope " << r.p;
    EXPECT_TRUE(r.point.stable);
    EXPECT_LE(r.point.residual, 1e-10);
  }
  EXPECT_TRUE(b.branch.special.empty());
  const std::string csv = gait_branch_csv(b);
  EXPECT_EQ(
      csv.substr(0, csv.find('\n')),
      "parameter,thetad,mode,period,speed,dissipated_per_step,gait,abs_lambda_1,arg_lambda_1,stable,residual,event,"
      "key,section,computed_at");
  // What the branch is of, on every row: the key, the section, the wheel without the key.
  EXPECT_EQ(b.section, Section::Touchdown);
  EXPECT_EQ(b.computed_at, branch_computed_at(base, "rimless.slope"));
  EXPECT_EQ(b.computed_at.find("rimless.slope="), std::string::npos) << b.computed_at;
  EXPECT_NE(b.computed_at.find("rimless.I=0.01;"), std::string::npos) << b.computed_at;
  EXPECT_NE(b.computed_at.find("sim.model=rigid"), std::string::npos) << b.computed_at;
  const std::string row = csv.substr(csv.find('\n') + 1, csv.find('\n', csv.find('\n') + 1) - csv.find('\n') - 1);
  EXPECT_TRUE(row.ends_with(",rimless.slope,touchdown," + b.computed_at)) << row;
}

// computed_at against a configuration: the same wheel has no difference whatever the continued
// key's value; each changed wheel key (or sim.model) is named with both values; a value spelled
// otherwise (1e0 for 1.0) is the same value; rimless.mu leaves out both of its keys; an entry
// that names no key of the wheel, or is no key=value, is a difference.
TEST(GaitBranch, ComputedAtNamesEveryDifferentWheelKey) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid"});
  const std::string at = branch_computed_at(base, "rimless.slope");
  EXPECT_TRUE(computed_at_differences(at, base, "rimless.slope").empty());
  const Config steeper =
      resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid", "rimless.slope=0.2"});
  EXPECT_TRUE(computed_at_differences(at, steeper, "rimless.slope").empty());
  const Config other = resolve_config(rimless_analysis_schema(), std::nullopt, {"rimless.K=2000", "rimless.legs=8"});
  EXPECT_EQ(computed_at_differences(at, other, "rimless.slope"),
            (std::vector<std::string>{"rimless.legs = 10 (here: 8)", "rimless.K = 1000.0 (here: 2000.0)",
                                      "sim.model = rigid (here: flexible)"}));
  EXPECT_TRUE(computed_at_differences("rimless.m=1e0;rimless.g=9.81", base, "rimless.slope").empty());
  const Config slippery =
      resolve_config(rimless_analysis_schema(), std::nullopt, {"rimless.mu_s=0.9", "rimless.mu_k=0.8"});
  EXPECT_EQ(branch_computed_at(base, "rimless.mu").find("rimless.mu_"), std::string::npos);
  EXPECT_TRUE(computed_at_differences("rimless.mu_s=0.1;rimless.mu_k=0.1", slippery, "rimless.mu").empty());
  EXPECT_EQ(computed_at_differences("rimless.mu_s=0.1", slippery, "rimless.slope").size(), 1u);
  EXPECT_EQ(computed_at_differences("solver.rtol=1e-9;nonsense", base, "rimless.slope").size(), 2u);
}

// The flexible wheel from μ = 0.6 down to 0.2 (default step 0.01): the stance foot starts to slip
// at touchdown (μ ≈ 0.3273: it still sticks in the landing double support, then slips again), then
// the landing slip runs straight into single support (μ ≈ 0.2805); the continuation locates both
// changes (bisection to 1e-7 of the interval: 4e-8 in μ) even though a map evaluation can fail near
// a boundary. Newton's gait, found directly from the configured start at the located μ ∓ 2e-4, must
// be the label before and after: each location is within 2e-4 of where the direct gait changes.
TEST(GaitBranch, FlexibleWheelLocatesTheStickToSlipStickChange) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {});
  GaitContinuationSpec spec{.param = "rimless.mu", .from = 0.6, .to = 0.2};
  const GaitBranch b = continue_gait(base, spec);
  ASSERT_TRUE(b.failure.empty()) << b.failure;
  std::vector<const GaitBranchRow*> changes;
  for (const auto& r : b.rows)
    if (r.event.starts_with("gait ")) changes.push_back(&r);
  ASSERT_EQ(changes.size(), 2u) << b.stop_reason;
  EXPECT_EQ(changes[0]->event, "gait stick -> touchdown-stick slip-stick");
  EXPECT_EQ(changes[1]->event, "gait touchdown-stick slip-stick -> slip-stick");
  for (const auto& sp : b.branch.special) EXPECT_TRUE(sp.located) << b.stop_reason;
  const std::vector<std::tuple<const GaitBranchRow*, double, const char*>> sides{
      {changes[0], 2e-4, "stick"},
      {changes[0], -2e-4, "touchdown-stick slip-stick"},
      {changes[1], 2e-4, "touchdown-stick slip-stick"},
      {changes[1], -2e-4, "slip-stick"}};
  for (const auto& [change, dp, gait] : sides) {
    const Config c = config_at(base, "rimless.mu", format_number(change->p + dp), "test");
    const SimulationOptions sim = simulation_from_config(c);
    const FixedPointReport fp = find_fixed_point(wheel_from_config(c), sim, analysis_from_config(c), sim.model,
                                                 Section::Touchdown, initial_from_config(c));
    ASSERT_TRUE(fp.converged) << fp.failure();
    EXPECT_EQ(fp.gait, gait) << "mu = " << change->p + dp;
  }
}

// ∂P/∂p by sensitivity changes nothing but the Jacobian's source: from μ = 0.6 down to 0.35 (the
// stick gait) and over the slope from 0.2 up to 0.215 (stick-slip-flight-slip-stick) the branch
// with ∂P/∂p by sensitivity and the one with central differences of the map end on the same
// fixed point (each Newton-converged to ||F|| <= 1e-10 with multipliers <= 0.93, so each within
// 1e-10 / (1 - 0.93) = 1.4e-9 of the true one: 3e-9) with the same multipliers (exact ∂P/∂z
// integrated at rtol 1e-10, at points 3e-9 apart: 5e-9; measured 1.5e-9), and the tangents there
// (in q, normalised) agree to 1e-6 (central differences in p at rtol 1e-12 carry ~1e-7).
TEST(GaitBranch, ParameterSensitivityLeavesTheBranchUnchanged) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {});
  for (const auto& [param, from, to] : {std::tuple{"rimless.mu", 0.6, 0.35}, std::tuple{"rimless.slope", 0.2, 0.215}}) {
    std::vector<GaitBranch> b;
    for (bool sensitivity : {true, false}) {
      GaitContinuationSpec spec{.param = param, .from = from, .to = to};
      spec.parameter_sensitivity = sensitivity;
      b.push_back(continue_gait(base, spec));
      ASSERT_TRUE(b.back().failure.empty()) << b.back().failure;
      ASSERT_TRUE(b.back().branch.reached_end) << b.back().stop_reason;
    }
    const GaitBranchRow &end0 = b[0].rows.back(), &end1 = b[1].rows.back();
    EXPECT_EQ(end0.p, to);
    EXPECT_EQ(end1.p, to);
    EXPECT_LE((end0.point.z - end1.point.z).lpNorm<Eigen::Infinity>(), 3e-9) << param;
    ASSERT_EQ(end0.point.multipliers.size(), end1.point.multipliers.size());
    for (std::size_t k = 0; k < end0.point.multipliers.size(); ++k)
      EXPECT_LE(std::abs(end0.point.multipliers[k] - end1.point.multipliers[k]), 5e-9) << param;
    EXPECT_LE((end0.point.tangent - end1.point.tangent).lpNorm<Eigen::Infinity>(), 1e-6) << param;
  }
}

// Period 2 (--period 2) on a period-1 gait: the fixed points of P² there are P's own, so the branch
// is the period-1 branch (Newton on P from each point moves it by <= 1e-8: both held to
// ||F|| <= 1e-10, 1/(1 - 0.75) amplifying) and its multipliers are P's squared (to 1e-5: P²'s
// Jacobian by central differences of the integrated map). No period doubling: nothing switched.
TEST(GaitBranch, PeriodTwoOfAPeriodOneGaitIsItsBranchWithSquaredMultipliers) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {});
  GaitContinuationSpec spec{.param = "rimless.slope", .from = 0.1, .to = 0.12, .step = 0.002};
  spec.period = 2;
  spec.switch_at_period_doubling = true;
  const GaitBranch b = continue_gait(base, spec);
  ASSERT_TRUE(b.failure.empty()) << b.failure;
  EXPECT_TRUE(b.branch.reached_end) << b.stop_reason;
  EXPECT_EQ(b.period, 2);
  EXPECT_FALSE(b.exact_jacobian);
  EXPECT_TRUE(b.switched.empty());
  ASSERT_GE(b.rows.size(), 5u);
  for (const GaitBranchRow& r : b.rows) {
    const Config c = sweep_point_config(base, SweepSpec{spec.param, r.p, r.p, 1}, 0);
    const SimulationOptions sim = simulation_from_config(c);
    const FixedPointReport fp = find_fixed_point_from(wheel_from_config(c), sim, analysis_from_config(c), r.section);
    ASSERT_TRUE(fp.converged) << fp.failure();
    EXPECT_LE((fp.point.z - r.point.z).lpNorm<Eigen::Infinity>(), 1e-8) << "slope " << r.p;
    ASSERT_EQ(fp.multipliers.size(), r.point.multipliers.size());
    for (std::size_t k = 0; k < fp.multipliers.size(); ++k)
      EXPECT_NEAR(std::abs(r.point.multipliers[k]), std::norm(fp.multipliers[k]), 1e-5) << "slope " << r.p;
    EXPECT_EQ(r.gait, "stick / stick");
  }
}

// The continuation's tuning keys: the defaults are the former literals; a larger first
// step (no --step) takes fewer points to the same end, the same closed-form branch; min_step above
// the first step is refused naming its key.
TEST(GaitBranch, TuningKeysDefaultsAndFirstStep) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid", "rimless.I=0.01"});
  const GaitContinuationOptions t = gait_continuation_from_config(base);
  EXPECT_EQ(t.max_points, 2000);
  EXPECT_EQ(t.initial_step, 0.02);
  EXPECT_EQ(t.max_step_factor, 2.0);
  EXPECT_EQ(t.min_step, 1e-9);
  EXPECT_EQ(t.locate_tolerance, 1e-9);
  EXPECT_EQ(t.label_tolerance, 1e-7);
  EXPECT_EQ(t.parameter_step, 6e-6);
  EXPECT_EQ(t.mode_change_distance, 1e-3);
  EXPECT_EQ(t.mode_probes, (std::vector<double>{3e-4, 1e-3, 3e-3, 1e-2}));
  EXPECT_EQ(t.back_distance, 0.05);
  EXPECT_EQ(t.back_max_points, 200);
  EXPECT_EQ(t.join_tolerance, 1e-3);
  GaitContinuationSpec spec{.param = "rimless.slope", .from = 0.05, .to = 0.15};
  spec.tuning = t;
  const GaitBranch small = continue_gait(base, spec);
  spec.tuning = gait_continuation_from_config(
      resolve_config(rimless_analysis_schema(), std::nullopt,
                     {"sim.model=rigid", "rimless.I=0.01", "analysis.continuation.initial_step=0.1"}));
  EXPECT_EQ(spec.tuning.initial_step, 0.1);
  const GaitBranch large = continue_gait(base, spec);
  ASSERT_TRUE(small.branch.reached_end && large.branch.reached_end) << small.stop_reason << large.stop_reason;
  EXPECT_LT(large.branch.points.size(), small.branch.points.size());
  // Both on the closed-form branch at the end (the same check as the first test, 1e-9).
  EXPECT_NEAR(large.rows.back().state(large.rows.back().state.size() - 1),
              small.rows.back().state(small.rows.back().state.size() - 1), 1e-9);
  // max_points = 3: the branch stops after three points, short of the end, and says so.
  spec.tuning.max_points = 3;
  const GaitBranch few = continue_gait(base, spec);
  EXPECT_EQ(few.branch.points.size(), 3u);
  EXPECT_FALSE(few.branch.reached_end);
  EXPECT_EQ(few.branch.end, numerics::BranchEnd::MaxPoints) << few.stop_reason;
  try {
    gait_continuation_from_config(
        resolve_config(rimless_analysis_schema(), std::nullopt, {"analysis.continuation.min_step=0.5"}));
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "analysis.continuation.min_step");
  }
}

// A branch that starts or ends on a bound of its key (rimless.I >= 0, the point-mass wheel): the
// difference step in the key stays inside the allowed values (one-sided at the bound) and the end
// is reached on the bound itself; every point is the closed form, as in the first test (1e-9).
TEST(GaitBranch, RigidWheelFromAndToTheBoundOfItsKey) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid"});
  for (const auto& [from, to] : {std::pair{0.0, 0.02}, std::pair{0.02, 0.0}}) {
    const GaitContinuationSpec spec{.param = "rimless.I", .from = from, .to = to};
    const GaitBranch b = continue_gait(base, spec);
    ASSERT_TRUE(b.failure.empty()) << b.failure;
    EXPECT_TRUE(b.branch.reached_end) << b.stop_reason;
    EXPECT_EQ(b.rows.front().p, from);
    EXPECT_EQ(b.rows.back().p, to);
    for (const GaitBranchRow& r : b.rows) {
      const WheelParams w = wheel_from_config(sweep_point_config(base, SweepSpec{"rimless.I", r.p, r.p, 1}, 0));
      EXPECT_NEAR(r.point.z(0), rigid_step_map(w).fixed_point(), 1e-9) << "I " << r.p;
    }
  }
}

TEST(GaitBranch, RefusesBadInput) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid"});
  GaitContinuationSpec spec{.param = "rimless.nothing", .from = 0.05, .to = 0.1};
  EXPECT_THROW(continue_gait(base, spec), ConfigError);
  spec.param = "rimless.slope";
  spec.to = spec.from;
  EXPECT_THROW(continue_gait(base, spec), ConfigError);
  spec.to = 2.0;  // beyond the slope's bound π/4
  EXPECT_THROW(continue_gait(base, spec), ConfigError);
  spec.to = 0.1;
  spec.period = 0;
  EXPECT_THROW(continue_gait(base, spec), ConfigError);
}

}  // namespace
}  // namespace flexgait::rimless
