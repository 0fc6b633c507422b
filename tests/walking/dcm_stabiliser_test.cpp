// The DCM stabiliser on the cart-table (linear inverted pendulum) model, no simulator: the DCM
// error follows ë + k_p ė + k_i e = 0 where the ZMP follows its command; with the ZMP held inside
// a support interval, a push below the capture-point bound is recovered and one above is not.
#include "flexgait/walking/dcm_stabiliser.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace flexgait::walking {
namespace {

constexpr double kG = 9.81, kHeight = 0.8, kDt = 0.004;

/// One axis of the cart-table with the ZMP p held over dt, integrated exactly:
/// c(t) = p + (c0 − p) cosh ωt + (ċ0 / ω) sinh ωt.
struct Pendulum {
  double c = 0, v = 0;
  void step(double p, double omega, double dt) {
    const double ch = std::cosh(omega * dt), sh = std::sinh(omega * dt);
    const double c1 = p + (c - p) * ch + v / omega * sh;
    v = (c - p) * omega * sh + v * ch;
    c = c1;
  }
};

/// The sagittal axis pushed to velocity v0 at rest over p_ref = 0 (ξ_ref = 0), the ZMP following
/// the command within [−limit, limit]; returns the DCM error after `seconds`, and its largest
/// deviation from the analytic error of the linear loop when the ZMP is unlimited.
struct PushRun {
  double final_error = 0, max_deviation = 0;
};
PushRun push(double v0, double limit, double seconds) {
  const double omega = std::sqrt(kG / kHeight);
  const DcmGains gains;  // Caron et al.: k_p 5, k_i 10
  DcmStabiliser dcm(gains);
  Pendulum x{0.0, v0};
  // Analytic: e(0) = v0/ω, ė(0) = −k_p e(0); roots −k_p/2 ± i β.
  const double e0 = v0 / omega, a = gains.kp / 2, beta = std::sqrt(gains.ki - a * a);
  PushRun r;
  const long n = std::lround(seconds / kDt);
  for (long k = 0; k < n; ++k) {
    const double t = k * kDt;
    const Eigen::Vector2d xi(dcm_of({x.c, 0}, {x.v, 0}, omega));
    const double p = std::clamp(dcm.zmp_command(xi, {0, 0}, {0, 0}, omega, kDt)(0), -limit, limit);
    const double analytic = e0 * std::exp(-a * t) * (std::cos(beta * t) + (a - gains.kp) / beta * std::sin(beta * t));
    r.max_deviation = std::max(r.max_deviation, std::abs(xi(0) - analytic));
    x.step(p, omega, kDt);
  }
  r.final_error = std::abs(dcm_of({x.c, 0}, {x.v, 0}, omega)(0));
  return r;
}

TEST(DcmStabiliser, ErrorFollowsTheSecondOrderLoopAndConverges) {
  // The ZMP unlimited: the sampled loop (ZMP held over 4 ms) against the continuous solution:
  // within 1 % of e(0) (the hold delays the command by T/2 = 2 ms against the loop's 0.4 s);
  // after 4 s the error is below 1e-4 of e(0) (envelope e^{−2.5 · 4} = 4.5e-5).
  const double v0 = 0.3, e0 = v0 / std::sqrt(kG / kHeight);
  const PushRun r = push(v0, 1e9, 4.0);
  EXPECT_LT(r.max_deviation, 0.01 * e0);
  EXPECT_LT(r.final_error, 1e-4 * e0);
}

TEST(DcmStabiliser, CapturePointBoundSeparatesRecoveredFromNot) {
  // The ZMP held within ±d (the feet's edges, 0.11 m from the COM): Δv_max = ω d.
  const double d = 0.11, bound = std::sqrt(kG / kHeight) * d;
  EXPECT_LT(push(0.95 * bound, d, 6.0).final_error, 1e-3);  // recovered
  EXPECT_GT(push(1.05 * bound, d, 6.0).final_error, 1.0);   // diverged: ξ − d grows as e^{ωt}
}

TEST(DcmStabiliser, IntegralIsClampedAndHeld) {
  DcmStabiliser dcm(DcmGains{5, 10, 0.02});
  for (int k = 0; k < 1000; ++k) dcm.zmp_command({0.1, -0.1}, {0, 0}, {0, 0}, 3.5, 0.01);
  EXPECT_DOUBLE_EQ(dcm.integral()(0), 0.02);
  EXPECT_DOUBLE_EQ(dcm.integral()(1), -0.02);
  dcm.reset();
  const Eigen::Vector2d p = dcm.zmp_command({0.1, 0}, {0, 0}, {0.01, 0}, 3.5, 0.01, /*hold=*/true);
  EXPECT_DOUBLE_EQ(dcm.integral()(0), 0.0);
  EXPECT_DOUBLE_EQ(p(0), 0.01 + (1 + 5 / 3.5) * 0.1);  // (D2) by hand
}

}  // namespace
}  // namespace flexgait::walking
