#include "flexgait/walking/tilt_observer.hpp"

#include <algorithm>
#include <cmath>

namespace flexgait::walking {

void TiltObserver::reset(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2) {
  x1_ = x1;
  x2_ = x2.normalized();
  x2_prime_ = x2_;
  started_ = true;
}

void TiltObserver::update(const Eigen::Vector3d& y_v, const Eigen::Vector3d& y_a, const Eigen::Vector3d& omega,
                          double dt) {
  const TiltObserverGains& k = gains_;
  const Eigen::Vector3d e = y_v - x1_;  // (T3)
  const Eigen::Vector3d dx1 = x1_.cross(omega) - k.gravity * x2_prime_ + y_a + k.alpha * e;
  const Eigen::Vector3d dx2_prime = x2_prime_.cross(omega) - k.beta * e;
  const Eigen::Vector3d dx2 = x2_.cross(omega - k.gamma * x2_.cross(x2_prime_));
  x1_ += dt * dx1;
  x2_prime_ += dt * dx2_prime;
  x2_ = (x2_ + dt * dx2).normalized();
}

Eigen::Vector2d roll_pitch_of_tilt(const Eigen::Vector3d& tilt) {
  return Eigen::Vector2d(std::atan2(tilt.y(), tilt.z()), std::asin(std::clamp(-tilt.x(), -1.0, 1.0)));
}

}  // namespace flexgait::walking
