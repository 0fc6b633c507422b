// Pseudo-arclength continuation on maps whose bifurcations are known in closed form: each special
// point located to <= 1e-8 in the parameter, every point on the branch a fixed point to the
// corrector's tolerance and equal to the closed-form branch.
#include "flexgait/numerics/continuation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

namespace flexgait::numerics {
namespace {

// The location tolerance the issue asks for. The test functions here are polynomials in (z, p),
// central differences of quadratic maps are exact to round-off and the Illinois iteration stops at
// 1e-10 in arclength (so in p), which leaves two orders of margin.
constexpr double kLocated = 1e-8;

// Every point solves (C1): ||P(z, p) - z||_inf <= tolerance, recomputed here from the map.
void expect_fixed_points(const MapFamily& f, const Branch& b, double tolerance) {
  for (const BranchPoint& pt : b.points) {
    Eigen::VectorXd out;
    ASSERT_FALSE(f.map(pt.z, pt.p, out));
    EXPECT_LE((out - pt.z).lpNorm<Eigen::Infinity>(), tolerance) << "p = " << pt.p;
  }
  for (const SpecialPoint& sp : b.special) {
    Eigen::VectorXd out;
    ASSERT_FALSE(f.map(sp.point.z, sp.point.p, out));
    EXPECT_LE((out - sp.point.z).lpNorm<Eigen::Infinity>(), tolerance) << to_string(sp.kind);
  }
}

std::vector<SpecialKind> kinds(const Branch& b) {
  std::vector<SpecialKind> k;
  for (const auto& sp : b.special) k.push_back(sp.kind);
  return k;
}

// x -> r x (1 - x): the fixed point x = 1 - 1/r has multiplier 2 - r, a period doubling at r = 3
// and no fold; the period-2 orbit x± = (r + 1 ± sqrt((r + 1)(r - 3)))/(2r) has multiplier
// r²(1 - 2x₊)(1 - 2x₋) = 4 + 2r - r², through -1 at r = 1 + sqrt 6.
MapFamily logistic(bool exact_jacobian) {
  MapFamily f;
  f.map = [](const Eigen::VectorXd& z, double r, Eigen::VectorXd& out) -> std::optional<std::string> {
    out = Eigen::VectorXd::Constant(1, r * z(0) * (1 - z(0)));
    return std::nullopt;
  };
  if (exact_jacobian)
    f.state_jacobian = [](const Eigen::VectorXd& z, double r, Eigen::MatrixXd& J) -> std::optional<std::string> {
      J = Eigen::MatrixXd::Constant(1, 1, r * (1 - 2 * z(0)));
      return std::nullopt;
    };
  return f;
}

TEST(Continuation, LogisticPeriodDoublingAtThreeAndItsPeriodTwoBranch) {
  for (bool exact : {false, true}) {
    SCOPED_TRACE(exact ? "exact dP/dz" : "central differences");
    const MapFamily f = logistic(exact);
    ContinuationOptions opt;
    const Branch b = continue_fixed_points(f, Eigen::VectorXd::Constant(1, 0.55), 2.5, 3.4, opt);
    ASSERT_FALSE(b.start_failure) << b.failure();
    EXPECT_TRUE(b.reached_end) << b.stop_reason;
    EXPECT_EQ(b.end, BranchEnd::ReachedEnd) << b.stop_reason;
    EXPECT_DOUBLE_EQ(b.points.back().p, 3.4);
    expect_fixed_points(f, b, opt.tolerance);
    for (const BranchPoint& pt : b.points) {
      EXPECT_NEAR(pt.z(0), 1 - 1 / pt.p, 1e-10);
      EXPECT_NEAR(pt.multipliers[0].real(), 2 - pt.p, 1e-8);  // central differences of a quadratic: round-off
      EXPECT_EQ(pt.stable, pt.p < 3);
    }
    ASSERT_EQ(kinds(b), std::vector<SpecialKind>{SpecialKind::PeriodDoubling}) << b.stop_reason;
    const SpecialPoint& pd = b.special[0];
    EXPECT_NEAR(pd.point.p, 3.0, kLocated);
    EXPECT_NEAR(pd.point.z(0), 2.0 / 3.0, kLocated);
    EXPECT_NEAR(std::abs(pd.eigenvector(0)), 1.0, 1e-12);

    const MapFamily f2 = iterate(f, 2);
    const Branch b2 = switch_at_period_doubling(f, pd, 3.5, opt);
    ASSERT_FALSE(b2.start_failure) << b2.failure();
    EXPECT_EQ(b2.period, 2);
    EXPECT_TRUE(b2.reached_end) << b2.stop_reason;
    expect_fixed_points(f2, b2, opt.tolerance);
    // The root is the period doubling on the period-1 branch (where x± has an infinite slope in r).
    EXPECT_NEAR(b2.points[0].z(0), 1 - 1 / b2.points[0].p, 1e-10);
    for (std::size_t i = 1; i < b2.points.size(); ++i) {
      const BranchPoint& pt = b2.points[i];
      const double r = pt.p, root = std::sqrt((r + 1) * std::max(0.0, r - 3));
      const double xp = (r + 1 + root) / (2 * r), xm = (r + 1 - root) / (2 * r);
      EXPECT_NEAR(std::min(std::abs(pt.z(0) - xp), std::abs(pt.z(0) - xm)), 0, 1e-9) << "r = " << r;
      EXPECT_NEAR(pt.multipliers[0].real(), 4 + 2 * r - r * r, 1e-7) << "r = " << r;  // differences of a quartic
    }
    // Off the period-1 branch beyond its root: a genuine period-2 orbit.
    Eigen::VectorXd once;
    ASSERT_FALSE(f.map(b2.points.back().z, b2.points.back().p, once));
    EXPECT_GT(std::abs(once(0) - b2.points.back().z(0)), 0.1);
    ASSERT_EQ(kinds(b2), std::vector<SpecialKind>{SpecialKind::PeriodDoubling}) << b2.stop_reason;
    EXPECT_NEAR(b2.special[0].point.p, 1 + std::sqrt(6.0), kLocated);
    EXPECT_FALSE(b2.points.back().stable);
    EXPECT_TRUE(b2.points[2].stable);
  }
}

TEST(Continuation, FoldOfTheNormalFormIsPassedAndLocated) {
  // x -> x + p - x²: fixed points x = ±sqrt(p), multiplier 1 - 2x, a fold at p = 0, x = 0. From
  // (0.5, 0.25) towards p = -0.25 the branch turns at the fold and leaves the interval at p = 0.25
  // on x = -0.5.
  MapFamily f;
  f.map = [](const Eigen::VectorXd& z, double p, Eigen::VectorXd& out) -> std::optional<std::string> {
    out = Eigen::VectorXd::Constant(1, z(0) + p - z(0) * z(0));
    return std::nullopt;
  };
  ContinuationOptions opt;
  const Branch b = continue_fixed_points(f, Eigen::VectorXd::Constant(1, 0.45), 0.25, -0.25, opt);
  ASSERT_FALSE(b.start_failure) << b.failure();
  EXPECT_FALSE(b.reached_end);
  EXPECT_EQ(b.end, BranchEnd::TurnedBack) << b.stop_reason;
  expect_fixed_points(f, b, opt.tolerance);
  for (const BranchPoint& pt : b.points) {
    EXPECT_NEAR(pt.p, pt.z(0) * pt.z(0), 1e-11);
    EXPECT_EQ(pt.stable, pt.z(0) > 0);
  }
  EXPECT_NEAR(b.points.back().z(0), -0.5, 1e-10);
  ASSERT_EQ(kinds(b), std::vector<SpecialKind>{SpecialKind::Fold}) << b.stop_reason;
  EXPECT_NEAR(b.special[0].point.p, 0, kLocated);
  EXPECT_NEAR(b.special[0].point.z(0), 0, 1e-6);  // z ~ sqrt(p) at a fold: the error in p, square-rooted
  EXPECT_NEAR(std::abs(b.special[0].point.multipliers[0]), 1, 1e-6);
}

TEST(Continuation, DelayedLogisticNeimarkSackerAtTwo) {
  // (x, y) -> (r x (1 - y), x): fixed point x = y = 1 - 1/r with Jacobian [[1, 1 - r], [1, 0]],
  // multipliers λ² - λ + (r - 1) = 0: a complex pair for r > 5/4 of modulus sqrt(r - 1), through
  // the unit circle at r = 2 with λ = exp(±iπ/3).
  for (bool exact : {false, true}) {
    SCOPED_TRACE(exact ? "exact dP/dz" : "central differences");
    MapFamily f;
    f.map = [](const Eigen::VectorXd& z, double r, Eigen::VectorXd& out) -> std::optional<std::string> {
      out = Eigen::Vector2d(r * z(0) * (1 - z(1)), z(0));
      return std::nullopt;
    };
    if (exact)
      f.state_jacobian = [](const Eigen::VectorXd& z, double r, Eigen::MatrixXd& J) -> std::optional<std::string> {
        J.resize(2, 2);
        J << r * (1 - z(1)), -r * z(0), 1, 0;
        return std::nullopt;
      };
    ContinuationOptions opt;
    const Branch b = continue_fixed_points(f, Eigen::Vector2d(0.3, 0.35), 1.5, 2.3, opt);
    ASSERT_FALSE(b.start_failure) << b.failure();
    EXPECT_TRUE(b.reached_end) << b.stop_reason;
    EXPECT_EQ(b.end, BranchEnd::ReachedEnd) << b.stop_reason;
    expect_fixed_points(f, b, opt.tolerance);
    for (const BranchPoint& pt : b.points) {
      EXPECT_NEAR(pt.z(0), 1 - 1 / pt.p, 1e-10);
      EXPECT_NEAR(std::abs(pt.multipliers[0]), std::sqrt(pt.p - 1), 1e-8);
      EXPECT_EQ(pt.stable, pt.p < 2);
    }
    ASSERT_EQ(kinds(b), std::vector<SpecialKind>{SpecialKind::NeimarkSacker}) << b.stop_reason;
    EXPECT_NEAR(b.special[0].point.p, 2.0, kLocated);
    EXPECT_NEAR(b.special[0].angle, std::numbers::pi / 3, 1e-8);
  }
}

TEST(Continuation, TranscriticalBranchPoint) {
  // x -> x + p x - x²: the branches x = 0 and x = p cross at p = 0, where the multiplier 1 + p of
  // x = 0 passes +1 without a fold (t_p stays 1).
  MapFamily f;
  f.map = [](const Eigen::VectorXd& z, double p, Eigen::VectorXd& out) -> std::optional<std::string> {
    out = Eigen::VectorXd::Constant(1, z(0) + p * z(0) - z(0) * z(0));
    return std::nullopt;
  };
  const Branch b = continue_fixed_points(f, Eigen::VectorXd::Zero(1), -0.47, 0.5, {});
  ASSERT_FALSE(b.start_failure) << b.failure();
  EXPECT_TRUE(b.reached_end) << b.stop_reason;
  ASSERT_EQ(kinds(b), std::vector<SpecialKind>{SpecialKind::BranchPoint}) << b.stop_reason;
  EXPECT_NEAR(b.special[0].point.p, 0, kLocated);
}

TEST(Continuation, LabelChangesAreLocatedByBisection) {
  // A label that flips where the logistic fixed point x = 1 - 1/r crosses 0.7, at r = 10/3 (as a
  // gait's contact sequence flips at a non-smooth boundary); bisection to label_tolerance = 1e-8 in
  // s, and |dp/ds| <= 1.
  MapFamily f = logistic(false);
  f.label = [](const Eigen::VectorXd& z, double) { return z(0) < 0.7 ? std::string("low") : std::string("high"); };
  const Branch b = continue_fixed_points(f, Eigen::VectorXd::Constant(1, 0.6), 2.5, 3.4, {});
  ASSERT_FALSE(b.start_failure) << b.failure();
  ASSERT_EQ(kinds(b), (std::vector<SpecialKind>{SpecialKind::PeriodDoubling, SpecialKind::LabelChange}));
  const SpecialPoint& change = b.special[1];
  EXPECT_EQ(change.label_before, "low");
  EXPECT_EQ(change.label_after, "high");
  EXPECT_NEAR(change.point.p, 10.0 / 3.0, 1e-8);
  EXPECT_EQ(b.points.front().label, "low");
  EXPECT_EQ(b.points.back().label, "high");
}

TEST(Continuation, PeriodKOrbitsByNewtonOnTheIterate) {
  // The period-2 orbit of the logistic map at r = 3.2 by Newton on P² (chain-rule Jacobian).
  const MapFamily f2 = iterate(logistic(true), 2);
  BranchPoint orbit;
  ASSERT_FALSE(fixed_point_at(f2, Eigen::VectorXd::Constant(1, 0.8), 3.2, {}, orbit));
  const double r = 3.2, xp = (r + 1 + std::sqrt((r + 1) * (r - 3))) / (2 * r);
  EXPECT_NEAR(orbit.z(0), xp, 1e-12);
  EXPECT_NEAR(orbit.multipliers[0].real(), 4 + 2 * r - r * r, 1e-12);  // chain rule: exact
}

TEST(Continuation, ReportsWhyItCannotStart) {
  const MapFamily f = logistic(false);
  const Branch empty = continue_fixed_points(f, Eigen::VectorXd::Constant(1, 0.5), 2.0, 2.0, {});
  EXPECT_EQ(empty.start_failure, StartFailure::EmptyInterval);
  EXPECT_EQ(empty.end, BranchEnd::NotStarted);
  EXPECT_EQ(empty.failure(), "the parameter interval is empty (from 2 to 2)");  // the words of before
  MapFamily shift;
  shift.map = [](const Eigen::VectorXd& z, double p, Eigen::VectorXd& out) -> std::optional<std::string> {
    out = z.array() + 1 + p * p;  // no fixed point anywhere
    return std::nullopt;
  };
  const Branch b = continue_fixed_points(shift, Eigen::VectorXd::Zero(1), 0, 1, {});
  EXPECT_EQ(b.start_failure, StartFailure::NoFixedPoint) << b.failure();
  EXPECT_TRUE(b.failure().starts_with("no fixed point at p = 0 from the initial guess: ")) << b.failure();
  EXPECT_TRUE(b.points.empty());
  EXPECT_EQ(b.end, BranchEnd::NotStarted);
  MapFamily failing;
  failing.map = [](const Eigen::VectorXd& z, double p, Eigen::VectorXd& out) -> std::optional<std::string> {
    if (p > 0.3) return std::string("fell over");
    out = 0.5 * z;
    return std::nullopt;
  };
  const Branch c = continue_fixed_points(failing, Eigen::VectorXd::Zero(1), 0, 1, {});
  ASSERT_FALSE(c.start_failure) << c.failure();
  EXPECT_FALSE(c.reached_end);
  EXPECT_EQ(c.end, BranchEnd::NoStep) << c.stop_reason;
  EXPECT_NE(c.stop_reason.find("fell over"), std::string::npos) << c.stop_reason;  // the map's own words, passed on
  // Steps halve down to min_step at the edge, short of it by the parameter's central-difference
  // step h_p = 1e-6 (which must stay inside).
  EXPECT_NEAR(c.points.back().p, 0.3, 1.1e-6);
  EXPECT_LE(c.points.back().p, 0.3 - 1e-6);
}

// z -> z/2 + p + p², defined only for p in [0, top] (as a configuration key is within its bounds):
// the fixed point z* = 2(p + p²), ∂P/∂p = 1 + 2p. The one-sided difference of second order is exact
// on a quadratic, so ∂P/∂p at the bound is 1 to round-off (|P| ~ 1 over h = 1e-6: ~1e-10; 1e-8
// allowed), where a first-order difference would be off by h = 1e-6: the test tells them apart.
MapFamily quadratic_on(double top) {
  MapFamily f;
  f.map = [top](const Eigen::VectorXd& z, double p, Eigen::VectorXd& out) -> std::optional<std::string> {
    if (p < 0 || p > top) return "p = " + std::to_string(p) + " is not valid";
    out = (0.5 * z.array() + p + p * p).matrix();
    return std::nullopt;
  };
  f.valid = [top](double p) { return p >= 0 && p <= top; };
  return f;
}

TEST(Continuation, ParameterDerivativeStaysInsideTheValidValues) {
  const Eigen::VectorXd z = Eigen::VectorXd::Constant(1, 0.3);
  Eigen::VectorXd Pp;
  for (const double p : {0.0, 1e-7, 0.5, 1.0}) {  // the lower bound, next to it, inside, the upper bound
    ASSERT_FALSE(parameter_derivative(quadratic_on(1.0), z, p, 1e-6, Pp)) << p;
    EXPECT_NEAR(Pp(0), 1 + 2 * p, 1e-8) << "p = " << p;
  }
  // A range narrower than the step: the step is halved until two of its points fit.
  ASSERT_FALSE(parameter_derivative(quadratic_on(1e-8), z, 0.0, 1e-6, Pp));
  EXPECT_NEAR(Pp(0), 1.0, 1e-6);  // round-off over h <= 5e-9: ~4e-8
  // Without MapFamily::valid the step crosses the bound and the map's failure is passed on.
  MapFamily unbounded = quadratic_on(1.0);
  unbounded.valid = nullptr;
  const auto e = parameter_derivative(unbounded, z, 0.0, 1e-6, Pp);
  ASSERT_TRUE(e);
  EXPECT_NE(e->find("is not valid"), std::string::npos) << *e;
  // No valid value next to p at all.
  MapFamily point = quadratic_on(1.0);
  point.valid = [](double p) { return p == 0; };
  EXPECT_TRUE(parameter_derivative(point, z, 0.0, 1e-6, Pp));
}

// The branch from a bound of the parameter and to it: both reach their end, the end on the bound
// exactly, every point on z* = 2(p + p²) to the corrector's tolerance (1e-11, amplified by
// 1/(1 - 1/2) = 2 in z).
TEST(Continuation, StartsAndEndsOnABoundOfTheParameter) {
  const MapFamily f = quadratic_on(1.0);
  for (const auto& [from, to] : {std::pair{0.0, 1.0}, std::pair{1.0, 0.0}}) {
    const Branch b = continue_fixed_points(f, Eigen::VectorXd::Constant(1, 2 * (from + from * from)), from, to, {});
    ASSERT_FALSE(b.start_failure) << b.failure();
    EXPECT_TRUE(b.reached_end) << b.stop_reason;
    EXPECT_EQ(b.points.back().p, to);
    for (const BranchPoint& pt : b.points) EXPECT_NEAR(pt.z(0), 2 * (pt.p + pt.p * pt.p), 3e-11) << pt.p;
  }
}

}  // namespace
}  // namespace flexgait::numerics
