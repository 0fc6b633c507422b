// Basin of attraction: the rigid wheel's computed basin against its closed form, cell
// by cell away from a band around the boundary; the axis syntax and bad input.
#include "flexgait/rimless/basin.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "flexgait/core/text.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "flexgait/rimless/wheel_setup.hpp"

namespace flexgait::rimless {
namespace {

/// The rigid wheel's fate from (β0, ω0) in closed form (rigid_wheel.hpp; spec rimless.md): a
/// pendulum about the foot, J β̈ = m g L0 sin(β + φ), J = m L0² + I, with its top at β = -φ and
/// potential U(β) = m g L0 cos(β + φ). Stage 1 (to the first impact at β = α): moving backward
/// (ω0 < 0) it rolls back when it starts behind the top (β0 < -φ) or has the energy to pass it
/// backward (E = ½ J ω0² + U(β0) > m g L0); moving forward behind the top it needs E > m g L0.
/// Stage 2: after the impact, ω⁺ = r ω⁻ with ω⁻² = ω0² + 2 (U(β0) - U(α)) / J; the wheel passes
/// upright iff ½ J ω⁺² > m g L0 (1 - cos(α - φ)). Passing once, it converges: the step map is
/// increasing with one fixed point ω* above the threshold (ω* = 1.58 > 0.59 rad/s here), so the
/// sequence is monotone towards it and stays above the threshold.
/// `margin` is the smallest energy excess of the conditions that decide, over m g L0.
struct ClosedForm {
  bool converges = false;
  double margin = 0;
};

ClosedForm closed_form(const WheelParams& w, double omega0, double beta0) {
  const double J = w.m * w.L0 * w.L0 + w.I, mgl = w.m * w.g * w.L0, alpha = w.alpha(), phi = w.slope;
  const auto U = [&](double b) { return mgl * std::cos(b + phi); };
  const double E = 0.5 * J * omega0 * omega0 + U(beta0);
  ClosedForm out{true, INFINITY};
  if (omega0 < 0) {
    if (beta0 < -phi) return {false, (mgl - U(beta0) + 0.5 * J * omega0 * omega0) / mgl};
    out.margin = (mgl - E) / mgl;
    if (E > mgl) return {false, out.margin};
  } else if (beta0 < -phi) {
    out.margin = (E - mgl) / mgl;
    if (E < mgl) return {false, out.margin};
  }
  const double omega_minus = std::sqrt(omega0 * omega0 + 2 * (U(beta0) - U(alpha)) / J);
  const double omega_plus = rigid_step_map(w).r * omega_minus;
  const double m2 = (0.5 * J * omega_plus * omega_plus - mgl * (1 - std::cos(alpha - phi))) / mgl;
  return {m2 > 0, std::min(std::abs(out.margin), std::abs(m2))};
}

// 33 × 25 cells over ω0 ∈ [-1.6, 2.4] rad/s, β0 ∈ [-0.3, 0.3] rad (|β0| < α = 0.314), which hold
// all four stage-1 cases and both sides of the stage-2 threshold. Band: cells whose deciding
// energy excess is within 1e-3 m g L0 of zero, and cells starting within 0.02 rad and 0.1 rad/s
// of the pendulum's top (they linger there for seconds), are not compared; every other cell must
// be "converged" exactly where the closed form converges and "rolled_back" elsewhere.
TEST(Basin, RigidWheelEqualsTheClosedFormAwayFromTheBoundary) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid"});
  const WheelParams w = wheel_from_config(base);
  BasinSpec spec;
  spec.x = parse_basin_axis("--x-range", "initial.omega", "-1.6:2.4:33");
  spec.y = parse_basin_axis("--y-range", "initial.beta", "-0.3:0.3:25");
  spec.steps_limit = 200;
  spec.tolerance = 1e-6;
  check_basin(base, spec);
  const BasinReference ref = basin_reference(base, spec.section);
  ASSERT_TRUE(ref.found) << ref.failure;
  EXPECT_NEAR(ref.point.z(0), rigid_step_map(w).fixed_point(), 1e-9);
  int compared = 0, converged = 0, rolled_back = 0;
  for (int cell = 0; cell < static_cast<int>(spec.cells()); ++cell) {
    const double omega0 = spec.x.value(cell % spec.x.count), beta0 = spec.y.value(cell / spec.x.count);
    const ClosedForm expect = closed_form(w, omega0, beta0);
    if (std::abs(expect.margin) < 1e-3 || (std::abs(beta0 + w.slope) < 0.02 && std::abs(omega0) < 0.1)) continue;
    const std::string row = basin_row(base, spec, ref, cell);
    const std::string outcome = split_text(row, ',').at(2);
    EXPECT_EQ(outcome, expect.converges ? "converged" : "rolled_back")
        << "omega0 " << omega0 << " beta0 " << beta0 << " margin " << expect.margin << ": " << row;
    ++compared;
    (expect.converges ? converged : rolled_back) += 1;
  }
  EXPECT_GE(compared, spec.cells() * 9 / 10);  // the band is thin
  EXPECT_GE(converged, 100);
  EXPECT_GE(rolled_back, 100);
}

TEST(Basin, AxisSyntax) {
  const BasinAxis a = parse_basin_axis("--x-range", "initial.omega", "0.5:2.5:5");
  EXPECT_EQ(a.count, 5);
  EXPECT_DOUBLE_EQ(a.value(0), 0.5);
  EXPECT_DOUBLE_EQ(a.value(4), 2.5);
  EXPECT_DOUBLE_EQ(a.spacing(), 0.5);
  for (const char* bad : {"1:1:5", "0:1:1", "0:1", "0:1:2.5", "a:1:3", "0:nan:3", "0:1:3:4", ""})
    EXPECT_THROW(parse_basin_axis("--x-range", "initial.omega", bad), UsageError) << bad;
}

TEST(Basin, RefusesKeysOutsideTheInitialState) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid"});
  BasinSpec spec;
  spec.x = parse_basin_axis("--x-range", "rimless.slope", "0.05:0.1:3");
  spec.y = parse_basin_axis("--y-range", "initial.beta", "-0.1:0.1:3");
  EXPECT_THROW(check_basin(base, spec), ConfigError);
  spec.x.key = "initial.beta";
  EXPECT_THROW(check_basin(base, spec), ConfigError);  // the same key twice
  spec.x.key = "initial.omega";
  spec.y = parse_basin_axis("--y-range", "initial.beta", "-0.5:0.1:3");  // |beta| >= alpha = 0.314
  EXPECT_THROW(check_basin(base, spec), ConfigError);
}

// A wheel at rest exactly at the vertical (ω0 = 0, β0 = -φ = -0.1, the stance leg statically compressed) sits
// on the inverted pendulum's equilibrium; round-off tips it over only after ~14 s. The cell is
// named balanced_at_vertical whatever analysis.no_landing_limit is below that (1 s and 10 s here);
// the cell next to it (ω0 = 0.05 rad/s, 0.5 rad/s after 1 s) moves off the vertical: no such cell.
TEST(Basin, AWheelAtRestAtTheVerticalIsBalancedWhateverTheNoLandingLimit) {
  // Both models: β0 = -0.1 = -φ is the stance leg at the true vertical (the rigid wheel's exact
  // equilibrium, sin(β + φ) = 0); ω0 = 0.05 rad/s walks off it.
  for (const char* model : {"sim.model=flexible", "sim.model=rigid"}) {
    const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {model});
    BasinSpec spec;
    spec.x = parse_basin_axis("--x-range", "initial.omega", "0:0.05:2");
    spec.y = parse_basin_axis("--y-range", "initial.beta", "-0.1:-0.09:2");
    spec.steps_limit = 2;
    const BasinReference ref;  // not found: no cell converges, the outcome is the run's
    for (double limit : {1.0, 10.0}) {
      spec.no_landing_limit = limit;
      const std::vector<std::string> f = split_text(basin_row(base, spec, ref, 0), ',');
      ASSERT_GE(f.size(), 7u);
      EXPECT_EQ(f[2], "balanced_at_vertical") << model << ", limit " << limit << ": " << f[6];
      const std::vector<std::string> g = split_text(basin_row(base, spec, ref, 1), ',');
      EXPECT_NE(g[2], "balanced_at_vertical") << model << ": " << g[6];
    }
  }
}

TEST(Basin, CountsCellsIn64BitsAndRefusesAGridAboveTheCap) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid"});
  BasinSpec spec;
  // 100000 x 100000 = 1e10 cells: above 2^31 (an int would wrap), above the cap; refused at once.
  spec.x = parse_basin_axis("--x-range", "initial.omega", "0.5:2.5:100000");
  spec.y = parse_basin_axis("--y-range", "initial.beta", "-0.1:0.1:100000");
  EXPECT_EQ(spec.cells(), 10'000'000'000LL);
  try {
    check_basin(base, spec);
    ADD_FAILURE() << "a grid of 1e10 cells was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--x-range, --y-range: 100000 x 100000 = 10000000000 cells"),
              std::string::npos)
        << e.what();
  }
  // 10000 x 10000 = 1e8 cells, the cap itself: accepted (the check looks at the four corners only).
  spec.x.count = spec.y.count = 10000;
  EXPECT_NO_THROW(check_basin(base, spec));
  spec.y.count = 10001;
  EXPECT_THROW(check_basin(base, spec), ConfigError);
}

TEST(Basin, FailureOutcomes) {
  struct Case {
    FailureReason reason;
    BasinOutcome outcome;
  };
  for (const Case& c :
       {Case{FailureReason::FellBack, BasinOutcome::RolledBack},
        Case{FailureReason::RolledBack, BasinOutcome::RolledBack}, Case{FailureReason::AtRest, BasinOutcome::Stopped},
        Case{FailureReason::NoLanding, BasinOutcome::Stopped},
        Case{FailureReason::BalancedAtVertical, BasinOutcome::BalancedAtVertical},
        Case{FailureReason::SlidAway, BasinOutcome::SlidAway}, Case{FailureReason::TimeLimit, BasinOutcome::TimeLimit},
        Case{FailureReason::SolverFailure, BasinOutcome::Failed},
        Case{FailureReason::InitialFootBelowGround, BasinOutcome::Failed}}) {
    EXPECT_EQ(failure_outcome(Failure{c.reason, "x", {}}), c.outcome) << name_of(c.reason);
    EXPECT_EQ(failure_outcome(Failure{c.reason, {}, "transient"}), c.outcome) << name_of(c.reason);  // any stage
  }
  // basin.csv's outcome column: the table's names, in the header's order.
  EXPECT_EQ(basin_outcomes(),
            (std::vector<std::string>{"converged", "other_gait", "rolled_back", "stopped", "balanced_at_vertical",
                                      "slid_away", "time_limit", "failed", "step_limit", "infeasible"}));
}

}  // namespace
}  // namespace flexgait::rimless
