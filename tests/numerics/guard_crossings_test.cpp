// GuardCrossings (numerics/guard_crossings.hpp) on analytic guard functions g(t), standing in for an
// integrator's interpolant: CVODE's crossing rules, the root located to its tolerance, the
// first-step probe and the interior samples for a guard that crosses and returns within one step.
#include "flexgait/numerics/guard_crossings.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace flexgait::numerics {
namespace {

using Guard = std::function<double(double)>;

// Drives GuardCrossings over one step [t0, t1] of the guards gs (started at t0).
class Watch {
 public:
  explicit Watch(std::vector<Guard> guards) : gs(std::move(guards)) {}
  std::vector<Guard> gs;
  GuardCrossings crossings;

  std::vector<double> at(double t) const {
    std::vector<double> g;
    for (const auto& f : gs) g.push_back(f(t));
    return g;
  }
  void start(double t0, std::vector<int> directions) { crossings.start(t0, directions, at(t0)); }
  std::optional<double> check(double t1) {
    const auto g1 = at(t1);
    return crossings.check(
        t1, g1,
        [this](double t, std::span<double> g) {
          for (std::size_t i = 0; i < gs.size(); ++i) g[i] = gs[i](t);
        },
        [this](double t, int i) { return gs[static_cast<std::size_t>(i)](t); });
  }
};

// CVODE's root tolerance over the step [t0, t1] (guard_crossings.cpp): 100·u·(|t1| + |h|).
double root_tolerance(double t0, double t1) {
  return 100.0 * std::numeric_limits<double>::epsilon() * (std::abs(t1) + std::abs(t1 - t0));
}

TEST(GuardCrossings, LocatesTheRootToCvodesToleranceOnTheCrossedSide) {
  Watch w({[](double t) { return std::cos(t) - 0.5; }});
  w.start(0.0, {0});
  const auto root = w.check(2.0);
  ASSERT_TRUE(root.has_value());
  // TOMS 748 stops when its bracket is shorter than the tolerance and returns the bracket's end on
  // the side the guard has crossed to: within the tolerance of π/3, and g ≤ 0 there.
  EXPECT_NEAR(*root, std::numbers::pi / 3, root_tolerance(0.0, 2.0));
  EXPECT_LE(std::cos(*root) - 0.5, 0.0);
  EXPECT_EQ(w.crossings.fired()[0], -1);
}

TEST(GuardCrossings, DirectionLetsOnlyItsCrossingsThrough) {
  // g = t − 0.5 rises through 0 at 0.5: direction −1 ignores it, +1 and 0 report it upward.
  for (int direction : {-1, 0, +1}) {
    Watch w({[](double t) { return t - 0.5; }});
    w.start(0.0, {direction});
    const auto root = w.check(1.0);
    if (direction == -1) {
      EXPECT_FALSE(root.has_value());
    } else {
      ASSERT_TRUE(root.has_value()) << direction;
      EXPECT_NEAR(*root, 0.5, root_tolerance(0.0, 1.0));
      EXPECT_EQ(w.crossings.fired()[0], +1);
    }
  }
}

TEST(GuardCrossings, EarliestGuardFiresAloneAndTheLaterOneInTheNextCheck) {
  Watch w({[](double t) { return 0.7 - t; }, [](double t) { return t - 0.3; }});
  w.start(0.0, {0, 0});
  const auto first = w.check(1.0);
  ASSERT_TRUE(first.has_value());
  EXPECT_NEAR(*first, 0.3, root_tolerance(0.0, 1.0));
  EXPECT_EQ(w.crossings.fired()[0], 0);
  EXPECT_EQ(w.crossings.fired()[1], +1);
  // Watching restarted at the crossing: the same step's end now gives the later guard (downward).
  const auto second = w.check(1.0);
  ASSERT_TRUE(second.has_value());
  EXPECT_NEAR(*second, 0.7, root_tolerance(0.3, 1.0));
  EXPECT_EQ(w.crossings.fired()[0], -1);
  EXPECT_EQ(w.crossings.fired()[1], 0);
  EXPECT_FALSE(w.check(2.0).has_value());
}

TEST(GuardCrossings, ExactZeroAtTheStepsEndIsACrossingThere) {
  Watch w({[](double t) { return 1.0 - t; }});
  w.start(0.0, {0});
  const auto root = w.check(1.0);
  ASSERT_TRUE(root.has_value());
  EXPECT_EQ(*root, 1.0);
  EXPECT_EQ(w.crossings.fired()[0], -1);
}

TEST(GuardCrossings, GuardZeroAtTheStartIsInactiveUntilItMovesAway) {
  // g = t (t − 0.5): 0 at the start (no crossing there), negative, then up through 0 at 0.5.
  Watch w({[](double t) { return t * (t - 0.5); }});
  w.start(0.0, {0});
  const auto root = w.check(1.0);
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(*root, 0.5, root_tolerance(0.0, 1.0));
  EXPECT_EQ(w.crossings.fired()[0], +1);
  // g = t: 0 at the start and moving away: no crossing at all.
  Watch away({[](double t) { return t; }});
  away.start(0.0, {0});
  EXPECT_FALSE(away.check(1.0).has_value());
}

TEST(GuardCrossings, FirstStepProbeFindsAHumpThatLaterStepsDoNotSee) {
  // Direction −1, g = −(t − 0.2)(t − 0.3): below 0 at both ends of [0, 1], above 0 on (0.2, 0.3).
  // The first step after a start probes at 1/2, 1/4, …: 0.25 is above 0, so the downward
  // crossing at 0.3 is found.
  const Guard hump = [](double t) { return -(t - 0.2) * (t - 0.3); };
  Watch w({hump});
  w.start(0.0, {-1});
  const auto root = w.check(1.0);
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(*root, 0.3, root_tolerance(0.0, 1.0));
  EXPECT_EQ(w.crossings.fired()[0], -1);
  // The same hump shifted into a later step ([1, 2]) is CVODE's blind spot (both ends below 0);
  // the interior samples see it: 1.25 above 0 starts the bracket, 1.5 below ends it.
  Watch later({[&hump](double t) { return hump(t - 1.0); }});
  later.start(0.0, {-1});
  EXPECT_FALSE(later.check(1.0).has_value());
  const auto late = later.check(2.0);
  ASSERT_TRUE(late.has_value());
  EXPECT_NEAR(*late, 1.3, root_tolerance(1.0, 2.0));
  EXPECT_EQ(later.crossings.fired()[0], -1);
}

TEST(GuardCrossings, ADipBetweenTheSamplesOfALaterStepIsFound) {
  // Direction −1, g = (t − 0.52)(t − 0.58) over the step [0, 1] (not the first: the watch starts
  // at −1): above 0 at both ends and at the interior samples 0.25, 0.5, 0.75, below 0 on
  // (0.52, 0.58). The samples' second differences give g'' = 2 exactly (a parabola), and the
  // chord bound min(g(0.5), g(0.75)) − 2·2·0.25²/8 < 0 sends the bisection into (0.5, 0.75):
  // it finds g(0.5625) < 0 and the crossing at 0.52. (The two-step bound does not skip the
  // samples: g(-1) = 2.40, g(0) = 0.3016, g(1) = 0.2016 show g'' = 2 too, and 4·4·1²/8 = 2 > 0.2016.)
  Watch w({[](double t) { return (t - 0.52) * (t - 0.58); }});
  w.start(-1.0, {-1});
  EXPECT_FALSE(w.check(0.0).has_value());
  const auto root = w.check(1.0);
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(*root, 0.52, root_tolerance(0.0, 1.0));
  EXPECT_EQ(w.crossings.fired()[0], -1);
  // The same dip for direction +1 is no crossing until its rise at 0.58 (watching restarted at 0.52).
  Watch up({[](double t) { return (t - 0.52) * (t - 0.58); }});
  up.start(-1.0, {+1});
  EXPECT_FALSE(up.check(0.0).has_value());
  const auto rise = up.check(1.0);
  ASSERT_TRUE(rise.has_value());
  EXPECT_NEAR(*rise, 0.58, root_tolerance(0.0, 1.0));
  EXPECT_EQ(up.crossings.fired()[0], +1);
}

TEST(GuardCrossings, AGuardThatStaysAwayFromZeroCostsTheSamplesAlone) {
  // g = 2 + sin 3t over [0, 1]: g(0) = 2, g(0.5) = 2.997, g(1) = 2.141, one second difference
  // -3.71, M = 2·2·3.71 = 14.8; the coarse bound 4 M (1/2)²/8 = 1.85 < 2 = min |g|: the midpoint
  // alone.
  Watch w({[](double t) { return 2.0 + std::sin(3.0 * t); }});
  w.start(0.0, {-1});
  EXPECT_FALSE(w.check(1.0).has_value());
  EXPECT_EQ(w.crossings.interior_evaluations(), 1);
  // g = 1.5 + sin 3t: the same curvature, 1.85 > 1.5: the coarse bound does not exclude a root; the
  // four parts' bound, M (1/4)²/8 = 0.134 with their largest second difference, does (no bisection):
  // kSamples − 1 evaluations.
  Watch nearer({[](double t) { return 1.5 + std::sin(3.0 * t); }});
  nearer.start(0.0, {-1});
  EXPECT_FALSE(nearer.check(1.0).has_value());
  EXPECT_EQ(nearer.crossings.interior_evaluations(), GuardCrossings::kSamples - 1);
  // The next step [1, 2] of 2 + sin 3t has the previous step's start: g(0) = 2, g(1) = 2.141,
  // g(2) = 1.721, second divided difference -0.281, M = 4·0.281 = 1.12; the two-step bound
  // 4 M 1²/8 = 0.56 < 1.721 = min(g(1), g(2)): no evaluation at all.
  EXPECT_FALSE(w.check(2.0).has_value());
  EXPECT_EQ(w.crossings.interior_evaluations(), 1);
  // A step half as long as its predecessor (past kPreviousStepRatio) takes the samples again.
  EXPECT_FALSE(w.check(2.5).has_value());
  EXPECT_GE(w.crossings.interior_evaluations(), 2);
}

TEST(GuardCrossings, ASlotWithoutAGuardIsNotWatchedAndChangesNothingElse) {
  // Slot 1 of a mode that leaves it unused holds a constant; slot 2 (kNoGuard as well) crosses,
  // but is not looked at. The dip of slot 0 (ADipBetweenTheSamplesOfALaterStepIsFound) is found
  // at the same root with the same samples and bisections as when the constant slot is watched.
  const Guard dip = [](double t) { return (t - 0.52) * (t - 0.58); };
  const Guard unused = [](double) { return 1.0; };
  const Guard crossing = [](double t) { return 0.3 - t; };
  Watch watched({dip, unused});
  watched.start(-1.0, {-1, -1});
  Watch skipped({dip, unused, crossing});
  skipped.start(-1.0, {-1, kNoGuard, kNoGuard});
  for (Watch* w : {&watched, &skipped}) EXPECT_FALSE(w->check(0.0).has_value());
  const auto expected = watched.check(1.0);
  const auto root = skipped.check(1.0);
  ASSERT_TRUE(expected.has_value() && root.has_value());
  EXPECT_EQ(*root, *expected);
  EXPECT_EQ(skipped.crossings.interior_evaluations(), watched.crossings.interior_evaluations());
  EXPECT_EQ(skipped.crossings.fired()[0], -1);
  EXPECT_EQ(skipped.crossings.fired()[1], 0);
  EXPECT_EQ(skipped.crossings.fired()[2], 0);
}

TEST(GuardCrossings, StartRejectsMismatchedSizes) {
  GuardCrossings c;
  const std::vector<int> directions{0, 0};
  const std::vector<double> g{1.0};
  EXPECT_THROW(c.start(0.0, directions, g), std::invalid_argument);
}

}  // namespace
}  // namespace flexgait::numerics
