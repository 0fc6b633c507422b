// The stagnation interval (paper Fig. 12): the stage, its end, the time near
// the true vertical, the critical omega0 and the log growth near it.
#include "flexgait/rimless/stagnation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

// The paper's phenomenon: the measured wheel with mu just above tan(phi), started at beta0 = -0.2.
WheelParams sliding_wheel() {
  return testing::measured_wheel(0.105);
}
InitialState start(double omega) {
  return InitialState{omega, -0.2};
}
SimulationOptions sim(double rtol = 1e-10) {
  SimulationOptions o;
  o.rtol = rtol;
  o.atol = 1e-12;
  return o;
}
// A scan without the grid's cost where the bracket is known: omega_c of this wheel is 0.5304.
StagnationOptions bracket(double lo, double hi) {
  StagnationOptions o;
  o.omega_from = lo;
  o.omega_to = hi;
  o.count = 2;
  return o;
}

// The Hermite measure against cases with known answers: a line crossing the window, a parabola
// dipping into it, and a cubic that never reaches it (to the last bits: bisection to 1e-16).
TEST(Stagnation, HermiteTimeWithinWindow) {
  // g = t − 0.5 on [0, 1] (ġ = 1): inside for |t − 0.5| < 0.1, 0.2 s.
  EXPECT_NEAR(hermite_time_within(0, -0.5, 1, 1, 0.5, 1, 0.1), 0.2, 1e-14);
  // g = (t − 1)² − 0.04 on [0, 2] (the Hermite cubic through its ends is the parabola):
  // |g| < 0.05 for 0 ≤ (t−1)² < 0.09, i.e. |t − 1| < 0.3: 0.6 s.
  EXPECT_NEAR(hermite_time_within(0, 0.96, -2, 2, 0.96, 2, 0.05), 0.6, 1e-14);
  EXPECT_EQ(hermite_time_within(0, 1, 0, 1, 2, 0, 0.5), 0.0);
  EXPECT_EQ(hermite_time_within(3, 0, 0, 3, 0, 0, 0.5), 0.0);  // zero-length interval (an event's two samples)
}

// A stage ends by the next leg landing (above omega_c) or by the leg behind landing (below), and the
// energy at the end is the start's minus what the friction and the dampers took: below omega_c the
// wheel loses more (it slides longer and gains no height back).
TEST(Stagnation, StageEndsAreClassified) {
  const StagnationOptions opt;
  const Stage pass = run_stage(sliding_wheel(), start(0.6), sim(), opt);
  const Stage back = run_stage(sliding_wheel(), start(0.45), sim(), opt);
  EXPECT_EQ(pass.end, StageEnd::NextLegLanded) << pass.failure;
  EXPECT_EQ(back.end, StageEnd::RolledBack) << back.failure;
  // The stance leg ends near +α when the leg ahead lands, near −α when the leg behind does (α = 0.314).
  EXPECT_GT(pass.beta_end, 0.2);
  EXPECT_LT(back.beta_end, -0.2);
  EXPECT_GT(pass.slide_total, 0.0);
  EXPECT_LE(pass.slide_near_vertical, pass.slide_total);
  EXPECT_LE(pass.slide_total, pass.duration);
}

// A stage still near the vertical at the time limit is a stagnation, not an error.
TEST(Stagnation, TimeLimitNearTheVerticalIsAStagnation) {
  StagnationOptions opt;
  opt.time_limit = 1.5;  // ω0 = 0.53039 stays near the vertical for ~2.5 s
  const Stage s = run_stage(sliding_wheel(), start(0.5303887), sim(), opt);
  EXPECT_EQ(s.end, StageEnd::Stagnated) << s.failure;
  EXPECT_NEAR(s.duration, 1.5, 1e-12);
}

// Exact to the event: the window crossings come from the Hermite interpolant, so the time near
// the vertical does not depend on the log's sampling: 1 ms against 0.25 ms within 1e-9 s (the
// interpolation error is O(h⁴) ≈ 1e-13 s; the integrator's dense output is not involved).
TEST(Stagnation, NearVerticalTimeIndependentOfSampling) {
  const StagnationOptions opt;
  SimulationOptions fine = sim();
  fine.sample_dt = 2.5e-4;
  for (double omega : {0.5303, 0.55}) {
    const Stage a = run_stage(sliding_wheel(), start(omega), sim(), opt);
    const Stage b = run_stage(sliding_wheel(), start(omega), fine, opt);
    EXPECT_NEAR(a.slide_near_vertical, b.slide_near_vertical, 1e-9) << omega;
    EXPECT_NEAR(a.slide_total, b.slide_total, 1e-12) << omega;  // event times only
    EXPECT_GT(a.slide_near_vertical, 0.1) << omega;
  }
}

// The paper's stagnation: omega_c = 0.53038867, the time sliding near the vertical
// grows like an inverted pendulum's approach time, ln(10) sqrt(I/(m g L)) = 0.40 s per decade of
// |omega0 − omega_c|, and at 1e-6 it is more than 10× its value at 1e-1.
// Tolerances: the growth within 5 % of the pendulum estimate (the leg is compressed by 1 % and the
// saddle lies at tan β = −μ, not exactly upright); omega_c to 1e-7 of the other implementation's
// 8 digits.
TEST(Stagnation, SlidingTimeGrowsLogarithmicallyTowardTheCriticalVelocity) {
  StagnationOptions opt = bracket(0.52, 0.54);
  opt.offset_max = 1e-1;
  opt.offset_min = 1e-6;
  opt.per_decade = 1;
  const StagnationScan scan = scan_stagnation(sliding_wheel(), start(0), sim(), opt);
  const StagnationSummary& r = scan.summary;
  ASSERT_TRUE(r.critical_found);
  EXPECT_TRUE(r.bisection_note.empty()) << r.bisection_note;
  EXPECT_NEAR(r.omega_c, 0.53038867, 1e-7);
  ASSERT_EQ(scan.offsets.size(), 6u);
  EXPECT_NEAR(scan.offsets.back(), 1e-6, 1e-18);
  for (std::size_t j = 0; j < scan.offsets.size(); ++j) {
    EXPECT_EQ(scan.above[j].end, StageEnd::NextLegLanded) << scan.offsets[j];
    EXPECT_EQ(scan.below[j].end, StageEnd::RolledBack) << scan.offsets[j];
  }
  EXPECT_GE(scan.above.back().slide_near_vertical, 10 * scan.above.front().slide_near_vertical);
  EXPECT_GE(scan.below.back().slide_near_vertical, 10 * scan.below.front().slide_near_vertical);
  EXPECT_EQ(r.kind, "sliding");
  // The growth is fitted over d ≤ 1e-3: 1e-3 … 1e-6, four points per side.
  EXPECT_NEAR(r.growth_above, r.estimate_sliding, 0.05 * r.estimate_sliding);
  EXPECT_NEAR(r.growth_below, r.estimate_sliding, 0.05 * r.estimate_sliding);
  EXPECT_NEAR(r.growth_stick, 0.0, 1e-12);
  // The interval holds omega_c and only the stages above the threshold.
  EXPECT_LT(r.interval_low, r.omega_c);
  EXPECT_GT(r.interval_high, r.omega_c);
  for (const auto* side : {&scan.above, &scan.below})
    for (const Stage& s : *side) {
      const bool inside = s.omega0 > r.interval_low && s.omega0 < r.interval_high;
      EXPECT_EQ(inside, s.near_vertical() > r.threshold) << s.omega0;
    }
  // The bounds are bisected as ω_c is (to bisection_tol = 1e-12 relative): a stage 1e-10 inside
  // each bound is above the threshold, one 1e-10 outside below it (1e-10 rad/s: 100 times the
  // bracket's width, far below the 2e-5 rad/s of the former interpolation in log d).
  for (const double edge : {r.interval_low, r.interval_high}) {
    const double in = edge < r.omega_c ? 1e-10 : -1e-10;
    EXPECT_GE(run_stage(sliding_wheel(), start(edge + in), sim(), opt).near_vertical(), r.threshold) << edge;
    EXPECT_LT(run_stage(sliding_wheel(), start(edge - in), sim(), opt).near_vertical(), r.threshold) << edge;
  }
}

// The fit's and the classification's keys: the defaults are the former literals; a fit
// window below every scan offset fits nothing (growth 0, kind none); a kind fraction above the
// measured growth (~1x the estimate, previous test) names no kind while the growth stays.
TEST(Stagnation, FitWindowAndKindFractionAreKeys) {
  const StagnationOptions defaults;
  EXPECT_EQ(defaults.fit_offset, 1e-3);
  EXPECT_EQ(defaults.kind_fraction, 0.25);
  EXPECT_EQ(defaults.rest_energy, 1e-9);
  StagnationOptions opt = bracket(0.52, 0.54);
  opt.offset_max = 1e-1;
  opt.offset_min = 1e-4;
  opt.per_decade = 1;
  opt.fit_offset = 1e-5;
  const StagnationSummary none = scan_stagnation(sliding_wheel(), start(0), sim(), opt).summary;
  ASSERT_TRUE(none.critical_found);
  EXPECT_EQ(none.growth_above, 0.0);
  EXPECT_EQ(none.growth_below, 0.0);
  EXPECT_EQ(none.kind, "none");
  opt.fit_offset = defaults.fit_offset;
  opt.kind_fraction = 10;
  const StagnationSummary strict = scan_stagnation(sliding_wheel(), start(0), sim(), opt).summary;
  EXPECT_GT(strict.growth_above, 0.5 * strict.estimate_sliding);
  EXPECT_EQ(strict.kind, "none");
  opt.kind_fraction = defaults.kind_fraction;
  EXPECT_EQ(scan_stagnation(sliding_wheel(), start(0), sim(), opt).summary.kind, "sliding");
}

// omega_c is a property of the wheel, not of the integrator: rtol 1e-10 → 1e-12 moves it by less
// than 1e-8 (the check; a tolerance-driven timing error of the landing that decides the
// outcome scales with rtol, and the saddle's sensitivity amplifies nothing at the outcome's flip).
TEST(Stagnation, CriticalVelocityStableUnderTolerance) {
  StagnationOptions opt = bracket(0.52, 0.54);
  opt.offset_max = 1e-3;
  opt.offset_min = 1e-3;
  const StagnationScan a = scan_stagnation(sliding_wheel(), start(0), sim(1e-10), opt);
  const StagnationScan b = scan_stagnation(sliding_wheel(), start(0), sim(1e-12), opt);
  ASSERT_TRUE(a.summary.critical_found && b.summary.critical_found);
  EXPECT_NEAR(a.summary.omega_c, b.summary.omega_c, 1e-8);
}

// Small inertia with mu = 0.25: the foot sticks near the vertical and the wheel topples about the
// foot, ln(10) sqrt((I + m L²)/(m g L)) = 0.74 s per decade. 5 % as above.
TEST(Stagnation, SmallInertiaStallsSticking) {
  WheelParams w = testing::measured_wheel(0.25);
  w.I = 0.02;
  StagnationOptions opt;
  opt.offset_max = 1e-1;
  opt.offset_min = 1e-6;
  opt.per_decade = 1;
  opt.omega_from = 0.2;
  opt.omega_to = 0.4;
  opt.count = 5;
  const StagnationScan scan = scan_stagnation(w, start(0), sim(), opt);
  const StagnationSummary& r = scan.summary;
  ASSERT_TRUE(r.critical_found);
  EXPECT_EQ(r.kind, "sticking");
  EXPECT_NEAR(r.growth_stick, r.estimate_sticking, 0.05 * r.estimate_sticking);
  EXPECT_NEAR(r.growth_slide, 0.0, 1e-12);
}

// Same bytes twice, and no critical value where the outcome never flips.
TEST(Stagnation, DeterministicAndNoFlipReported) {
  StagnationOptions opt = bracket(0.52, 0.54);
  opt.offset_min = 1e-4;
  const std::string a = stagnation_csv(scan_stagnation(sliding_wheel(), start(0), sim(), opt));
  const std::string b = stagnation_csv(scan_stagnation(sliding_wheel(), start(0), sim(), opt));
  EXPECT_EQ(a, b);
  const StagnationScan none = scan_stagnation(sliding_wheel(), start(0), sim(), bracket(0.6, 0.8));
  EXPECT_FALSE(none.summary.critical_found);
  EXPECT_EQ(none.summary.kind, "none");
  EXPECT_TRUE(none.above.empty());
}

// A stage must start on or before the vertical (beta0 <= −phi): the key is named.
TEST(Stagnation, StartPastTheVerticalIsAConfigError) {
  try {
    run_stage(sliding_wheel(), InitialState{0.5, -0.05}, sim(), StagnationOptions{});
    FAIL() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "initial.beta");
  }
}

// A resumed stagnation-map row is kept only as its own variation's row: the header's cell count,
// the variation first, then four numbers.
TEST(Stagnation, AMapRowIsValidOnlyAsItsOwnVariationsRow) {
  const std::string header = stagnation_map_header();
  const auto columns = static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
  std::vector<std::string> row(columns, "");
  row[0] = "rimless.mu=0.5";
  row[1] = "0.1";
  row[2] = "0.01";
  row[3] = "0";
  row[4] = "10000";
  EXPECT_TRUE(stagnation_map_row_valid("rimless.mu=0.5", row));
  EXPECT_FALSE(stagnation_map_row_valid("rimless.mu=0.6", row));  // another variation's row
  auto base = row;
  base[0] = "base";
  EXPECT_TRUE(stagnation_map_row_valid("", base));
  for (std::size_t k = 1; k <= 4; ++k) {
    auto damaged = row;
    damaged[k] = "1e";
    EXPECT_FALSE(stagnation_map_row_valid("rimless.mu=0.5", damaged)) << k;
  }
  row.pop_back();
  EXPECT_FALSE(stagnation_map_row_valid("rimless.mu=0.5", row));
}

}  // namespace
}  // namespace flexgait::rimless
