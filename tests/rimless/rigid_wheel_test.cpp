// The rigid rimless wheel: the analytic limit (spec rimless.md, "Checks").
#include "flexgait/rimless/rigid_wheel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "flexgait/rimless/flexible_wheel.hpp"
#include "test_support.hpp"

namespace flexgait::rimless {
namespace {

WheelParams point_mass_wheel(int legs) {
  WheelParams w;
  w.I = 0.0;
  w.legs = legs;
  return w;
}

TEST(RigidWheel, StepMapMatchesMcGeersClosedForm) {
  const WheelParams w = point_mass_wheel(10);
  const RigidStepMap map = rigid_step_map(w);
  const double alpha = w.alpha();
  const double a = 4.0 * (w.g / w.L0) * std::sin(alpha) * std::sin(w.slope);
  EXPECT_NEAR(map.fixed_point(), std::sqrt(a) / std::tan(2 * alpha), 1e-14);  // ω* = cot 2α sqrt(a)
  EXPECT_NEAR(map.next(map.fixed_point()), map.fixed_point(), 1e-14);
  EXPECT_NEAR(map.derivative(map.fixed_point()), std::pow(std::cos(2 * alpha), 2), 1e-14);
  // α = π/8: the multiplier is cos²(π/4) = 1/2.
  EXPECT_NEAR(rigid_step_map(point_mass_wheel(8)).derivative(rigid_step_map(point_mass_wheel(8)).fixed_point()), 0.5,
              1e-15);
}

TEST(RigidWheel, InertiaKeepsAngularMomentumAboutTheNewFoot) {
  WheelParams w = point_mass_wheel(10);
  w.I = 0.3;
  const RigidStepMap map = rigid_step_map(w);
  const double ml2 = w.m * w.L0 * w.L0;
  EXPECT_NEAR(map.r, (ml2 * std::cos(2 * w.alpha()) + w.I) / (ml2 + w.I), 1e-15);
  EXPECT_NEAR(map.derivative(map.fixed_point()), map.r * map.r, 1e-14);
}

// The simulated wheel, started on the fixed point's orbit, reproduces ω* after every impact to
// 1e-9 (integration at rtol 1e-12 over a step of ~0.4 s).
TEST(RigidWheel, SimulationReachesTheAnalyticFixedPoint) {
  for (double I : {0.0, 0.3}) {
    WheelParams w = point_mass_wheel(10);
    w.I = I;
    const RigidStepMap map = rigid_step_map(w);
    const double J = w.m * w.L0 * w.L0 + w.I;
    // Speed at β = 0 on the fixed orbit: energy from β = -α (ω*) to β = 0.
    const double omega0 = std::sqrt(map.fixed_point() * map.fixed_point() -
                                    2 * w.m * w.g * w.L0 * (std::cos(w.slope) - std::cos(w.slope - w.alpha())) / J);
    SimulationOptions o = testing::run_options(6, 1e-12);
    o.atol = 1e-14;
    const SimulationResult r = simulate_rigid(w, InitialState{omega0, 0.0}, o);
    ASSERT_FALSE(r.failure.has_value()) << *r.failure;
    ASSERT_EQ(r.steps_completed, 6);
    int impacts = 0;
    for (std::size_t i = 1; i < r.samples.size(); ++i) {
      // The sample logged right after an impact carries β = -α and ω⁺.
      if (r.samples[i].t == r.samples[i - 1].t) {
        EXPECT_NEAR(r.samples[i].q[5], map.fixed_point(), 1e-9) << "I = " << I << ", impact " << impacts;
        ++impacts;
      }
    }
    EXPECT_EQ(impacts, 6);
    EXPECT_LE(r.energy_balance_error, 1e-11);
    // Every touchdown is a step of length 2 L0 sin α.
    EXPECT_NEAR(r.steps[3].x_end - r.steps[3].x_start, 2 * w.L0 * std::sin(w.alpha()), 1e-9);
  }
}

TEST(RigidWheel, ConvergesToTheFixedPointFromElsewhere) {
  const WheelParams w = point_mass_wheel(10);
  const RigidStepMap map = rigid_step_map(w);
  SimulationOptions o = testing::run_options(40, 1e-12);
  const SimulationResult r = simulate_rigid(w, InitialState{2.5, 0.0}, o);
  ASSERT_FALSE(r.failure.has_value());
  const double omega_last = r.samples.back().q[5];
  // The last sample is at the last impact: ω⁺ within cos²(2α)^39 of ω* (the map contracts).
  EXPECT_NEAR(omega_last, map.fixed_point(), 1e-6);
}

TEST(RigidWheel, TooSlowRollsBack) {
  const SimulationResult r = simulate_rigid(point_mass_wheel(10), InitialState{-0.5, 0.0}, testing::run_options(3));
  ASSERT_TRUE(r.failure.has_value());
  EXPECT_EQ(r.failure->reason, FailureReason::FellBack) << *r.failure;
}

// Stiff, well-damped legs with tan α < μ < cot α: the flexible wheel's hub follows the rigid
// wheel's pendulum about the foot (spec rimless.md, "Checks").
TEST(RigidWheel, StiffFlexibleWheelApproachesIt) {
  WheelParams w = testing::measured_wheel(1.0);
  auto speed_gap = [&](double K) {
    w.K = K;
    w.C = 2.0 * std::sqrt(K * w.m);  // critically damped leg
    SimulationOptions o = testing::run_options(30);
    o.log = false;
    const SimulationResult flex = simulate_flexible(w, InitialState{}, o);
    const SimulationResult rigid = simulate_rigid(w, InitialState{}, o);
    EXPECT_FALSE(flex.failure.has_value()) << *flex.failure;
    const auto& a = flex.steps[28];
    const auto& b = rigid.steps[28];
    return std::abs((a.t_end - a.t_start) - (b.t_end - b.t_start)) / (b.t_end - b.t_start);
  };
  // The limit is not exact: a stiff damped leg's landing is a short double support with a
  // landing slip, not McGeer's instantaneous inelastic impact. Measured: 0.11 % (K = 1e4),
  // 0.35 % (K = 1e6). A soft leg (K = 300) differs by several per cent.
  for (double K : {1e4, 1e5, 1e6}) EXPECT_LT(speed_gap(K), 0.01) << "K = " << K;
  EXPECT_GT(speed_gap(300.0), 0.02);
}

}  // namespace
}  // namespace flexgait::rimless
