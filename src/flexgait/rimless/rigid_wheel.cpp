#include "flexgait/rimless/rigid_wheel.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include "flexgait/numerics/ode_integrator.hpp"

namespace flexgait::rimless {
namespace {

// Pendulum about the foot: state (β, β̇); guards: β - α (next touchdown, upward),
// β + α (rolled back over the previous foot, downward), β (upright, upward).
class Pendulum final : public numerics::OdeSystem {
 public:
  explicit Pendulum(const WheelParams& w) : w_(w), J_(w.m * w.L0 * w.L0 + w.I) {}
  bool rhs(double, std::span<const double> y, std::span<double> yd) override {
    yd[0] = y[1];
    yd[1] = w_.m * w_.g * w_.L0 * std::sin(y[0] + w_.slope) / J_;
    return true;
  }
  void guards(double, std::span<const double> y, std::span<double> g) override {
    g[0] = y[0] - w_.alpha();
    g[1] = y[0] + w_.alpha();
    g[2] = y[0];
  }
  double J() const { return J_; }

 private:
  const WheelParams& w_;
  double J_;
};

}  // namespace

double RigidStepMap::next(double omega_plus) const { return r * std::sqrt(omega_plus * omega_plus + a); }
double RigidStepMap::fixed_point() const { return r * std::sqrt(a / (1.0 - r * r)); }
double RigidStepMap::derivative(double omega_plus) const {
  return r * omega_plus / std::sqrt(omega_plus * omega_plus + a);
}

RigidStepMap rigid_step_map(const WheelParams& w) {
  const double ml2 = w.m * w.L0 * w.L0;
  const double alpha = w.alpha();
  return {(ml2 * std::cos(2 * alpha) + w.I) / (ml2 + w.I),
          4.0 * w.m * w.g * w.L0 * std::sin(alpha) * std::sin(w.slope) / (ml2 + w.I)};
}

SimulationResult simulate_rigid(const WheelParams& w, const InitialState& init, const SimulationOptions& opt,
                                std::optional<Section> stop_at) {
  Pendulum pendulum(w);
  const double J = pendulum.J();
  numerics::OdeOptions ode;
  ode.rtol = opt.rtol;
  ode.atol = opt.atol;
  ode.method = opt.method;
  numerics::OdeIntegrator integ(pendulum, 2, ode);
  const double alpha = w.alpha();
  const double sphi = std::sin(w.slope), cphi = std::cos(w.slope);
  std::array<double, 2> y{init.beta, init.omega};
  double foot = 0.0;   // x of the stance foot [m]
  int stance = 0;      // stance leg index
  double w_impact = 0; // impact losses [J]

  auto sample_at = [&](double t, const std::array<double, 2>& s) {
    const double b = s[0], bd = s[1], bdd = w.m * w.g * w.L0 * std::sin(b + w.slope) / J;
    LogSample out;
    out.t = t;
    const double x = foot + w.L0 * std::sin(b), yy = w.L0 * std::cos(b);
    const double xd = w.L0 * bd * std::cos(b), yd = -w.L0 * bd * std::sin(b);
    out.q = {x, yy, b - 2 * alpha * stance, xd, yd, bd};
    // Ground reaction from the hub's acceleration: R = m a - m g (sin φ, -cos φ).
    const double ax = w.L0 * (bdd * std::cos(b) - bd * bd * std::sin(b));
    const double ay = w.L0 * (-bdd * std::sin(b) - bd * bd * std::cos(b));
    out.contact[0] = {((stance % w.legs) + w.legs) % w.legs, FootMode::Stick, w.m * ay + w.m * w.g * cphi,
                      w.m * ax - w.m * w.g * sphi, foot, 0.0};
    out.energy.kinetic = 0.5 * J * bd * bd;
    out.energy.gravity = w.m * w.g * (yy * cphi - x * sphi);
    out.w_damp = w_impact;
    return out;
  };

  SimulationResult res;
  ContactSet contacts;
  contacts.count = 1;
  contacts.leg[0] = 0;
  auto modes = [&]() {
    contacts.leg[0] = ((stance % w.legs) + w.legs) % w.legs;
    return describe_contacts(contacts);
  };
  const LogSample first = sample_at(0.0, y);
  res.energy_initial = first.energy.total();
  if (opt.log) res.samples.push_back(first);
  res.events.push_back({0.0, "start", 0, modes()});
  StepTracker tracker;
  tracker.start(0.0, first.q[0], res.energy_initial, contacts, w.legs);

  const std::array<int, 3> dirs{+1, -1, +1};
  integ.restart(0.0, y, dirs);
  double t = 0.0, next_sample = opt.sample_dt, last_touchdown = 0.0;
  long sample_index = 1;
  std::array<double, 2> dense{};
  while (res.steps_completed < opt.steps) {
    const double t_stop = std::min(opt.max_time, last_touchdown + opt.max_step_time);
    const auto status = integ.step(t_stop);
    t = integ.time();
    if (opt.log) {
      while (next_sample < t) {
        integ.interpolate(next_sample, dense);
        res.samples.push_back(sample_at(next_sample, dense));
        next_sample = opt.sample_dt * static_cast<double>(++sample_index);
      }
    }
    y = {integ.state()[0], integ.state()[1]};
    if (status == numerics::StepStatus::StopTime) {
      res.failure = t >= opt.max_time ? "time limit sim.max_time reached"
                                      : "stopped: no new leg landed within sim.max_step_time";
      break;
    }
    if (status != numerics::StepStatus::Guard) continue;
    if (opt.log) res.samples.push_back(sample_at(t, y));
    if (integ.guards_fired()[1] != 0) {
      res.failure = "rolled back: the wheel fell back onto the previous leg";
      break;
    }
    if (integ.guards_fired()[0] == 0) {  // only the upright guard crossed
      if (stop_at == Section::Upright && res.steps_completed > 0) {
        res.events.push_back({t, "section", contacts.leg[0], modes()});
        break;
      }
      continue;
    }
    // Impact: the new foot is 2 L0 sin α further down; angular momentum about it is kept.
    const double omega_minus = y[1];
    const double omega_plus = omega_minus * (w.m * w.L0 * w.L0 * std::cos(2 * alpha) + w.I) / J;
    w_impact += 0.5 * J * (omega_minus * omega_minus - omega_plus * omega_plus);
    foot += 2.0 * w.L0 * std::sin(alpha);
    stance -= 1;  // β_{k-1} = β_k - 2α
    y = {y[0] - 2.0 * alpha, omega_plus};
    ++res.steps_completed;
    last_touchdown = t;
    const LogSample after = sample_at(t, y);
    if (opt.log) res.samples.push_back(after);
    res.events.push_back({t, "touchdown", contacts.leg[0] = ((stance % w.legs) + w.legs) % w.legs, modes()});
    tracker.touchdown(t, after.q[0], after.energy.total(), contacts.leg[0], contacts);
    if (stop_at == Section::Touchdown) {
      res.events.push_back({t, "section", contacts.leg[0], modes()});
      break;
    }
    integ.restart(t, y, dirs);
  }
  if (res.failure) res.events.push_back({t, "failure", -1, *res.failure});
  const LogSample last = sample_at(t, y);
  if (opt.log && (res.samples.empty() || res.samples.back().t < t)) res.samples.push_back(last);
  res.t_final = t;
  res.final_state = {last.q[0], last.q[1], last.q[2], last.q[3], last.q[4], last.q[5]};
  res.final_contacts = contacts;
  res.steps = tracker.steps();
  res.energy_final = last.energy.total();
  res.work_damping = w_impact;
  const double scale = first.energy.kinetic + w.m * w.g * w.L0 + w_impact;
  res.energy_balance_error = std::abs(res.energy_final + w_impact - res.energy_initial) / scale;
  const double t_end = res.steps_completed > 0 ? last_touchdown : t;
  double x_end = last.q[0];
  for (const auto& st : res.steps)
    if (st.complete) x_end = st.x_end;
  res.mean_speed = t_end > 0 ? (x_end - first.q[0]) / t_end : 0.0;
  const auto st = integ.stats();
  res.solver_steps = st.steps;
  res.rhs_evals = st.rhs_evals;
  return res;
}

}  // namespace flexgait::rimless
