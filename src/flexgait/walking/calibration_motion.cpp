#include "flexgait/walking/calibration_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flexgait::walking {

namespace {
double sin_squared(double x) {
  const double s = std::sin(x);
  return s * s;
}
}  // namespace

CalibrationOffset calibration_offset(const CalibrationMotion& m, double t) {
  CalibrationOffset o;
  const double s = t - m.start;
  if (!(m.time > 0) || s <= 0 || s >= m.time) return o;
  constexpr double pi = std::numbers::pi;
  // The fade: sin² over the ramp at each end (a shorter calibration fades over half of it each way).
  const double ramp = std::min(m.ramp, 0.5 * m.time);
  const double fade = sin_squared(0.5 * pi * std::min({1.0, s / ramp, (m.time - s) / ramp}));
  const double w = 2 * pi / m.period;
  o.com_y = fade * m.com_y * std::sin(w * s);
  o.com_x = fade * m.com_x * std::sin(w * s / CalibrationMotion::kForwardRatio);
  o.pelvis_z = -fade * m.squat * sin_squared(0.5 * w * s / CalibrationMotion::kSquatRatio);
  o.pelvis_pitch = fade * m.pelvis_pitch * std::sin(w * s / CalibrationMotion::kPelvisPitchRatio);
  o.sole_roll[0] = fade * m.sole_roll * std::sin(w * s / CalibrationMotion::kLeftSoleRollRatio);
  o.sole_roll[1] = fade * m.sole_roll * std::sin(w * s / CalibrationMotion::kRightSoleRollRatio);
  return o;
}

}  // namespace flexgait::walking
