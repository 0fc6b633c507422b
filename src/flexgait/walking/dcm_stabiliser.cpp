#include "flexgait/walking/dcm_stabiliser.hpp"

namespace flexgait::walking {

Eigen::Vector2d DcmStabiliser::zmp_command(const Eigen::Vector2d& xi, const Eigen::Vector2d& xi_ref,
                                           const Eigen::Vector2d& p_ref, double omega, double dt, bool hold) {
  error_ = xi - xi_ref;
  if (!hold) {
    const double lim = gains_.integral_limit;
    integral_ = (integral_ + dt * error_).cwiseMax(-lim).cwiseMin(lim);
  }
  return p_ref + (1.0 + gains_.kp / omega) * error_ + (gains_.ki / omega) * integral_;  // (D2)
}

}  // namespace flexgait::walking
