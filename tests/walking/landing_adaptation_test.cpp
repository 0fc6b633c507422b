// Landing orientation control (walking/landing_adaptation.hpp): off it never tilts a sole; the
// stance the robot starts in opens no window; after a touchdown from a swing the tilt integrates
// (L1) exactly for the window, is held after it and while the F/T readings are bad, is clamped per
// axis, and returns to level while the foot swings.
#include "flexgait/walking/landing_adaptation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flexgait::walking {
namespace {

constexpr double kPeriod = 0.004;  // [s]

TEST(LandingAdaptation, OffItNeverTilts) {
  LandingAdaptation a(LandingGains{0.0, 0.2, 0.15, 0.1});
  for (int k = 0; k < 100; ++k) a.update(0, k * kPeriod, kPeriod, false, true, Eigen::Vector2d(20, -30), true);
  EXPECT_EQ(a.tilt(0), Eigen::Vector2d::Zero());
}

TEST(LandingAdaptation, TheStanceItStartsInOpensNoWindow) {
  // Loaded from t = 0 with a torque (the twin settling onto its soles): not a landing, no tilt.
  LandingAdaptation a(LandingGains{0.01, 0.2, 0.15, 0.1});
  for (int k = 0; k < 100; ++k) a.update(0, k * kPeriod, kPeriod, false, true, Eigen::Vector2d(20, -30), true);
  EXPECT_EQ(a.tilt(0), Eigen::Vector2d::Zero());
}

TEST(LandingAdaptation, IntegratesTheTorqueForTheWindowFromTouchdownThenHolds) {
  const LandingGains g{0.01, 0.2, 0.15, 0.1};
  LandingAdaptation a(g);
  const Eigen::Vector2d torque(2.0, -3.0);  // [Nm]: 0.02 and −0.03 rad/s, far from the clamp
  int periods_in_window = 0;
  for (int k = 0; k < 200; ++k) {
    const double t = k * kPeriod;
    const bool contact = t >= 0.1;  // swings, touches down at 0.1 s: nothing before
    a.update(1, t, kPeriod, !contact, contact, torque, true);
    if (contact && t - 0.1 < g.window - 1e-9) ++periods_in_window;
    if (!contact) {
      EXPECT_EQ(a.tilt(1), Eigen::Vector2d::Zero());
    }
  }
  EXPECT_EQ(periods_in_window, 50);  // 0.2 s at 4 ms
  // δ = A τ × (periods × T); the sum of 50 equal increments, to rounding (1e-15 rad).
  EXPECT_NEAR(a.tilt(1).x(), g.admittance * torque.x() * 50 * kPeriod, 1e-15);
  EXPECT_NEAR(a.tilt(1).y(), g.admittance * torque.y() * 50 * kPeriod, 1e-15);
  EXPECT_EQ(a.tilt(0), Eigen::Vector2d::Zero());  // the other foot never touched
}

TEST(LandingAdaptation, ClampsEachAxisAndHoldsWhileTheReadingsAreBad) {
  LandingAdaptation a(LandingGains{0.1, 1.0, 0.05, 0.1});
  a.update(0, -kPeriod, kPeriod, true, false, Eigen::Vector2d::Zero(), true);  // a swing, then the landing at 0
  for (int k = 0; k < 100; ++k) a.update(0, k * kPeriod, kPeriod, false, true, Eigen::Vector2d(100, -1), true);
  EXPECT_DOUBLE_EQ(a.tilt(0).x(), 0.05);  // 10 rad/s against a 0.05 rad clamp
  const double y = a.tilt(0).y();         // −0.1 rad/s × 0.4 s = −0.04 rad: inside
  EXPECT_NEAR(y, -0.04, 1e-12);
  for (int k = 100; k < 150; ++k) a.update(0, k * kPeriod, kPeriod, false, true, Eigen::Vector2d(0, -100), false);
  EXPECT_EQ(a.tilt(0).y(), y);
}

TEST(LandingAdaptation, ReturnsToLevelInTheAirAndAdaptsAgainAtTheNextTouchdown) {
  const LandingGains g{0.01, 0.1, 0.15, 0.1};
  LandingAdaptation a(g);
  a.update(0, -kPeriod, kPeriod, true, false, Eigen::Vector2d::Zero(), true);  // a swing, then the landing at 0
  for (int k = 0; k < 50; ++k) a.update(0, k * kPeriod, kPeriod, false, true, Eigen::Vector2d(5, 5), true);
  const double held = a.tilt(0).x();
  ASSERT_GT(held, 0.0);
  // 0.5 s of swing with T_r = 0.1 s: (1 − T/(T_r + T))^125 = e^{−4.9} ≈ 0.0074 of it remains.
  for (int k = 50; k < 175; ++k) a.update(0, k * kPeriod, kPeriod, true, false, Eigen::Vector2d(5, 5), true);
  EXPECT_LT(a.tilt(0).norm(), 0.01 * held * std::sqrt(2.0));
  const Eigen::Vector2d before = a.tilt(0);
  // A new touchdown opens a new window.
  a.update(0, 175 * kPeriod, kPeriod, false, true, Eigen::Vector2d(5, 5), true);
  EXPECT_NEAR(a.tilt(0).x() - before.x(), g.admittance * 5 * kPeriod, 1e-15);
}

}  // namespace
}  // namespace flexgait::walking
