#include "flexgait/rimless/rigid_wheel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "flexgait/numerics/hybrid_simulation.hpp"
#include "flexgait/numerics/ode_integrator.hpp"
#include "flexgait/rimless/gait.hpp"

namespace flexgait::rimless {
namespace {

// The wheel's guard/reset pairs (docs/theory/rimless.md, "The rigid wheel, the analytic limit"; McGeer 1990), on the
// pendulum state
// (β, β̇) of the stance leg:
//   touchdown  g = β - α ↑ 0, reset impact_reset();
//   roll-back  g = β + α ↓ 0, the wheel fell back onto the previous foot: a failure, no reset;
//   upright    g = β ↑ 0, the stance leg passes the slope normal: the upright section, no reset.
double touchdown_guard(const WheelParams& w, double beta) {
  return beta - w.alpha();
}
double rollback_guard(const WheelParams& w, double beta) {
  return beta + w.alpha();
}
double upright_guard(double beta) {
  return beta;
}
enum Guard : std::size_t { kTouchdown = 0, kRollback = 1, kUpright = 2 };
constexpr std::array<int, 3> kGuardDirections{+1, -1, +1};

// The impact at touchdown: the new stance leg is the one 2α behind, β⁺ = β⁻ - 2α, and the
// angular momentum about the new foot is kept, (m L0² cos 2α + I) ω⁻ = (m L0² + I) ω⁺.
// Postcondition: the new leg starts at β⁺ = -α (to 1e-8 rad: the crossing is located to
// ~1e-13 s) and the momentum balance holds to round-off (1e-12 relative).
std::array<double, 2> impact_reset(const WheelParams& w, double J, const std::array<double, 2>& minus) {
  const double alpha = w.alpha();
  const double ml2_cos = w.m * w.L0 * w.L0 * std::cos(2 * alpha);
  const double omega_plus = minus[1] * (ml2_cos + w.I) / J;
  const std::array<double, 2> plus{minus[0] - 2.0 * alpha, omega_plus};
  const double before = (ml2_cos + w.I) * minus[1], after = J * plus[1];
  if (!(std::abs(plus[0] + alpha) <= 1e-8) || !(std::abs(after - before) <= 1e-12 * std::abs(before)))
    throw std::logic_error(
        fmt::format("rigid impact reset: beta+ = {} (want {}), momentum {} -> {}", plus[0], -alpha, before, after));
  return plus;
}

// Pendulum about the foot: (m L0² + I) β̈ = m g L0 sin(β + φ); guards above.
class Pendulum final : public numerics::OdeSystem {
 public:
  explicit Pendulum(const WheelParams& w) : w_(w), J_(w.m * w.L0 * w.L0 + w.I) {}
  bool rhs(double, std::span<const double> y, std::span<double> yd) override {
    yd[0] = y[1];
    yd[1] = w_.m * w_.g * w_.L0 * std::sin(y[0] + w_.slope) / J_;
    return true;
  }
  void guards(double, std::span<const double> y, std::span<double> g) override {
    g[kTouchdown] = touchdown_guard(w_, y[0]);
    g[kRollback] = rollback_guard(w_, y[0]);
    g[kUpright] = upright_guard(y[0]);
  }
  double J() const { return J_; }

 private:
  const WheelParams& w_;
  double J_;
};

void simulate_rigid_into(const WheelParams& w, const InitialState& init, const SimulationOptions& opt,
                         std::optional<Section> stop_at, RunSink& sink, SimulationResult& res);

}  // namespace

double RigidStepMap::next(double omega_plus) const {
  return r * std::sqrt(omega_plus * omega_plus + a);
}
double RigidStepMap::fixed_point() const {
  return r * std::sqrt(a / (1.0 - r * r));
}
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
  SimulationResult res;
  RunCollector keep(res);
  simulate_rigid_into(w, init, opt, stop_at, keep, res);
  return res;
}

SimulationResult simulate_rigid(const WheelParams& w, const InitialState& init, const SimulationOptions& opt,
                                RunSink& sink, std::optional<Section> stop_at) {
  SimulationResult res;
  simulate_rigid_into(w, init, opt, stop_at, sink, res);
  return res;
}

namespace {

// One run of the rigid wheel as a model of the hybrid loop (numerics/hybrid_simulation.hpp).
class RigidRun final : public numerics::HybridModel {
 public:
  RigidRun(const WheelParams& w, const InitialState& init, const SimulationOptions& opt, std::optional<Section> stop_at,
           RunSink& sink, SimulationResult& res, double J)
      : w_(w), opt_(opt), stop_at_(stop_at), sink_(sink), res_(res), J_(J), y_{init.beta, init.omega} {
    contacts_.count = 1;
    contacts_.leg[0] = 0;
  }

  // The log's sample of pendulum state s at t: the hub, the ground reaction, the energy.
  LogSample sample_at(double t, const std::array<double, 2>& s) const {
    const double alpha = w_.alpha();
    const double sphi = std::sin(w_.slope), cphi = std::cos(w_.slope);
    const double b = s[0], bd = s[1], bdd = w_.m * w_.g * w_.L0 * std::sin(b + w_.slope) / J_;
    LogSample out;
    out.t = t;
    const double x = foot_ + w_.L0 * std::sin(b), yy = w_.L0 * std::cos(b);
    const double xd = w_.L0 * bd * std::cos(b), yd = -w_.L0 * bd * std::sin(b);
    out.q = {x, yy, b - 2 * alpha * stance_, xd, yd, bd};
    // Ground reaction from the hub's acceleration: R = m a - m g (sin φ, -cos φ).
    const double ax = w_.L0 * (bdd * std::cos(b) - bd * bd * std::sin(b));
    const double ay = w_.L0 * (-bdd * std::sin(b) - bd * bd * std::cos(b));
    out.contact[0] = {
        stance_leg(), FootMode::Stick, w_.m * ay + w_.m * w_.g * cphi, w_.m * ax - w_.m * w_.g * sphi, foot_, 0.0};
    out.energy.kinetic = 0.5 * J_ * bd * bd;
    out.energy.gravity = w_.m * w_.g * (yy * cphi - x * sphi);
    out.w_damp = w_impact_;
    return out;
  }
  int stance_leg() const { return ((stance_ % w_.legs) + w_.legs) % w_.legs; }
  void record_event(double te, RunEvent kind, int leg) {
    ++res_.event_count;
    contacts_.leg[0] = stance_leg();
    sink_.on_event({te, kind, leg, contacts_, kind == RunEvent::Failure ? res_.failure->text() : std::string()});
  }
  void log_sample(const LogSample& s) {
    sink_.on_sample(s);
    last_logged_t_ = s.t;
  }

  // The start at t = 0; returns the first sample.
  LogSample start() {
    const LogSample first = sample_at(0.0, y_);
    res_.energy_initial = first.energy.total();
    sink_.on_start(res_.energy_initial);
    if (opt_.log) log_sample(first);
    record_event(0.0, RunEvent::Start, 0);
    tracker_.start(0.0, first.q[0], res_.energy_initial, contacts_, w_.legs);
    return first;
  }
  void finish(double t, const LogSample& first) {
    if (res_.failure) record_event(t, RunEvent::Failure, -1);
    const LogSample last = sample_at(t, y_);
    if (opt_.log && last_logged_t_ < t) log_sample(last);
    res_.t_final = t;
    res_.final_state = {last.q[0], last.q[1], last.q[2], last.q[3], last.q[4], last.q[5]};
    res_.final_contacts = contacts_;
    tracker_.finish(t, last.q[0]);
    res_.gaits = tracker_.gaits();
    res_.last_step = tracker_.steps().back();
    const StepRecord* last_complete = tracker_.last_complete();
    for (const StepRecord& st : tracker_.steps()) sink_.on_step(st);
    res_.energy_final = last.energy.total();
    res_.work_damping = w_impact_;
    const double scale = first.energy.kinetic + w_.m * w_.g * w_.L0 + w_impact_;
    res_.energy_balance_error = std::abs(res_.energy_final + w_impact_ - res_.energy_initial) / scale;
    const double t_end = res_.steps_completed > 0 ? last_touchdown_ : t;
    const double x_end = last_complete != nullptr ? last_complete->x_end : last.q[0];
    res_.mean_speed = t_end > 0 ? (x_end - first.q[0]) / t_end : 0.0;
  }
  std::span<const double> state() const { return y_; }

  bool finished() const override { return done_ || res_.steps_completed >= opt_.steps; }
  double stop_time() const override { return std::min(opt_.max_time, last_touchdown_ + opt_.max_step_time); }
  void sample(double t, std::span<const double> y) override { log_sample(sample_at(t, {y[0], y[1]})); }
  void stepped(double, std::span<const double> y) override { y_ = {y[0], y[1]}; }
  bool smooth_step(double t, std::span<const double>, numerics::StepStatus status) override {
    if (status != numerics::StepStatus::StopTime) return true;
    fail(t >= opt_.max_time                       ? FailureReason::TimeLimit
         : balanced_at_vertical(w_, y_[0], y_[1]) ? FailureReason::BalancedAtVertical
                                                  : FailureReason::NoLanding);
    return false;
  }
  numerics::HybridNext guards_crossed(double t, std::span<const double>, std::span<const int> fired,
                                      const numerics::OdeIntegrator&,
                                      std::vector<numerics::HybridEvent>& events) override {
    if (opt_.log) log_sample(sample_at(t, y_));
    if (fired[kRollback] != 0) {
      fail(FailureReason::FellBack);
      return numerics::HybridNext::Stop;
    }
    if (fired[kTouchdown] == 0) {  // only the upright guard crossed
      if (stop_at_ == Section::Upright && res_.steps_completed > 0) {
        record_event(t, RunEvent::Section, contacts_.leg[0]);
        done_ = true;
        return numerics::HybridNext::Stop;
      }
      return numerics::HybridNext::Continue;
    }
    events.push_back({((stance_ - 1) % w_.legs + w_.legs) % w_.legs, static_cast<int>(RunEvent::Touchdown)});
    return numerics::HybridNext::Restart;
  }
  numerics::HybridNext reset(double t, std::span<double> y, std::span<const numerics::HybridEvent>) override {
    const double omega_minus = y_[1];
    y_ = impact_reset(w_, J_, y_);
    w_impact_ += 0.5 * J_ * (omega_minus * omega_minus - y_[1] * y_[1]);
    foot_ += 2.0 * w_.L0 * std::sin(w_.alpha());  // the new foot is 2 L0 sin α further down
    stance_ -= 1;                                 // β_{k-1} = β_k - 2α
    ++res_.steps_completed;
    last_touchdown_ = t;
    const LogSample after = sample_at(t, y_);
    if (opt_.log) log_sample(after);
    record_event(t, RunEvent::Touchdown, stance_leg());
    tracker_.touchdown(t, after.q[0], after.energy.total(), contacts_.leg[0], contacts_);
    for (const StepRecord& st : tracker_.final_steps()) sink_.on_step(st);
    tracker_.drop_final_steps();
    if (stop_at_ == Section::Touchdown) {
      record_event(t, RunEvent::Section, contacts_.leg[0]);
      done_ = true;
      return numerics::HybridNext::Stop;
    }
    y[0] = y_[0];
    y[1] = y_[1];
    return numerics::HybridNext::Restart;
  }
  std::span<const int> directions() const override { return kGuardDirections; }
  void fail(FailureReason reason, std::string detail = {}) { res_.failure = Failure{reason, std::move(detail), {}}; }
  void loop_failed(numerics::LoopFailure what, double, const std::string& detail) override {
    fail(loop_failure_reason(what), detail);
  }
  void work_limit_reached(numerics::WorkLimit limit, double t, double measured) override {
    if (limit == numerics::WorkLimit::WallTime)
      fail(FailureReason::WallTime, fmt::format("{} s at t = {} s", measured, t));
    else
      fail(FailureReason::StepRate, fmt::format("{:.3g} solver steps per simulated second at t = {} s", measured, t));
  }
  std::string describe(const numerics::HybridEvent& e) const override {
    return fmt::format("leg {} touchdown", e.unit);
  }

 private:
  const WheelParams& w_;
  const SimulationOptions& opt_;
  std::optional<Section> stop_at_;
  RunSink& sink_;
  SimulationResult& res_;
  double J_;                   // m L0² + I [kg m²]
  std::array<double, 2> y_;    // (β, β̇) of the stance leg
  ContactSet contacts_;        // the stance foot (leg[0] set when an event is recorded)
  double foot_ = 0.0;          // x of the stance foot [m]
  int stance_ = 0;             // stance leg index (decreasing; stance_leg() wraps it)
  double w_impact_ = 0;        // impact losses [J]
  double last_touchdown_ = 0;  // [s]
  double last_logged_t_ = 0;   // [s]
  bool done_ = false;          // the stop section was reached
  StepTracker tracker_;
};

void simulate_rigid_into(const WheelParams& w, const InitialState& init, const SimulationOptions& opt,
                         std::optional<Section> stop_at, RunSink& sink, SimulationResult& res) {
  Pendulum pendulum(w);
  numerics::OdeOptions ode;
  ode.rtol = opt.rtol;
  ode.atol = opt.atol;
  ode.method = opt.method;
  numerics::OdeIntegrator integ(pendulum, 2, ode);
  RigidRun run(w, init, opt, stop_at, sink, res, pendulum.J());
  const LogSample first = run.start();
  integ.restart(0.0, run.state(), kGuardDirections);
  numerics::HybridSimulation loop(integ, 2);
  numerics::HybridLimits limits;
  limits.sample = opt.log;
  limits.sample_dt = opt.sample_dt;
  limits.max_wall_time = opt.max_wall_time;
  limits.max_step_rate = opt.max_step_rate;
  limits.poll = opt.poll;
  run.finish(loop.run(run, limits, 0.0), first);
  const auto st = integ.stats();
  res.solver_steps = st.steps;
  res.rhs_evals = st.rhs_evals;
}

}  // namespace

}  // namespace flexgait::rimless
