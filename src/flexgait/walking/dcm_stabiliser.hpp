#pragma once
/// \file dcm_stabiliser.hpp
/// The divergent component of motion (DCM) tracked by a ZMP command (Englsberger et al., "Three-
/// dimensional bipedal walking control based on divergent component of motion", IEEE T-RO 2015;
/// Caron et al., "Stair climbing stabilization of the HRP-4 humanoid robot using whole-body
/// admittance control", ICRA 2019). In the linear inverted pendulum (ω = √(g / z_c))
///
///   ξ = c + ċ / ω,   ξ̇ = ω (ξ − p),                                                (D1)
///
/// and the reference (ξ_ref, p_ref) satisfies the same law. The ZMP command
///
///   p_d = p_ref + (1 + k_p / ω) e + (k_i / ω) ∫ e dt,   e = ξ − ξ_ref,                  (D2)
///
/// gives, where the ZMP follows the command, ė = −k_p e − k_i ∫ e: ë + k_p ė + k_i e = 0, stable
/// for k_p, k_i > 0 (Caron et al.'s HRP-4 gains k_p = 5 1/s, k_i = 10 1/s²: roots −2.5 ± 1.94 i).
/// The integral is clamped (anti-windup) and held on request (while a sensor it needs is held).
/// Pure arithmetic on fixed-size values: no allocation, no simulator.
#include <Eigen/Dense>

namespace flexgait::walking {

struct DcmGains {
  double kp = 5.0;               ///< k_p [1/s]
  double ki = 10.0;              ///< k_i [1/s^2]
  double integral_limit = 0.05;  ///< clamp of each component of ∫ e dt [m s]
};

class DcmStabiliser {
 public:
  explicit DcmStabiliser(const DcmGains& gains = {}) : gains_(gains) {}

  /// The ZMP command (D2) for the measured DCM `xi` against `xi_ref` with the reference ZMP
  /// `p_ref`, ω [1/s]; advances the integral by dt [s] unless `hold` [m].
  Eigen::Vector2d zmp_command(const Eigen::Vector2d& xi, const Eigen::Vector2d& xi_ref, const Eigen::Vector2d& p_ref,
                              double omega, double dt, bool hold = false);
  /// e = ξ − ξ_ref of the last command [m].
  const Eigen::Vector2d& error() const { return error_; }
  const Eigen::Vector2d& integral() const { return integral_; }
  void reset() {
    error_.setZero();
    integral_.setZero();
  }

 private:
  DcmGains gains_;
  Eigen::Vector2d error_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d integral_ = Eigen::Vector2d::Zero();
};

/// The DCM ξ = c + ċ / ω (D1) of a COM position and velocity [m].
inline Eigen::Vector2d dcm_of(const Eigen::Vector2d& c, const Eigen::Vector2d& c_dot, double omega) {
  return c + c_dot / omega;
}

}  // namespace flexgait::walking
