// The DOP853 stepper's observed orders on a problem with a known solution: a table silently
// degraded (a wrong coefficient, a stage wrongly reused as first-same-as-last) shows as a lower
// order here.
#include "flexgait/numerics/dop853.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flexgait::numerics {
namespace {

// y' = -2 a² t y², y(0) = 1: y = 1 / (1 + a² t²), a = 4. Nonlinear and non-autonomous, so the
// nonlinear order conditions count (a linear test problem checks only the stability polynomial).
constexpr double kA2 = 16.0;
double exact(double t) {
  return 1.0 / (1.0 + kA2 * t * t);
}
bool flow(double t, std::span<const double> y, std::span<double> yd) {
  yd[0] = -2.0 * kA2 * t * y[0] * y[0];
  return true;
}

Dop853 fixed_step_stepper(double h) {
  Dop853Options o;
  o.rtol = o.atol = 1e3;  // every step is accepted: the steps are max_step exactly
  o.max_step = h;
  return Dop853(flow, 1, o);
}

// Global error at t = 2.5 from t = 0.5 with the fixed step h (<= 0.3, the first step dop853.f's
// initial-step rule allows here).
double global_error(double h) {
  Dop853 s = fixed_step_stepper(h);
  s.start(0.5, std::vector<double>{exact(0.5)});
  while (s.time() < 2.5) {
    s.step(2.5);
    EXPECT_NEAR(s.time() - s.previous_time(), h, 1e-12);
  }
  return std::abs(s.state()[0] - exact(2.5));
}

// Error of the dense output in the middle of a first step of length h (local error).
double dense_error(double h) {
  Dop853 s = fixed_step_stepper(h);
  s.start(0.5, std::vector<double>{exact(0.5)});
  s.step(0.5 + h);
  EXPECT_NEAR(s.time() - s.previous_time(), h, 1e-12);
  std::vector<double> y(1);
  const double tm = 0.5 + 0.37 * h;
  s.dense(tm, y);
  return std::abs(y[0] - exact(tm));
}

// Halving the step divides the global error by ~2^8: observed order log2(e(h)/e(h/2)) within
// [7.5, 9] for h = 0.2 → 0.1 → 0.05 (measured 8.6 and 8.3, errors 4e-11 → 3e-16, still 100 ulp
// of y; a 7th-order defect would show ≤ 7).
TEST(Dop853, GlobalErrorHasOrderEight) {
  const double e1 = global_error(0.2), e2 = global_error(0.1), e3 = global_error(0.05);
  const double p1 = std::log2(e1 / e2), p2 = std::log2(e2 / e3);
  EXPECT_GT(p1, 7.5);
  EXPECT_LT(p1, 9.0);
  EXPECT_GT(p2, 7.5);
  EXPECT_LT(p2, 9.0);
}

// The dense output has order 7: its local error is O(h^8); observed log2 ratio within [7.4, 8.8]
// for h = 0.2 → 0.1 → 0.05 (measured 8.4 and 8.6; order 6 would show ≈ 7, order 5 ≈ 6).
TEST(Dop853, DenseOutputHasOrderSeven) {
  const double e1 = dense_error(0.2), e2 = dense_error(0.1), e3 = dense_error(0.05);
  EXPECT_GT(std::log2(e1 / e2), 7.4);
  EXPECT_LT(std::log2(e1 / e2), 8.8);
  EXPECT_GT(std::log2(e2 / e3), 7.4);
  EXPECT_LT(std::log2(e2 / e3), 8.8);
}

// Adaptive: at rtol 1e-10 the error at t = 2 stays near the tolerance, and truncating a step
// ends it on the dense output.
TEST(Dop853, AdaptiveStepsMeetTheToleranceAndTruncate) {
  Dop853Options o;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  Dop853 s(flow, 1, o);
  s.start(0.0, std::vector<double>{1.0});
  while (s.time() < 2.0) s.step(2.0);
  EXPECT_EQ(s.time(), 2.0);  // lands on the stop time exactly
  EXPECT_NEAR(s.state()[0], exact(2.0), 1e-9);
  const double tm = 0.5 * (s.previous_time() + s.time());
  s.truncate(tm);
  EXPECT_EQ(s.time(), tm);
  EXPECT_NEAR(s.state()[0], exact(tm), 1e-9);
  s.step(2.0);  // continues from the truncation point
  EXPECT_GT(s.time(), tm);
}

}  // namespace
}  // namespace flexgait::numerics
