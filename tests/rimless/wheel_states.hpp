#pragma once
// Hand-built states of the flexible wheel for the tests of its pure functions (dynamics, flow,
// energy): the hub at (x, y) with velocities, feet on the ground where their legs point, free legs
// compressed by given amounts (contact.hpp's StateIndex layout).
#include <cmath>
#include <span>
#include <vector>

#include "flexgait/rimless/contact.hpp"

namespace flexgait::rimless::testing {

struct WheelState {
  std::vector<double> y;
  ContactSet contacts;
};

/// θ, hub height, velocities (ẋ, ẏ, θ̇); free leg k compressed by 1e-3·(k + 1) m; the given legs on
/// the ground in the given modes, each anchored where its foot is (c = x - y tan β).
inline WheelState wheel_state(const WheelParams& w, double theta, double height, double xd, double yd, double thetad,
                              std::initializer_list<std::pair<int, FootMode>> feet) {
  WheelState s;
  s.y.assign(static_cast<std::size_t>(state_size(w)), 0.0);
  s.y[StateIndex::x] = 0.3;
  s.y[StateIndex::y] = height;
  s.y[StateIndex::theta] = theta;
  s.y[StateIndex::xd] = xd;
  s.y[StateIndex::yd] = yd;
  s.y[StateIndex::thetad] = thetad;
  for (int k = 0; k < w.legs; ++k) s.y[static_cast<std::size_t>(StateIndex::free_delta + k)] = 1e-3 * (k + 1);
  for (const auto& [leg, mode] : feet) {
    const int i = s.contacts.count++;
    s.contacts.leg[i] = leg;
    s.contacts.mode[i] = mode;
    s.contacts.anchor[i] = leg_kinematics(w, leg, s.y).c;
  }
  return s;
}

}  // namespace flexgait::rimless::testing
