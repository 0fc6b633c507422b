#include "flexgait/walking/landing_adaptation.hpp"

namespace flexgait::walking {

void LandingAdaptation::update(int side, double t, double period, bool swinging, bool contact,
                               const Eigen::Vector2d& torque, bool live) {
  Eigen::Vector2d& d = tilt_[side];
  if (gains_.admittance <= 0) return;
  if (swinging) {  // back to level in the air
    landed_[side] = false;
    d -= period / (gains_.return_time + period) * d;
    return;
  }
  if (!landed_[side] && contact) {
    landed_[side] = true;
    touchdown_[side] = t;
  }
  if (!landed_[side] || !live || t - touchdown_[side] > gains_.window - 0.5 * period) return;    // held
  d = (d + period * gains_.admittance * torque).cwiseMax(-gains_.limit).cwiseMin(gains_.limit);  // (L1)
}

}  // namespace flexgait::walking
