// Poincaré maps and fixed points of the rimless wheel.
#include "flexgait/rimless/poincare.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

AnalysisOptions analysis() {
  return AnalysisOptions{};
}  // rtol 1e-12, Newton tolerance 1e-10

// The rigid wheel's simulated map has McGeer's fixed point and multiplier cos²(2α), to 1e-9.
TEST(Poincare, RigidWheelFixedPointIsAnalytic) {
  for (int legs : {8, 10, 16}) {
    WheelParams w;
    w.I = 0.0;
    w.legs = legs;
    const RigidStepMap exact = rigid_step_map(w);
    const FixedPointReport r =
        find_fixed_point(w, testing::run_options(1), analysis(), Model::Rigid, Section::Touchdown, InitialState{});
    ASSERT_TRUE(r.converged) << r.failure();
    EXPECT_NEAR(r.point.z(0), exact.fixed_point(), 1e-9) << legs << " legs";
    ASSERT_EQ(r.multipliers.size(), 1u);
    EXPECT_NEAR(r.multipliers[0].real(), std::pow(std::cos(2 * w.alpha()), 2), 1e-9) << legs << " legs";
    if (legs == 8) {
      EXPECT_NEAR(r.multipliers[0].real(), 0.5, 1e-9);
    }
    EXPECT_TRUE(r.stable);
  }
}

struct Gait {
  double mu;
  const char* label;
};

class FlexibleFixedPoint : public ::testing::TestWithParam<Gait> {};

// A fixed point of the flexible wheel maps to itself within 1e-10, for each of the four behaviours.
TEST_P(FlexibleFixedPoint, MapsToItselfAndAttractsPerturbations) {
  const WheelParams w = testing::measured_wheel(GetParam().mu);
  const SimulationOptions sim = testing::run_options(1);
  const FixedPointReport r = find_fixed_point(w, sim, analysis(), Model::Flexible, Section::Touchdown, InitialState{});
  ASSERT_TRUE(r.converged) << r.failure();
  EXPECT_EQ(r.gait, GetParam().label);
  SimulationOptions map_opt = sim;  // exactly the map Newton solved on
  map_opt.rtol = analysis().rtol;
  map_opt.atol = analysis().atol;
  PoincareMap map(w, map_opt, Model::Flexible, Section::Touchdown);
  const MapStep once = map.apply(r.point);
  ASSERT_FALSE(once.failure.has_value()) << *once.failure;
  EXPECT_LE((once.next.z - r.point.z).lpNorm<Eigen::Infinity>(), 1e-10);
  ASSERT_TRUE(r.stable);
  // A perturbation of 1e-3 (relative to each component's scale) returns: after 60 steps the
  // distance has shrunk at least like |λ_max|^60 (λ_max <= 0.93 here), with margin.
  SectionState p = r.point;
  p.z += 1e-3 * p.scale(w).cwiseProduct(Eigen::VectorXd::Ones(p.z.size()));
  const double d0 = (p.z - r.point.z).lpNorm<Eigen::Infinity>();
  for (int k = 0; k < 60; ++k) {
    const MapStep s = map.apply(p);
    ASSERT_FALSE(s.failure.has_value()) << "step " << k << ": " << *s.failure;
    p = s.next;
  }
  const double lambda = std::abs(r.multipliers.front());
  EXPECT_LE((p.z - r.point.z).lpNorm<Eigen::Infinity>(), 10.0 * d0 * std::pow(lambda, 60) + 1e-9);
}

INSTANTIATE_TEST_SUITE_P(FourBehaviours, FlexibleFixedPoint,
                         ::testing::Values(Gait{0.105, "slip"}, Gait{0.13, "slip-stick-slip"}, Gait{0.2, "slip-stick"},
                                           Gait{0.6, "stick"}),
                         [](const auto& info) {
                           return "mu" + std::to_string(static_cast<int>(info.param.mu * 1000));
                         });

// The variational Jacobian (forward sensitivities, saltation matrices) agrees with finite
// differences of the map to 1e-6 (the bound), for every behaviour, through jam impulses,
// on both sections. The reference is central differences of a map integrated at rtol 1e-13,
// h = 3e-5 of each component's scale: measured, its error is the map's integration noise
// (~5e-11 at rtol 1e-12, ~5e-12 at 1e-13) over h plus a curvature term ~2e-6 (h / 1e-4)²,
// i.e. below 5e-7 here; at rtol 1e-12 the noise alone reaches 3e-6.
TEST(Poincare, VariationalJacobianMatchesFiniteDifferences) {
  for (double mu : {0.105, 0.13, 0.2, 0.6, 5.0}) {
    for (Section section : {Section::Touchdown, Section::Upright}) {
      if (section == Section::Upright && mu != 0.13) continue;  // one upright case keeps the test short
      const WheelParams w = testing::measured_wheel(mu);
      const SimulationOptions sim = testing::run_options(1);
      const auto r = find_fixed_point(w, sim, analysis(), Model::Flexible, section, {});
      ASSERT_TRUE(r.converged) << r.failure();
      ASSERT_TRUE(r.jacobian_exact) << r.jacobian_note;
      SimulationOptions map_opt = sim;
      map_opt.rtol = 1e-13;
      map_opt.atol = 1e-16;
      PoincareMap map(w, map_opt, Model::Flexible, section);
      const numerics::VectorMap P = [&](const Eigen::VectorXd& z, Eigen::VectorXd& out) {
        return map(r.point, z, out);
      };
      Eigen::MatrixXd reference;
      const auto failure = numerics::central_difference_jacobian(P, r.point.z, 3e-5 * r.point.scale(w), reference);
      ASSERT_FALSE(failure.has_value()) << *failure;
      EXPECT_LE((r.jacobian - reference).lpNorm<Eigen::Infinity>(), 1e-6) << "mu = " << mu << ", " << name_of(section);
    }
  }
}

// DOP853 and CVODE Adams, two independent integrators, find the same fixed point of every
// behaviour to 1e-8 (Newton's tolerance 1e-10 plus each map's integration error at rtol 1e-12),
// the same multipliers to 1e-7, and variational Jacobians (DOP853: the variational equations on
// its own steps) that agree to 1e-6, the bound Adams's meets against central differences above.
TEST(Poincare, Dop853FixedPointsAndJacobiansAgreeWithAdams) {
  for (double mu : {0.105, 0.13, 0.2, 0.6, 5.0}) {
    const WheelParams w = testing::measured_wheel(mu);
    SimulationOptions sim = testing::run_options(1);
    const auto adams = find_fixed_point(w, sim, analysis(), Model::Flexible, Section::Touchdown, {});
    sim.method = numerics::OdeMethod::Dop853;
    const auto dop = find_fixed_point(w, sim, analysis(), Model::Flexible, Section::Touchdown, {});
    ASSERT_TRUE(adams.converged && dop.converged) << adams.failure() << dop.failure();
    ASSERT_TRUE(dop.jacobian_exact) << dop.jacobian_note;
    EXPECT_EQ(adams.gait, dop.gait);
    EXPECT_LE((adams.point.z - dop.point.z).lpNorm<Eigen::Infinity>(), 1e-8) << "mu = " << mu;
    ASSERT_EQ(adams.multipliers.size(), dop.multipliers.size());
    for (std::size_t k = 0; k < adams.multipliers.size(); ++k)
      EXPECT_LE(std::abs(adams.multipliers[k] - dop.multipliers[k]), 1e-7) << "mu = " << mu << ", k = " << k;
    EXPECT_LE((adams.jacobian - dop.jacobian).lpNorm<Eigen::Infinity>(), 1e-6) << "mu = " << mu;
  }
}

// The multipliers are a property of the orbit, not of the section: both sections agree.
TEST(Poincare, MultipliersDoNotDependOnTheSection) {
  for (double mu : {0.13, 0.6}) {
    const WheelParams w = testing::measured_wheel(mu);
    const auto td = find_fixed_point(w, testing::run_options(1), analysis(), Model::Flexible, Section::Touchdown, {});
    const auto up = find_fixed_point(w, testing::run_options(1), analysis(), Model::Flexible, Section::Upright, {});
    ASSERT_TRUE(td.converged && up.converged) << td.failure() << up.failure();
    // Central differences at rtol 1e-12: the dominant multiplier agrees to 1e-6.
    EXPECT_NEAR(std::abs(td.multipliers[0]), std::abs(up.multipliers[0]), 1e-6) << "mu = " << mu;
    EXPECT_NEAR(td.period, up.period, 1e-9);
    EXPECT_NEAR(td.speed, up.speed, 1e-9);
    EXPECT_NEAR(td.dissipated, up.dissipated, 1e-9);
  }
}

// On a periodic orbit the energy dissipated per cycle equals the work of gravity, m g Δx sin φ.
TEST(Poincare, DissipationBalancesGravityOnTheOrbit) {
  const WheelParams w = testing::measured_wheel(0.13);
  const auto r = find_fixed_point(w, testing::run_options(1), analysis(), Model::Flexible, Section::Touchdown, {});
  ASSERT_TRUE(r.converged);
  const double gravity_work = w.m * w.g * std::sin(w.slope) * r.speed * r.period;
  EXPECT_NEAR(r.dissipated, gravity_work, 1e-9 * gravity_work);
}

TEST(Poincare, ReportsWhenThereIsNoFixedPoint) {
  // μ < tan φ: the wheel slides away; no fixed point, and the report says why.
  const WheelParams w = testing::measured_wheel(0.05);
  const auto r = find_fixed_point(w, testing::run_options(1), analysis(), Model::Flexible, Section::Touchdown, {});
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.failure().empty());
}

}  // namespace
}  // namespace flexgait::rimless
