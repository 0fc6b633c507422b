#include "flexgait/twin/detail/elastic_drives.hpp"

#include <stdexcept>

namespace flexgait::twin {

ElasticDrives::ElasticDrives(const mjModel* m, std::vector<int> joints, std::vector<ActuatorParams> params)
    : joints_(std::move(joints)), params_(std::move(params)) {
  if (joints_.size() != params_.size()) throw std::invalid_argument("ElasticDrives: one parameter set per joint");
  for (int j : joints_) {
    if (j == kAbsentJoint) {
      qpos_.push_back(-1);
      dof_.push_back(-1);
      continue;
    }
    if (j < 0 || j >= m->njnt || m->jnt_type[j] != mjJNT_HINGE)
      throw std::invalid_argument("ElasticDrives: not a hinge joint");
    qpos_.push_back(m->jnt_qposadr[j]);
    dof_.push_back(m->jnt_dofadr[j]);
  }
}

void ElasticDrives::take_springs(mjModel* m) const {
  for (int j : joints_)
    if (j != kAbsentJoint) m->jnt_stiffness[j] = 0.0;
}

std::vector<ActuatorState> ElasticDrives::at_rest(const mjData* d) const {
  std::vector<ActuatorState> states(joints_.size());
  for (std::size_t i = 0; i < states.size(); ++i)
    if (qpos_[i] >= 0) states[i] = {d->qpos[qpos_[i]], d->qvel[dof_[i]], 0.0, 0.0};
  return states;
}

void ElasticDrives::step(const mjModel* m, mjData* d, std::vector<ActuatorState>& states,
                         const double* commands) const {
  const double dt = m->opt.timestep;
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (qpos_[i] < 0) continue;  // absent: its motor stays at rest
    const double theta_l = d->qpos[qpos_[i]], omega_l = d->qvel[dof_[i]];
    ActuatorState& s = states[i];
    const ActuatorParams& p = params_[i];
    step_motor(p, s, commands[i], theta_l, omega_l, dt);
    // τ = k dz(θ_m − θ_l) + d θ̇_m here; the joint damping adds −d θ̇_l implicitly.
    d->qfrc_applied[dof_[i]] = p.k * gear_deflection(p, s.theta_m, theta_l) + p.d * s.omega_m;
  }
  mj_step(m, d);
}

}  // namespace flexgait::twin
