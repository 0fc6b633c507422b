#include "flexgait/humanoid/elastic_actuator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace flexgait::humanoid {

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
  const double kp = p.rotor_inertia * w * w, kd = 2.0 * p.rotor_inertia * w, ki = p.integral_time > 0 ? kp / p.integral_time : 0.0;
  const double e = command - s.theta_m;
  double servo = kp * e + ki * s.integral - kd * s.omega_m;
  const double limited = std::clamp(servo, -p.torque_limit, p.torque_limit);
  if (limited == servo) s.integral += e * dt;  // no wind-up while saturated
  servo = limited;
  const double tau = gear_torque(p, s, theta_l, omega_l);
  s.omega_m += dt * (servo - tau) / p.rotor_inertia;
  s.theta_m += dt * s.omega_m;
}

double encoder_reading(const ActuatorParams& p, double theta_m) {
  const double q = 2.0 * std::numbers::pi / p.encoder_steps;
  return q * std::nearbyint(theta_m / q);
}

ElasticDrives::ElasticDrives(const mjModel* m, std::vector<int> joints, std::vector<ActuatorParams> params)
    : params_(std::move(params)), states_(joints.size()) {
  if (joints.size() != params_.size()) throw std::invalid_argument("ElasticDrives: one parameter set per joint");
  for (int j : joints) {
    if (j < 0 || j >= m->njnt || m->jnt_type[j] != mjJNT_HINGE)
      throw std::invalid_argument("ElasticDrives: not a hinge joint");
    qpos_.push_back(m->jnt_qposadr[j]);
    dof_.push_back(m->jnt_dofadr[j]);
  }
}

void ElasticDrives::reset_to_links(const mjData* d) {
  for (std::size_t i = 0; i < states_.size(); ++i) states_[i] = {d->qpos[qpos_[i]], d->qvel[dof_[i]], 0.0};
}

void ElasticDrives::step(mjModel* m, mjData* d, const double* commands) {
  const double dt = m->opt.timestep;
  for (std::size_t i = 0; i < states_.size(); ++i) {
    const double theta_l = d->qpos[qpos_[i]], omega_l = d->qvel[dof_[i]];
    ActuatorState& s = states_[i];
    step_motor(params_[i], s, commands[i], theta_l, omega_l, dt);
    // MuJoCo's joint spring: k (qpos_spring − θ_l) = k dz(θ_m − θ_l).
    m->qpos_spring[qpos_[i]] = theta_l + gear_deflection(params_[i], s.theta_m, theta_l);
    d->qfrc_applied[dof_[i]] = params_[i].d * s.omega_m;  // the joint damping adds −d θ̇_l implicitly
  }
  mj_step(m, d);
}

}  // namespace flexgait::humanoid
