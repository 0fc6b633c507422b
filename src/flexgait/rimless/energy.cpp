#include "flexgait/rimless/energy.hpp"

#include <cmath>

namespace flexgait::rimless {

double kinetic_energy(const WheelParams& w, std::span<const double> y) {
  using S = StateIndex;
  return 0.5 * w.m * (y[S::xd] * y[S::xd] + y[S::yd] * y[S::yd]) + 0.5 * w.I * y[S::thetad] * y[S::thetad];
}

EnergyTerms mechanical_energy(const WheelParams& w, const ContactSet& contacts, std::span<const double> y) {
  using S = StateIndex;
  EnergyTerms e;
  e.kinetic = kinetic_energy(w, y);
  e.gravity = w.m * w.g * (y[S::y] * std::cos(w.slope) - y[S::x] * std::sin(w.slope));
  for (int k = 0; k < w.legs; ++k) {
    const int i = contacts.find(k);
    const double delta = i >= 0 ? leg_kinematics(w, k, y).delta : y[S::free_delta + k];
    e.spring += 0.5 * w.K * delta * delta;
  }
  return e;
}

}  // namespace flexgait::rimless
