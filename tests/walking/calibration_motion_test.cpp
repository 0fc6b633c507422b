// The stiffness calibration's motion (calibration_motion.hpp): nothing outside its window or when off; it fades
// in and out from rest (value and rate → 0 at both ends: the sin² fade's value and slope vanish there); no
// component exceeds its amplitude and the squat only lowers the pelvis; the controller's commanded soles stay
// where the plan puts them while the COM reference follows the sideways and forward offsets.
#include "flexgait/walking/calibration_motion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

#include "flexgait/walking/walking_controller.hpp"

namespace flexgait::walking {
namespace {

CalibrationMotion sixty_seconds() {
  CalibrationMotion m;
  m.time = 60.0;
  return m;
}

double magnitude(const CalibrationOffset& o) {
  return std::abs(o.com_x) + std::abs(o.com_y) + std::abs(o.pelvis_z) + std::abs(o.pelvis_pitch) +
         std::abs(o.sole_roll[0]) + std::abs(o.sole_roll[1]);
}

TEST(CalibrationMotion, NothingOutsideItsWindowOrWhenOff) {
  const CalibrationMotion m = sixty_seconds();
  EXPECT_EQ(magnitude(calibration_offset(m, 0.5)), 0.0);
  EXPECT_EQ(magnitude(calibration_offset(m, 61.5)), 0.0);
  EXPECT_GT(magnitude(calibration_offset(m, 30.0)), 0.0);
  CalibrationMotion off = m;
  off.time = 0;
  EXPECT_EQ(magnitude(calibration_offset(off, 30.0)), 0.0);
  EXPECT_EQ(off.end(), 0.0);
  EXPECT_EQ(m.end(), 61.0);
}

TEST(CalibrationMotion, StartsAndEndsAtRestAndStaysWithinItsAmplitudes) {
  const CalibrationMotion m = sixty_seconds();
  // 1 ms into and before the end of the window: the fade sin²(π/2 · s/ramp) ≈ (π/2 · 1e-3/3)² ≈ 3e-7.
  for (const double t : {m.start + 1e-3, m.end() - 1e-3}) {
    const CalibrationOffset o = calibration_offset(m, t);
    EXPECT_LT(magnitude(o), 1e-7) << t;
  }
  double lowest = 0, highest = 0;
  for (double t = m.start; t <= m.end(); t += 0.004) {
    const CalibrationOffset o = calibration_offset(m, t);
    EXPECT_LE(std::abs(o.com_y), m.com_y);
    EXPECT_LE(std::abs(o.com_x), m.com_x);
    EXPECT_LE(std::abs(o.pelvis_pitch), m.pelvis_pitch);
    EXPECT_LE(std::abs(o.sole_roll[0]), m.sole_roll);
    EXPECT_LE(std::abs(o.sole_roll[1]), m.sole_roll);
    EXPECT_LE(o.pelvis_z, 0.0);
    EXPECT_GE(o.pelvis_z, -m.squat);
    lowest = std::min(lowest, o.pelvis_z);
    highest = std::max(highest, o.com_y);
  }
  // Over 60 s every component reaches most of its amplitude (the squat's 11 s period, the COM's 5 s).
  EXPECT_LT(lowest, -0.95 * m.squat);
  EXPECT_GT(highest, 0.95 * m.com_y);
}

TEST(CalibrationMotion, TheControllersSolesStayPutWhileItsComReferenceMoves) {
  WalkParams w;
  w.steps = 0;
  w.calibration.time = 20.0;
  w.start_time = 23.0;
  BalanceParams balance;
  balance.enabled = false;  // (the commands alone: no sensor feedback)
  HealthParams constant;
  constant.stuck_samples = 0;  // (these synthetic readings are constant: not stuck)
  WalkingController c(humanoid::RobotParams{}, w, balance, 0.004, EstimatorParams{}, constant);
  humanoid::SensorReadings s;
  for (auto& ft : s.ft) ft.force = {0, 0, -250.0};
  s.imu.accel = {0, 0, 9.81};
  double com_y_max = 0;
  std::array<Pose, 2> soles0;
  for (int k = 0; k < static_cast<int>(20.0 / 0.004); ++k) {
    const double t = k * 0.004;
    s.t = t;
    s.encoder_stamp.fill(t);
    for (auto& ft : s.ft) ft.stamp = t;
    s.imu.gyro_stamp = s.imu.accel_stamp = s.imu.quat_stamp = t;
    c.update(s, t);
    if (k == 0) {
      soles0 = c.status().sole;
      continue;
    }
    for (int side = 0; side < 2; ++side) {
      ASSERT_FALSE(c.status().swinging[side]);
      EXPECT_LT((c.status().sole[side].p - soles0[side].p).norm(), 1e-12) << t;
    }
    com_y_max = std::max(com_y_max, std::abs(c.status().com_ref.y()));
  }
  // The COM follows the ZMP reference's ±7 cm (the preview's cart: about as far at 5 s periods).
  EXPECT_GT(com_y_max, 0.05);
}

// The soles' rolls are what tells the two ankle rolls apart, so nothing else may move at their
// frequencies. The plant is not linear (the contact, the weight split times a lever), so each
// component also makes its double and, with each other one, its sum and difference frequency. The
// least squares over a window T resolves frequencies 1/T apart: with the default 90 s window and
// 5 s sideways period, 0.056 ω. Each sole roll must keep 0.1 ω (about two resolutions) from every such
// product of the other components, the other sole's roll included. Frequencies in units of the
// sideways one, ω = 2π/calibration.period.
TEST(CalibrationMotion, TheSoleRollsKeepClearOfTheOtherComponentsSecondOrderProducts) {
  using M = CalibrationMotion;
  const double others[] = {1.0, 1 / M::kForwardRatio, 1 / M::kSquatRatio, 1 / M::kPelvisPitchRatio};
  const double soles[2] = {1 / M::kLeftSoleRollRatio, 1 / M::kRightSoleRollRatio};
  for (int side = 0; side < 2; ++side) {
    std::vector<double> f(std::begin(others), std::end(others));
    f.push_back(soles[1 - side]);
    double nearest = 1e9;
    for (std::size_t i = 0; i < f.size(); ++i) {
      nearest = std::min({nearest, std::abs(soles[side] - f[i]), std::abs(soles[side] - 2 * f[i])});
      for (std::size_t j = i + 1; j < f.size(); ++j)
        nearest =
            std::min({nearest, std::abs(soles[side] - (f[i] + f[j])), std::abs(soles[side] - std::abs(f[i] - f[j]))});
    }
    EXPECT_GE(nearest, 0.1) << "side " << side;
  }
}

}  // namespace
}  // namespace flexgait::walking
