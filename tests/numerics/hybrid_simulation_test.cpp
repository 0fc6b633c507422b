// The hybrid loop on a bouncing ball, whose impact times are known in closed form and accumulate
// (a Zeno sequence) at a finite time.
#include "flexgait/numerics/hybrid_simulation.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace flexgait::numerics {
namespace {

constexpr double kG = 9.81;  // [m/s²]

// Ball at height h with velocity v: ḣ = v, v̇ = -g. Guard h ↓ 0 (the ground); reset v⁺ = -e v⁻
// (Newton's restitution), postcondition v⁺ >= 0.
class Ball final : public OdeSystem {
 public:
  bool rhs(double, std::span<const double> y, std::span<double> yd) override {
    yd[0] = y[1];
    yd[1] = -kG;
    return true;
  }
  void guards(double, std::span<const double> y, std::span<double> g) override { g[0] = y[0]; }
};

class BouncingBall final : public HybridModel {
 public:
  BouncingBall(double e, int bounces) : e_(e), bounces_(bounces) {}
  bool finished() const override { return static_cast<int>(impacts.size()) >= bounces_; }
  double stop_time() const override { return 100.0; }
  void sample(double t, std::span<const double> y) override { samples.push_back({t, y[0]}); }
  // The missed-event check: the ball below the ground (by more than the impacts' 1e-9 s times
  // the largest speed, sqrt(2 g h0) ≈ 4.4 m/s, rounded up to 1e-8 m).
  bool smooth_step(double t, std::span<const double> y, StepStatus status) override {
    if (y[0] < -1e-8) fail(t, "missed event: the ball is below the ground");
    if (status == StepStatus::StopTime) fail(t, "time limit");
    return failure.empty();
  }
  HybridNext guards_crossed(double t, std::span<const double>, std::span<const int> fired, const OdeIntegrator&,
                            std::vector<HybridEvent>& events) override {
    EXPECT_EQ(fired[0], -1);
    impacts.push_back(t);
    events.push_back({0, 0});
    return HybridNext::Restart;
  }
  // Postcondition: the ball leaves the ground (v⁺ > 0); a crossing met on the way up is the
  // integrator's round-off at a flight too short to resolve: the model names it and stops.
  HybridNext reset(double t, std::span<double> y, std::span<const HybridEvent>) override {
    y[0] = 0.0;
    y[1] = -e_ * y[1];
    if (!(y[1] > 0)) {
      fail(t, "impact on the way up: the flights are below the integrator's resolution");
      return HybridNext::Stop;
    }
    return HybridNext::Restart;
  }
  std::span<const int> directions() const override { return directions_; }
  void fail(double t, const std::string& why) {
    failure = why;
    failure_time = t;
  }
  void loop_failed(LoopFailure what, double t, const std::string&) override { fail(t, std::string(name_of(what))); }
  void work_limit_reached(WorkLimit, double, double) override { failure = "work limit"; }
  std::string describe(const HybridEvent&) const override { return "impact"; }

  std::vector<double> impacts;                 // [s]
  std::vector<std::array<double, 2>> samples;  // (t, h)
  std::string failure;
  double failure_time = 0;

 private:
  double e_;
  int bounces_;
  std::array<int, 1> directions_{-1};
};

// Dropped from h0 at rest: the first impact at t1 = sqrt(2 h0 / g) with speed v1 = g t1, then
// flights of 2 e^k v1 / g; they add up to t∞ = t1 + 2 e v1 / (g (1 - e)).
double impact_time(double h0, double e, int k) {
  const double t1 = std::sqrt(2 * h0 / kG);
  return t1 + 2 * t1 * e * (1 - std::pow(e, k)) / (1 - e);
}

double run(BouncingBall& ball, OdeMethod method, double h0, double sample_dt) {
  Ball flow;
  OdeOptions o;
  o.rtol = 1e-12;
  o.atol = 1e-14;
  o.method = method;
  OdeIntegrator integ(flow, 2, o);
  const std::array<double, 2> y0{h0, 0.0};
  integ.restart(0.0, y0, ball.directions());
  HybridSimulation loop(integ, 2);
  HybridLimits limits;
  limits.sample = sample_dt > 0;
  limits.sample_dt = sample_dt;
  return loop.run(ball, limits, 0.0);
}

TEST(HybridSimulation, ImpactTimesMatchTheClosedForm) {
  for (OdeMethod method : {OdeMethod::Dop853, OdeMethod::Adams}) {
    BouncingBall ball(0.8, 10);
    run(ball, method, 1.0, 0.0);
    ASSERT_EQ(ball.impacts.size(), 10u);
    EXPECT_TRUE(ball.failure.empty()) << ball.failure;
    // rtol 1e-12 on a quadratic flow (exact for both methods up to round-off) and ten restarts:
    // each impact to 1e-9 s.
    for (int k = 0; k < 10; ++k) EXPECT_NEAR(ball.impacts[static_cast<std::size_t>(k)], impact_time(1.0, 0.8, k), 1e-9);
  }
}

TEST(HybridSimulation, SamplesEveryPeriodOnTheFlow) {
  BouncingBall ball(0.8, 3);
  const double t_end = run(ball, OdeMethod::Dop853, 1.0, 0.01);
  // Samples at 0.01 k strictly before the last step's end: every one of them, none twice.
  ASSERT_EQ(ball.samples.size(), static_cast<std::size_t>(std::ceil(t_end / 0.01)) - 1);
  const double t1 = std::sqrt(2.0 / kG);
  for (std::size_t i = 0; i < ball.samples.size(); ++i) {
    const auto [t, h] = ball.samples[i];
    EXPECT_NEAR(t, 0.01 * static_cast<double>(i + 1), 1e-15);
    if (t < t1) {
      EXPECT_NEAR(h, 1.0 - 0.5 * kG * t * t, 1e-10);  // the first fall, in closed form
    }
  }
}

TEST(HybridSimulation, StopsAZenoSequenceBeforeItsAccumulationPoint) {
  // e = 0.5: the impacts accumulate at t∞ = 3 t1. The run must stop with a named failure (the
  // loop's Zeno watch or repeated-event watch, or the model's own checks once the flights reach
  // round-off), never by the time limit, and not past t∞ (to 1e-9 s: the impacts' accuracy).
  for (OdeMethod method : {OdeMethod::Dop853, OdeMethod::Adams}) {
    BouncingBall ball(0.5, 1'000'000);
    const double t_end = run(ball, method, 1.0, 0.0);
    const double t_inf = 3.0 * std::sqrt(2.0 / kG);
    EXPECT_FALSE(ball.failure.empty());
    EXPECT_NE(ball.failure, "time limit");
    EXPECT_LE(t_end, t_inf + 1e-9);
    // Measured: dop853 35 impacts (stopped by the repeated-event watch), adams 26 (the model's
    // postcondition); e^20 ≈ 1e-6: no watch stops a sequence of flights the integrator resolves.
    EXPECT_GT(ball.impacts.size(), 20u) << ball.failure;
  }
}

// y falls at unit speed onto its guard y = 0 and is reset to 1e-12 above it: an event every
// 1e-12 s. Events alternate between two units (or keep one, `same_unit`).
class Hopper final : public HybridModel {
 public:
  explicit Hopper(bool same_unit) : same_unit_(same_unit) {}
  bool finished() const override { return events >= 1000; }
  double stop_time() const override { return 10.0; }
  bool smooth_step(double, std::span<const double>, StepStatus status) override {
    if (status == StepStatus::StopTime) failure = "time limit";
    return status != StepStatus::StopTime;
  }
  HybridNext guards_crossed(double, std::span<const double>, std::span<const int>, const OdeIntegrator&,
                            std::vector<HybridEvent>& out) override {
    out.push_back({same_unit_ ? 0 : events % 2, 0});
    ++events;
    return HybridNext::Restart;
  }
  HybridNext reset(double, std::span<double> y, std::span<const HybridEvent>) override {
    y[0] = 1e-12;
    return HybridNext::Restart;
  }
  std::span<const int> directions() const override { return directions_; }
  void loop_failed(LoopFailure what, double, const std::string&) override { loop_failure = what; }
  void work_limit_reached(WorkLimit, double, double) override { failure = "work limit"; }
  std::string describe(const HybridEvent&) const override { return "hop"; }

  int events = 0;
  std::string failure;                      // the model's own stops
  std::optional<LoopFailure> loop_failure;  // the loop's

 private:
  bool same_unit_;
  std::array<int, 1> directions_{-1};
};

class Fall final : public OdeSystem {
 public:
  bool rhs(double, std::span<const double>, std::span<double> yd) override {
    yd[0] = -1.0;
    return true;
  }
  void guards(double, std::span<const double> y, std::span<double> g) override { g[0] = y[0]; }
};

void run_hopper(Hopper& hopper) {
  Fall fall;
  OdeOptions o;
  o.method = OdeMethod::Dop853;
  OdeIntegrator integ(fall, 1, o);
  const std::array<double, 1> y0{1.0};
  integ.restart(0.0, y0, hopper.directions());
  HybridSimulation loop(integ, 1);
  loop.run(hopper, HybridLimits{}, 0.0);
}

TEST(HybridSimulation, TheZenoWatchStopsKZenoCountEventsWithinItsWindow) {
  // Events 1e-12 s apart (located to ~1e-14 s): the 64th lies 63e-12 s after the first, inside
  // the 1e-9 s window, so the watch stops the run there, not earlier.
  Hopper hopper(false);
  run_hopper(hopper);
  EXPECT_EQ(hopper.loop_failure, LoopFailure::Zeno);
  EXPECT_EQ(hopper.events, static_cast<int>(HybridSimulation::kZenoCount));
}

TEST(HybridSimulation, AnEventAgainWithinItsRepeatWindowStopsTheRun) {
  // The same event 1e-12 s after itself (< kRepeatWindow = 1e-10 s): stopped at the second.
  Hopper hopper(true);
  run_hopper(hopper);
  EXPECT_EQ(hopper.loop_failure, LoopFailure::RepeatedEvent);
  EXPECT_EQ(hopper.events, 2);
}

}  // namespace
}  // namespace flexgait::numerics
