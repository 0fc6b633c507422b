// The flexible wheel's gait continued in μ from 0.6 down: across every behaviour
// threshold that `analysis gait-vs-friction` bisects, including the changes of the touchdown
// section's foot mode (the branch goes on in the new mode), to where the branch truly ends.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <tuple>

#include "flexgait/rimless/analyses.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/gait_branch.hpp"
#include "flexgait/rimless/sweep.hpp"
#include "flexgait/rimless/wheel_setup.hpp"

namespace flexgait::rimless {
namespace {

/// The threshold column of gait-vs-friction's thresholds.csv, computed as the command does with its
/// analysis.friction.* keys (100 values of μ in [0.1, 1.5], bisection to 1e-8).
std::vector<double> friction_thresholds(const Config& base) {
  const PaperAnalysisOptions o = paper_analysis_from_config(base);
  const SweepSpec sweep{"rimless.mu", o.friction_mu_from, o.friction_mu_to, o.friction_count};
  std::vector<double> mus;
  for (int i = 0; i < sweep.count; ++i) mus.push_back(sweep.value(i));
  const std::vector<FrictionGait> gaits = friction_gaits(base, mus, Section::Touchdown, o);
  std::istringstream csv(friction_thresholds_csv(base, gaits, Section::Touchdown, o));
  std::string line;
  std::getline(csv, line);  // header
  std::vector<double> out;
  while (std::getline(csv, line)) out.push_back(std::stod(line.substr(line.rfind(',') + 1)));
  return out;
}

// Between μ ≈ 0.2805 and 0.3273 the measured wheel's steady gait is slip−, stick, slip+, stick, slip+
// over the stance foot's contact: it sticks in the double support after its landing, then slips
// again into single support (`touchdown-stick slip-stick`); below 0.2805 the landing slip runs
// straight into single support (`slip-stick`). gait-vs-friction's bisection (to 1e-8) finds the
// boundary where `simulate`'s contact_phases change, [0.28047539, 0.28047559], to 1e-6 (the
// bracket was measured on runs from the configured start, not on fixed points).
TEST(GaitBranchThresholds, TheTouchdownStickWindowStartsAtMu02805) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {});
  const PaperAnalysisOptions o = paper_analysis_from_config(base);
  const std::vector<FrictionGait> gaits = friction_gaits(base, {0.2800, 0.2810}, Section::Touchdown, o);
  ASSERT_EQ(gaits.size(), 2u);
  EXPECT_EQ(gaits[0].gait, "slip-stick");
  EXPECT_EQ(gaits[1].gait, "touchdown-stick slip-stick");
  std::istringstream csv(friction_thresholds_csv(base, gaits, Section::Touchdown, o));
  std::string line;
  std::getline(csv, line);  // header
  // Newton may fail within ~1e-8 of the non-smooth boundary (the stick phase in double support is
  // of zero length there): such a midpoint is a third "gait" that splits the bracket, so the
  // boundary may come as more than one row; every row lies at the boundary.
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    const double t = std::stod(line.substr(line.rfind(',') + 1));
    EXPECT_GE(t, 0.28047539 - 1e-6) << line;
    EXPECT_LE(t, 0.28047559 + 1e-6) << line;
  }
  EXPECT_GE(rows, 1);
}

// Every threshold has a special point of the branch (a gait change, a change of the section's
// mode, or the branch's end) within 1e-6 of it: the bisection brackets it to 1e-8; the
// continuation locates a gait change to 1e-7 of the interval (5.5e-8 in μ) and a change of the
// section's mode to its smallest step (1e-9: with ∂P/∂p by sensitivity no evaluation leaves the
// point, so the corrector follows the old mode's branch to the boundary); measured, the largest
// distance is 1.7e-8. The branch's fixed points are the ones Newton finds directly from the
// configured start at the same μ, to 1e-9 (both converged to ||P(z) - z|| <= 1e-10, multipliers
// below 0.93: |Δz| <~ 1e-9).
TEST(GaitBranchThresholds, MuContinuationPassesEveryFrictionThreshold) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {});
  const GaitContinuationSpec spec{.param = "rimless.mu", .from = 0.6, .to = 0.05};
  const GaitBranch b = continue_gait(base, spec);
  ASSERT_TRUE(b.failure.empty()) << b.failure;
  EXPECT_EQ(b.segments, 4) << b.stop_reason;
  // The branch ends where the sliding gait's friction balances gravity along the slope.
  EXPECT_FALSE(b.branch.reached_end);
  EXPECT_EQ(b.end, GaitBranchEnd::SlideBalance) << b.stop_reason;  // mu_k = tan(slope)
  EXPECT_EQ(b.branch.end, numerics::BranchEnd::Vertical) << b.stop_reason;
  EXPECT_NEAR(b.rows.back().p, std::tan(0.1), 1e-9);

  std::vector<std::pair<double, std::string>> events;
  for (const auto& r : b.rows)
    if (!r.event.empty() && r.event != "start") events.emplace_back(r.p, r.event);
  const std::vector<double> thresholds = friction_thresholds(base);
  ASSERT_GE(thresholds.size(), 5u);
  for (double t : thresholds) {
    if (t > spec.from) continue;
    double best = INFINITY;
    std::string which;
    for (const auto& [p, ev] : events)
      if (std::abs(p - t) < best) {
        best = std::abs(p - t);
        which = ev;
      }
    EXPECT_LE(best, 1e-6) << "threshold " << t << ", nearest event " << which;
  }
  for (const char* boundary :
       {"section mode stick -> slip-", "section mode slip- -> stick", "section mode stick -> slip+"})
    EXPECT_TRUE(std::any_of(events.begin(), events.end(), [&](const auto& e) {
      return e.second.starts_with(boundary);
    })) << boundary;

  // Direct Newton at branch points away from the boundaries: at least one per section mode.
  std::map<std::string, int> compared;
  for (std::size_t i = 0; i < b.rows.size(); i += 3) {
    const GaitBranchRow& r = b.rows[i];
    if (!r.event.empty()) continue;
    const Config c = sweep_point_config(base, SweepSpec{spec.param, r.p, r.p, 1}, 0);
    const SimulationOptions sim = simulation_from_config(c);
    const FixedPointReport fp = find_fixed_point(wheel_from_config(c), sim, analysis_from_config(c), sim.model,
                                                 Section::Touchdown, initial_from_config(c));
    if (!fp.converged || fp.point.flight != r.section.flight || fp.point.mode != r.section.mode) continue;
    ASSERT_EQ(fp.point.z.size(), r.point.z.size());
    EXPECT_LE((fp.point.z - r.point.z).lpNorm<Eigen::Infinity>(), 1e-9) << "mu = " << r.p;
    EXPECT_EQ(fp.gait, r.gait) << "mu = " << r.p;
    ++compared[mode_text(r.section)];
  }
  for (const char* mode : {"stick", "slip-", "slip+"}) EXPECT_GE(compared[mode], 1) << mode;
}

// Over the slope the last stick phase before the landing vanishes at φ ≈ 0.2193 (the section's
// mode stick -> slip+): the branch from 0.2 up and the one from 0.222 down both cross it and place
// it within 1e-6 of each other (each segment runs to the boundary to within its smallest step,
// 1e-9 of the interval; measured, they agree to 7e-12); both reach their ends.
TEST(GaitBranchThresholds, SlopeBranchesCrossTheSectionModeChangeFromBothSides) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {});
  std::vector<double> at;
  for (const auto& [from, to, event] : {std::tuple{0.2, 0.2355, "section mode stick -> slip+"},
                                        std::tuple{0.222, 0.2, "section mode slip+ -> stick"}}) {
    const GaitBranch b = continue_gait(base, GaitContinuationSpec{.param = "rimless.slope", .from = from, .to = to});
    ASSERT_TRUE(b.failure.empty()) << b.failure;
    EXPECT_TRUE(b.branch.reached_end) << b.stop_reason;
    EXPECT_EQ(b.segments, 2);
    for (const auto& r : b.rows)
      if (r.event.starts_with(event)) at.push_back(r.p);
  }
  ASSERT_EQ(at.size(), 2u);
  EXPECT_NEAR(at[0], at[1], 1e-6);
  EXPECT_NEAR(at[0], 0.2193, 1e-4);
}

// analysis.continuation.join_tolerance: the two modes' ends at φ ≈ 0.2193 meet to the
// correctors' tolerance (||F|| <= 1e-10), not to 1e-13: held to that, the branch is not carried
// over and ends at the boundary, saying so.
TEST(GaitBranchThresholds, JoinToleranceDecidesTheCrossing) {
  const Config base = resolve_config(rimless_analysis_schema(), std::nullopt, {});
  GaitContinuationSpec spec{.param = "rimless.slope", .from = 0.2, .to = 0.2355};
  spec.tuning.join_tolerance = 1e-13;
  const GaitBranch b = continue_gait(base, spec);
  ASSERT_TRUE(b.failure.empty()) << b.failure;
  EXPECT_FALSE(b.branch.reached_end);
  EXPECT_EQ(b.segments, 1);
  EXPECT_EQ(b.end, GaitBranchEnd::ModeChangeNotContinued) << b.stop_reason;
  EXPECT_NEAR(b.rows.back().p, 0.2193, 1e-4);
}

}  // namespace
}  // namespace flexgait::rimless
