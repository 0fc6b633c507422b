#include "flexgait/rimless/contact.hpp"

#include <cmath>

namespace flexgait::rimless {

const char* mode_name(FootMode m) {
  switch (m) {
    case FootMode::Stick:
      return "stick";
    case FootMode::SlipForward:
      return "slip+";
    case FootMode::SlipBackward:
      return "slip-";
  }
  return "?";
}

LegKinematics leg_kinematics(const WheelParams& w, int k, std::span<const double> s) {
  LegKinematics g;
  leg_kinematics(w, k, s, g);
  return g;
}

double foot_height(const WheelParams& w, int k, std::span<const double> s) {
  // cos is 2π-periodic: no need to wrap the angle (a hot path: every free leg, every step).
  const double cb = std::cos(s[StateIndex::theta] + 2.0 * w.alpha() * k);
  return s[StateIndex::y] - (w.L0 - s[StateIndex::free_delta + k]) * cb;
}

}  // namespace flexgait::rimless
