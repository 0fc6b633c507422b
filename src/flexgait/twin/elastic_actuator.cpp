#include "flexgait/twin/elastic_actuator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flexgait::twin {

double gear_deflection(const ActuatorParams& p, double theta_m, double theta_l) {
  const double delta = theta_m - theta_l;
  const double half = 0.5 * p.backlash;
  if (delta > half) return delta - half;
  if (delta < -half) return delta + half;
  return 0.0;
}

double gear_torque(const ActuatorParams& p, const ActuatorState& s, double theta_l, double omega_l) {
  return p.k * gear_deflection(p, s.theta_m, theta_l) + p.d * (s.omega_m - omega_l);
}

void step_motor(const ActuatorParams& p, ActuatorState& s, double command, double theta_l, double omega_l, double dt) {
  const double w = 2.0 * std::numbers::pi * p.bandwidth;
  const double kp = p.rotor_inertia * w * w, kd = 2.0 * p.rotor_inertia * w,
               ki = p.integral_time > 0 ? kp / p.integral_time : 0.0;
  const double e = command - s.theta_m;
  double servo = kp * e + ki * s.integral - kd * s.omega_m;
  const double limited = std::clamp(servo, -p.torque_limit, p.torque_limit);
  if (limited == servo) s.integral += e * dt;  // no wind-up while saturated
  servo = limited;
  s.servo = servo;
  const double tau = gear_torque(p, s, theta_l, omega_l);
  s.omega_m += dt * (servo - tau) / p.rotor_inertia;
  s.theta_m += dt * s.omega_m;
}

double encoder_reading(const ActuatorParams& p, double theta_m) {
  const double q = 2.0 * std::numbers::pi / p.encoder_steps;
  return q * std::nearbyint(theta_m / q);
}

}  // namespace flexgait::twin
