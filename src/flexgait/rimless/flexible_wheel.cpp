#include "flexgait/rimless/flexible_wheel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "flexgait/core/config.hpp"
#include "flexgait/numerics/guard_crossings.hpp"
#include "flexgait/numerics/hybrid_simulation.hpp"
#include "flexgait/numerics/ode_integrator.hpp"
#include "flexgait/rimless/dynamics.hpp"
#include "flexgait/rimless/flow.hpp"
#include "flexgait/rimless/mode_selection.hpp"
#include "flexgait/rimless/variational.hpp"

namespace flexgait::rimless {
namespace {

// The smooth flow and the guards of the current contact mode, for the integrator.
// With the upright section active, one more guard follows the wheel's: sin β of the next leg to
// pass upright, crossing 0 upward.
//
// A foot that has just left the ground starts on its touchdown guard (h = 0: at lift-off the
// free leg keeps the contact leg's compression) and rises only as h ≈ ½ ḧ τ² — so slowly at first
// that the integration error of h (~ rtol·L0) can dip it below 0 and "land" the foot again a few
// 1e-11 s later with a tensile leg force. Until the foot has cleared the ground by `clearance`,
// its touchdown guard is h + clearance: a foot that truly comes back down without rising still
// lands (at h = -clearance, far inside the missed-event check's 1e-7 L0), one that rises is armed
// with the true guard h once h >= clearance.
class WheelFlow final : public numerics::OdeSystem {
 public:
  WheelFlow(const WheelParams& w, const ContactSet& contacts, double clearance)
      : w_(w),
        offsets_(leg_offsets(w)),
        contacts_(contacts),
        clearance_(clearance),
        clearing_(static_cast<std::size_t>(w.legs), 0) {}
  // The flow; its dynamics and the configuration and velocities they were computed from are kept
  // until the next evaluation: the guards at a step's end are evaluated at the point of the step's
  // last evaluation (DOP853's first-same-as-last stage) and take its dynamics instead of computing
  // them again.
  bool rhs(double, std::span<const double> y, std::span<double> yd) override {
    const bool ok = flow_derivative(w_, contacts_, y, yd, dynamics_[1 - last_]);
    std::copy_n(y.begin(), kDynamicsInputs, rhs_q_.begin());
    rhs_valid_ = true;
    return ok;
  }
  // Sensitivities: a sticking foot's anchor moves with the perturbed solution (it is where that
  // solution's foot stopped), so the Baumgarte position term vanishes on every nearby solution.
  bool linearization_rhs(double, std::span<const double> y, std::span<double> yd) override {
    return flow_derivative(w_, linearization_contacts(y), y, yd, linearization_dynamics_);
  }
  // ∂f/∂p of the parameter column (ParameterDirection): a central difference of the flow in p at y.
  bool parameter_derivative(double, std::span<const double> y, int, std::span<double> dfdp) override {
    if (parameter_ == nullptr) {
      std::fill(dfdp.begin(), dfdp.end(), 0.0);
      return true;
    }
    const ContactSet c = linearization_contacts(y);
    plus_.resize(y.size());
    if (!flow_derivative(parameter_->plus, c, y, plus_) || !flow_derivative(parameter_->minus, c, y, dfdp))
      return false;
    for (std::size_t i = 0; i < y.size(); ++i) dfdp[i] = (plus_[i] - dfdp[i]) / (2.0 * parameter_->step);
    return true;
  }
  void set_parameter(const ParameterDirection* p) { parameter_ = p; }
  void guards(double, std::span<const double> y, std::span<double> g) override {
    const std::size_t n = static_cast<std::size_t>(guard_count(w_));
    last_y_.assign(y.begin(), y.end());
    if (rhs_valid_ && std::memcmp(rhs_q_.data(), y.data(), sizeof(rhs_q_)) == 0) {
      last_ = 1 - last_;  // the right-hand side's: the numbers contact_dynamics() gives at y
      if (!dynamics_[last_].failure) normal_forces(contacts_, dynamics_[last_]);  // the flow leaves N out
      rhs_valid_ = false;
    } else {
      contact_dynamics(w_, contacts_, y, dynamics_[last_]);
    }
    guard_values(w_, offsets_, contacts_, dynamics_[last_], y, g.first(n));
    for (int k = 0; k < w_.legs; ++k) {
      const std::size_t i = static_cast<std::size_t>(kGuardsPerLeg * k);
      last_heights_[static_cast<std::size_t>(k)] = g[i];  // the free feet's heights (contacts: N)
      if (clearing_[static_cast<std::size_t>(k)] != 0) g[i] += clearance_;
    }
    if (upright_leg_ >= 0) g[n] = std::sin(y[StateIndex::theta] + 2.0 * w_.alpha() * upright_leg_);
  }
  // One guard, as guards() computes it: a free foot's touchdown guard and the upright guard
  // alone (a sine and a cosine of θ, against the mode's dynamics and every foot for all of them).
  double guard(double t, std::span<const double> y, int i, std::span<double> scratch) override {
    const int n = guard_count(w_);
    if (i == n && upright_leg_ >= 0) return std::sin(y[StateIndex::theta] + 2.0 * w_.alpha() * upright_leg_);
    const int k = i / kGuardsPerLeg;
    if (i >= n || i % kGuardsPerLeg != 0 || contacts_.find(k) >= 0) {
      guards(t, y, scratch);
      return scratch[static_cast<std::size_t>(i)];
    }
    const double theta = y[StateIndex::theta];
    const double h = free_foot_height(w_, offsets_, k, std::cos(theta), std::sin(theta), y);
    return clearing_[static_cast<std::size_t>(k)] != 0 ? h + clearance_ : h;
  }
  /// Whether the latest guard evaluation was at this very y in the current mode (the end of a
  /// step): then last_dynamics() is the number contact_dynamics() would compute again there and
  /// last_height() the touchdown guard's height (free_foot_height, within 2 ulp of foot_height()),
  /// the missed-event check's.
  bool remembered(std::span<const double> y) const {
    return last_y_.size() == y.size() && std::equal(y.begin(), y.end(), last_y_.begin());
  }
  const Dynamics& last_dynamics() const { return dynamics_[last_]; }
  double last_height(int k) const { return last_heights_[static_cast<std::size_t>(k)]; }
  void set_contacts(const ContactSet& c) {
    contacts_ = c;
    last_y_.clear();  // the remembered evaluations were of another mode
    rhs_valid_ = false;
  }
  const ContactSet& contacts() const { return contacts_; }
  void set_upright_leg(int k) { upright_leg_ = k; }
  int upright_leg() const { return upright_leg_; }
  /// The feet of `before` (and the landing ones of `events`) that are not in contacts(): they
  /// left the ground now and have yet to clear it.
  void start_clearing(const ContactSet& before, std::span<const GuardEvent> events) {
    for (int i = 0; i < before.count; ++i)
      if (contacts_.find(before.leg[i]) < 0) clearing_[static_cast<std::size_t>(before.leg[i])] = 1;
    for (const auto& e : events)
      if (e.kind == EventKind::Touchdown && contacts_.find(e.leg) < 0) clearing_[static_cast<std::size_t>(e.leg)] = 1;
  }
  /// Arms the true touchdown guard of every clearing foot that is now `clearance` above the
  /// ground (call between integrator steps only: the guard changes sign nowhere by this).
  void arm_cleared(std::span<const double> y) {
    for (int k = 0; k < w_.legs; ++k) {
      char& c = clearing_[static_cast<std::size_t>(k)];
      if (c != 0 && (contacts_.find(k) >= 0 || foot_height(w_, k, y) >= clearance_)) c = 0;
    }
  }
  void clear_all() { std::fill(clearing_.begin(), clearing_.end(), 0); }
  /// Whether foot k's touchdown guard is still h + clearance (it has not cleared the ground).
  bool clearing(int k) const { return clearing_[static_cast<std::size_t>(k)] != 0; }
  double clearance() const { return clearance_; }

 private:
  // The mode with each sticking foot's anchor where the foot is at y (it moves with a perturbed
  // solution: the Baumgarte position term vanishes on every nearby solution). The foot's position
  // is kinematics alone, the same for every value of a parameter.
  ContactSet linearization_contacts(std::span<const double> y) const {
    ContactSet c = contacts_;
    for (int i = 0; i < c.count; ++i)
      if (c.mode[i] == FootMode::Stick) c.anchor[i] = leg_kinematics(w_, c.leg[i], y).c;
    return c;
  }

  const WheelParams& w_;
  LegOffsets offsets_;  // the free feet's heights by angle addition (flow.hpp)
  ContactSet contacts_;
  double clearance_;            // [m]
  std::vector<char> clearing_;  // per leg: 1 while a foot that left has not cleared the ground
  int upright_leg_ = -1;
  const ParameterDirection* parameter_ = nullptr;  // the sensitivities' parameter column, if any
  std::vector<double> plus_;                       // scratch: the flow at p + h
  // The latest guard evaluation: its state (empty: none of this mode), dynamics, and per leg
  // guard slot 0 before the clearance (a free foot's height).
  std::vector<double> last_y_;
  std::vector<double> last_heights_ = std::vector<double>(static_cast<std::size_t>(w_.legs));
  // The latest right-hand side's configuration and velocities (rhs_valid_: one of this mode) and
  // dynamics; the two Dynamics swap roles when the guards take the right-hand side's.
  // contact_dynamics() reads (x, y, θ, ẋ, ẏ, θ̇) alone: equal bits there, equal dynamics.
  static constexpr std::size_t kDynamicsInputs = StateIndex::thetad + 1;
  std::array<double, kDynamicsInputs> rhs_q_{};
  bool rhs_valid_ = false;
  std::array<Dynamics, 2> dynamics_;
  int last_ = 0;  // dynamics_[last_]: the latest guard evaluation's; the other: the right-hand side's
  Dynamics linearization_dynamics_;  // scratch of linearization_rhs()
};

}  // namespace

RunSpec default_run(const WheelParams& w, const InitialState& initial) {
  RunSpec spec;
  spec.y0 = initial_state(w, initial);
  spec.pending = {{0, EventKind::Touchdown}};  // the stance foot's mode is chosen at t = 0
  return spec;
}

std::vector<double> initial_state(const WheelParams& w, const InitialState& init) {
  using S = StateIndex;
  std::vector<double> y(static_cast<std::size_t>(state_size(w)), 0.0);
  const double delta = w.m * w.g * std::cos(w.slope) / w.K;
  const double L = w.L0 - delta;
  y[S::theta] = init.beta;
  y[S::y] = L * std::cos(init.beta);
  y[S::x] = y[S::y] * std::tan(init.beta);
  y[S::xd] = L * init.omega * std::cos(init.beta);
  y[S::yd] = -L * init.omega * std::sin(init.beta);
  y[S::thetad] = init.omega;
  return y;
}

void check_initial_state(const WheelParams& w, const InitialState& init) {
  const double delta = w.m * w.g * std::cos(w.slope) / w.K;  // as initial_state()
  if (!(delta < w.L0))
    throw ConfigError("rimless.K",
                      fmt::format("rimless.K = {} with rimless.m = {}, rimless.g = {}, rimless.slope = {}: "
                                  "the stance leg's static compression m g cos(slope) / K = {:.6g} m is not "
                                  "below rimless.L0 = {} m (a stiffer leg or a lighter wheel is needed)",
                                  w.K, w.m, w.g, w.slope, delta, w.L0));
  const std::vector<double> y = initial_state(w, init);
  for (int k = 1; k < w.legs; ++k) {
    const double h = foot_height(w, k, y);
    if (h >= -1e-12 * w.L0) continue;  // the run's own test at t = 0
    throw ConfigError(
        "rimless.legs",
        fmt::format("rimless.legs = {} with initial.beta = {}, rimless.K = {}, rimless.m = {}, rimless.g = {}, "
                    "rimless.L0 = {}: foot {} starts {:.3g} m below the ground (the stance leg's static compression "
                    "{:.3g} m exceeds the clearance of the neighbouring feet, L0 (1 - cos(2 pi / legs)) = {:.3g} m at "
                    "beta = 0); fewer legs, a stiffer rimless.K or a smaller |initial.beta| is needed",
                    w.legs, init.beta, w.K, w.m, w.g, w.L0, k, -h, delta, w.L0 * (1 - std::cos(2 * w.alpha()))));
  }
}

namespace {

// How far a foot that left the ground must rise before its touchdown guard is armed (WheelFlow):
// ten times the integration error of the foot height, never below 1e-9 L0 [m].
double foot_clearance(const WheelParams& w, const SimulationOptions& o) {
  return std::max(1e-9, 10.0 * o.rtol) * w.L0;
}

// What makes a flow stiff here: the leg's fastest mode, the larger root of m s² + C s + K = 0,
// |λ| = C/2m + sqrt((C/2m)² + K/m) [1/s]. An explicit or Adams method's step stays below
// kStabilityBoundary/|λ| whatever the tolerance (DOP853's stability region reaches -6.1 on the
// real axis, Hairer–Wanner IV.2; CVODE's Adams orders reach less), BDF's does not.
double leg_fastest_mode(const WheelParams& w) {
  const double half = w.C / (2.0 * w.m);
  return half + std::sqrt(half * half + w.K / w.m);
}
constexpr double kStabilityBoundary = 6.1;

// The work limits' advice.
std::string stiffness_hint(const WheelParams& w, numerics::OdeMethod method) {
  const double lambda = leg_fastest_mode(w);
  return fmt::format("the leg's fastest mode has |lambda| = {:.3g} 1/s (rimless.K, rimless.C, rimless.m){}", lambda,
                     method == numerics::OdeMethod::Bdf ? "" : ": a stiff flow runs faster with solver.method=bdf");
}

// The integrator's options.

}  // namespace

numerics::OdeOptions integrator_options(const WheelParams& w, const SimulationOptions& o) {
  numerics::OdeOptions ode;
  // The energy ledger E + W_damp + W_fric = E(0) loses nothing at the resets (its jumps at
  // events are 0 to round-off) and nothing in the flow (d/dt of it is 0 to round-off): what it
  // loses is the integration error, and most of that is the velocities' (the loading of a stiff
  // stance leg). Measured against their own size (~2 m/s) the velocities are allowed 100 times
  // the error they get measured against a fixed 1 % of sqrt(g L0): over 400 seeded random wheels
  // at rtol 1e-10 the ledger's worst error falls from 1.3e-8 to 5.0e-9 for 5 % more right-hand
  // side evaluations (tests/rimless/parameter_space_test.cpp).
  const double v_ref = 0.01 * std::sqrt(w.g * w.L0);
  ode.error_scale.assign(static_cast<std::size_t>(state_size(w)), 0.0);
  ode.error_scale[StateIndex::xd] = ode.error_scale[StateIndex::yd] = v_ref;
  ode.error_scale[StateIndex::thetad] = v_ref / w.L0;
  ode.rtol = o.rtol;
  ode.atol = o.atol;
  ode.method = o.method;
  ode.sensitivities = o.sensitivities;
  return ode;
}

struct FlexibleWheelSimulator::Impl {
  WheelParams w;
  SimulationOptions opt;
  std::optional<ParameterDirection> parameter;  // the sensitivities' parameter column, if any
  WheelFlow flow;
  numerics::OdeIntegrator integrator;
  numerics::HybridSimulation loop;  // the event-driven loop on `integrator`
  std::vector<int> directions;
  std::vector<double> y;           // scratch state
  std::vector<double> y_minus;     // scratch: the state before a reset
  std::vector<GuardEvent> events;  // scratch: the events of one instant

  Impl(const WheelParams& wheel, const SimulationOptions& options, std::optional<ParameterDirection> dp)
      : w(wheel),
        opt(options),
        parameter(std::move(dp)),
        flow(w, ContactSet{}, foot_clearance(w, options)),
        integrator(flow, state_size(w), with_parameter_column(integrator_options(w, options), parameter.has_value())),
        loop(integrator, state_size(w)),
        directions(static_cast<std::size_t>(kGuardsPerLeg * w.legs), -1),
        y(static_cast<std::size_t>(state_size(w))),
        y_minus(static_cast<std::size_t>(state_size(w))) {
    events.reserve(static_cast<std::size_t>(kGuardsPerLeg * w.legs));
    if (parameter) flow.set_parameter(&*parameter);
  }
  // The contact mode c: the flow's, and the directions of its guards (the slots it leaves unused
  // are not watched; an upright guard after them keeps its own).
  void set_mode(const ContactSet& c) {
    flow.set_contacts(c);
    guard_directions(w, c, std::span<int>(directions).first(static_cast<std::size_t>(guard_count(w))));
  }
  static numerics::OdeOptions with_parameter_column(numerics::OdeOptions o, bool column) {
    o.parameter_columns = column && o.sensitivities ? 1 : 0;
    return o;
  }
  // Sensitivity columns: the states, then the parameter's (ParameterDirection) if any.
  Eigen::Index columns() const {
    return static_cast<Eigen::Index>(y.size()) + (parameter && opt.sensitivities ? 1 : 0);
  }
  // ∂g_index/∂p at s (ParameterDirection): the mode's guard with the wheel at p ± h. The clearance
  // offset of a clearing foot and the upright guard do not depend on p.
  double guard_parameter_derivative(int index, std::span<const double> s) const {
    const int n = guard_count(w);
    if (!parameter || index >= n) return 0.0;
    std::vector<double> up(static_cast<std::size_t>(n)), down(static_cast<std::size_t>(n));
    guard_values(parameter->plus, flow.contacts(), s, up);
    guard_values(parameter->minus, flow.contacts(), s, down);
    const auto i = static_cast<std::size_t>(index);
    return (up[i] - down[i]) / (2.0 * parameter->step);
  }
  // ∂(reset)/∂p at s with the mode decision held at `decided`.
  Eigen::VectorXd reset_parameter_derivative(const ContactSet& before, const std::vector<GuardEvent>& events,
                                             const ModeDecision& decided, std::span<const double> s) const {
    const Eigen::Index n = static_cast<Eigen::Index>(s.size());
    std::vector<double> up(s.begin(), s.end()), down(s.begin(), s.end());
    apply_reset(parameter->plus, before, events, decided, up);
    apply_reset(parameter->minus, before, events, decided, down);
    return (Eigen::Map<const Eigen::VectorXd>(up.data(), n) - Eigen::Map<const Eigen::VectorXd>(down.data(), n)) /
           (2.0 * parameter->step);
  }

  // --- linearisation across events (variational.hpp) ---
  Eigen::VectorXd flow_at(const ContactSet& c, std::span<const double> s) const {
    Eigen::VectorXd f(static_cast<Eigen::Index>(s.size()));
    flow_derivative(w, c, s, std::span<double>(f.data(), s.size()));
    return f;
  }
  Eigen::RowVectorXd guard_gradient(int index, std::span<const double> s) {
    std::vector<double> g(directions.size());
    return gradient(
        [&](std::span<const double> x) {
          flow.guards(0.0, x, g);
          return g[static_cast<std::size_t>(index)];
        },
        s, state_steps(w, s));
  }
  // ∂(reset)/∂y with the mode decision held at `decided` (the one choose_modes made at s).
  std::optional<std::string> reset_jacobian(const ContactSet& before, const std::vector<GuardEvent>& events,
                                            const ModeDecision& decided, std::span<const double> s,
                                            Eigen::MatrixXd& R) {
    return jacobian(
        [&](std::span<const double> in, std::span<double> out) {
          std::copy(in.begin(), in.end(), out.begin());
          apply_reset(w, before, events, decided, out);
          return true;
        },
        s, state_steps(w, s), R);
  }
  Eigen::MatrixXd sensitivities_now() const {
    const Eigen::Index n = static_cast<Eigen::Index>(y.size());
    Eigen::MatrixXd S(n, columns());
    integrator.sensitivities(std::span<double>(S.data(), static_cast<std::size_t>(S.size())));
    return S;
  }
  void restart(double t, std::span<const double> s, const Eigen::MatrixXd& S) {
    if (opt.sensitivities) {
      integrator.restart(t, s, directions, std::span<const double>(S.data(), static_cast<std::size_t>(S.size())));
    } else {
      integrator.restart(t, s, directions);
    }
  }

  LogSample sample(double t, std::span<const double> s) const {
    LogSample out;
    out.t = t;
    for (int j = 0; j < 6; ++j) out.q[j] = s[j];
    const ContactSet& c = flow.contacts();
    const Dynamics d = contact_dynamics(w, c, s);
    out.q[StateIndex::thetad] = d.thetad;  // differs from the state's only for I = 0 with all feet slipping
    for (int i = 0; i < c.count; ++i) {
      out.contact[i] = {c.leg[i], c.mode[i], d.force[i].N, d.force[i].T, d.leg[i].c, d.leg[i].cdot};
    }
    out.energy = mechanical_energy(w, c, s);
    out.w_damp = s[StateIndex::w_damp];
    out.w_fric = s[StateIndex::w_fric];
    return out;
  }

  // At rest in double support: no motion (kinetic energy below 1e-12 m g L0) and no force to
  // start one (|q̈| below 1e-6 g, |θ̈| below 1e-6 g / L0: not a turning point of a rocking).
  bool at_rest(std::span<const double> s) const {
    const ContactSet& c = flow.contacts();
    if (c.count < 2 || kinetic_energy(w, s) >= 1e-12 * w.m * w.g * w.L0) return false;
    const Dynamics d = contact_dynamics(w, c, s);
    const double tol = 1e-6 * w.g;
    return !d.failure && std::abs(d.qdd[0]) <= tol && std::abs(d.qdd[1]) <= tol && std::abs(d.qdd[2]) * w.L0 <= tol;
  }

  // A wheel on two or more feet that all slip the same way, neither turning nor rising: a rigid
  // translation along the slope. Its leg forces are constant, so ẍ is too, and the wheel stays
  // in this relative equilibrium: no leg lands again. With ẍ along the slip it slides away ever
  // faster (in effect μ_k < tan φ): that ends the run. Against it, it slides to rest, which the
  // run shows (the feet stick, it comes to rest in double support). Returns whether the state
  // is near such a translation (to 1e-6 in units of sqrt(g L0), sqrt(g / L0), g and g / L0: the
  // translation attracts, the approach is a decaying rocking that may take seconds), with
  // `accelerating` and a description in `detail`.
  bool is_translation(std::span<const double> s, bool& accelerating, std::string& detail) const {
    using S = StateIndex;
    const ContactSet& c = flow.contacts();
    if (c.count < 2) return false;
    const int dir = slip_sign(c.mode[0]);
    for (int i = 0; i < c.count; ++i)
      if (dir == 0 || slip_sign(c.mode[i]) != dir) return false;
    const double v = std::sqrt(w.g * w.L0), omega = std::sqrt(w.g / w.L0), tol = 1e-6;
    if (std::abs(s[S::yd]) > tol * v || std::abs(s[S::thetad]) > tol * omega) return false;
    const Dynamics d = contact_dynamics(w, c, s);
    if (d.failure || std::abs(d.qdd[1]) > tol * w.g || std::abs(d.qdd[2]) > tol * w.g / w.L0) return false;
    std::string legs;
    for (int i = 0; i < c.count; ++i) legs += fmt::format("{}{}", i ? ", " : "", c.leg[i]);
    accelerating = dir * d.qdd[0] > 0;
    detail = fmt::format("sliding without turning on legs {}, {}, xdot = {} m/s, xddot = {} m/s^2", legs,
                         dir > 0 ? "forward" : "backward", s[S::xd], d.qdd[0]);
    return true;
  }

  // After a smooth step: the modes must still be consistent, or an event was missed.
  std::optional<FailureReason> check_consistency(std::span<const double> s, std::string& detail) const {
    const ContactSet& c = flow.contacts();
    const bool remembered = flow.remembered(s);  // the guards' numbers at s (the step's end)
    std::optional<Dynamics> computed;            // (a Dynamics is large: built only where it is needed)
    const Dynamics& d = remembered ? flow.last_dynamics() : computed.emplace(contact_dynamics(w, c, s));
    if (d.failure) return d.failure;
    const double tol_f = 1e-6 * w.m * w.g, tol_v = 1e-6 * std::sqrt(w.g * w.L0);
    for (int i = 0; i < c.count; ++i) {
      const ContactForce& cf = d.force[i];
      const int s_i = slip_sign(c.mode[i]);
      const bool bad = cf.N < -tol_f || (s_i == 0 && std::abs(cf.T) > w.mu_s * cf.N + tol_f) ||
                       (s_i != 0 && s_i * d.leg[i].cdot < -tol_v);
      if (bad) {
        detail = fmt::format("leg {} in {}: N = {}, T = {}, cdot = {}", c.leg[i], mode_name(c.mode[i]), cf.N, cf.T,
                             d.leg[i].cdot);
        return FailureReason::MissedModeChange;
      }
    }
    for (int k = 0; k < w.legs; ++k) {
      if (c.find(k) >= 0) continue;
      const double h = remembered ? flow.last_height(k) : foot_height(w, k, s);
      if (h < -1e-7 * w.L0) {
        detail = fmt::format("leg {} foot height {}", k, h);
        return FailureReason::MissedTouchdown;
      }
    }
    return std::nullopt;
  }
};

FlexibleWheelSimulator::FlexibleWheelSimulator(const WheelParams& wheel, const SimulationOptions& options)
    : impl_(std::make_unique<Impl>(wheel, options, std::nullopt)) {}
FlexibleWheelSimulator::FlexibleWheelSimulator(const WheelParams& wheel, const SimulationOptions& options,
                                               const ParameterDirection& parameter)
    : impl_(std::make_unique<Impl>(wheel, options, parameter)) {}
FlexibleWheelSimulator::~FlexibleWheelSimulator() = default;

SimulationResult FlexibleWheelSimulator::run(const RunSpec& spec, SectionHit* section) {
  SimulationResult res;
  RunCollector keep(res);
  run_into(spec, section, keep, res);
  return res;
}

SimulationResult FlexibleWheelSimulator::run(const RunSpec& spec, RunSink& sink, SectionHit* section) {
  SimulationResult res;
  run_into(spec, section, sink, res);
  return res;
}

// One run of the flexible wheel as a model of the hybrid loop (numerics/hybrid_simulation.hpp).
//
// Its guard/reset pairs (docs/theory/rimless.md, "Events and contact modes"; the guards are flow.hpp's, four per leg):
//   touchdown   h_k = y - (L0 - δ_k) cos β_k ↓ 0        lift-off      N_k ↓ 0
//   stick→slip  μ_s - |T_k|/N_k ↓ 0                    slip→stick    s ċ_k ↓ 0
//   fall over   cos β_k ↓ 0                            slip jam      cos β_k - μ s sin β_k ↓ 0
// and one reset for the events of an instant together, choose_modes() (spec "Contact modes are
// chosen, not guessed"): the feet's modes are decided jointly, since two feet in double support
// constrain each other. The reset checks its postcondition (check_reset()). With the upright
// section one more guard, sin β of the next leg to pass upright ↑ 0, ends the run (no reset).
struct FlexibleWheelSimulator::Run final : numerics::HybridModel {
  using S = StateIndex;
  Impl& m;
  const WheelParams& w;
  const RunSpec& spec;
  SectionHit* section;
  RunSink& sink;
  SimulationResult& res;
  const int steps_wanted;
  const bool upright_stop, touchdown_stop;
  bool hit = false;
  bool logged_any = false;
  double last_logged_t = 0;                        // [s]
  double last_touchdown = 0.0;                     // [s]
  double translating_since = -1.0;                 // [s], -1: not translating
  double ke0 = 0;                                  // kinetic energy at t = 0, after the modes were chosen [J]
  double step_begin = 0, step_end = 0;             // the latest integrator step's ends [s]
  static constexpr double kTranslationHold = 1.0;  // s a rigid translation must last to end the run
  StepTracker tracker;
  Eigen::MatrixXd sens;  // ∂y/∂y(0), with sensitivities (n×n)
  // At a guard crossing, before the reset:
  ContactSet before;        // the feet on the ground
  Eigen::MatrixXd S_minus;  // with sensitivities: ∂y/∂y(0) at the crossing
  Eigen::VectorXd f_minus;  // the flow there
  Eigen::RowVectorXd g_y;   // the first fired guard's gradient there
  double g_p = 0;           // and its derivative in the parameter (ParameterDirection)

  Run(Impl& impl, const RunSpec& s, SectionHit* hit_out, RunSink& out, SimulationResult& result)
      : m(impl),
        w(impl.w),
        spec(s),
        section(hit_out),
        sink(out),
        res(result),
        steps_wanted(s.steps > 0 ? s.steps : impl.opt.steps),
        upright_stop(s.stop_at == Section::Upright),
        touchdown_stop(s.stop_at == Section::Touchdown) {}

  void record_event(double te, RunEvent kind, int leg) {
    ++res.event_count;
    sink.on_event({te, kind, leg, m.flow.contacts(), {}});
  }
  // The events of a reset, in leg order. At a slip→stick event every other foot that came to
  // rest with it (slipping before, sticking after, no event of its own: two feet slipping as one,
  // whose slip velocities reach 0 within round-off of each other) is reported as reaching stick
  // too, so the record does not depend on which of the two guards the round-off fired.
  void record_events(double te, std::span<const GuardEvent> events, const ContactSet& after) {
    bool slip_to_stick = false;
    for (const auto& e : events) slip_to_stick = slip_to_stick || e.kind == EventKind::SlipToStick;
    for (int k = 0; k < w.legs; ++k) {
      bool own = false;
      for (const auto& e : events) {
        if (e.leg != k) continue;
        record_event(te, run_event(e.kind), k);
        own = true;
      }
      const int i = before.find(k), j = after.find(k);
      if (!own && slip_to_stick && i >= 0 && before.mode[i] != FootMode::Stick && j >= 0 &&
          after.mode[j] == FootMode::Stick)
        record_event(te, RunEvent::SlipToStick, k);
    }
  }
  void fail(double te, FailureReason reason, std::string detail = {}) {
    res.failure = Failure{reason, std::move(detail), {}};
    ++res.event_count;
    sink.on_event({te, RunEvent::Failure, -1, m.flow.contacts(), res.failure->text()});
  }
  void loop_failed(numerics::LoopFailure what, double te, const std::string& detail) override {
    fail(te, loop_failure_reason(what), detail);
  }
  void log_sample(double ts, std::span<const double> ys) {
    sink.on_sample(m.sample(ts, ys));
    logged_any = true;
    last_logged_t = ts;
  }
  void release_steps() {
    for (const StepRecord& st : tracker.final_steps()) sink.on_step(st);
    tracker.drop_final_steps();
  }

  // The modes at t = 0 and the first restart; false if the run ended there.
  bool start();
  // The result's totals at the end time t.
  void finish(double t);

  bool finished() const override { return hit || res.steps_completed >= steps_wanted; }
  // Known before the first step: stability alone needs |λ|/6.1 steps per simulated second.
  bool ready(double t) override {
    if (m.opt.method == numerics::OdeMethod::Bdf || leg_fastest_mode(w) / kStabilityBoundary <= m.opt.max_step_rate)
      return true;
    fail(t, FailureReason::StepRateFromStart,
         fmt::format("{} needs at least {:.3g} steps per simulated second for stability alone (limit {:.3g}); {}",
                     name_of(m.opt.method), leg_fastest_mode(w) / kStabilityBoundary, m.opt.max_step_rate,
                     stiffness_hint(w, m.opt.method)));
    return false;
  }
  void work_limit_reached(numerics::WorkLimit limit, double t, double measured) override {
    if (limit == numerics::WorkLimit::WallTime) {
      fail(t, FailureReason::WallTime,
           fmt::format("{} s at t = {} s after {} steps; {}", m.opt.max_wall_time, t, res.steps_completed,
                       stiffness_hint(w, m.opt.method)));
    } else {
      fail(t, FailureReason::StepRate,
           fmt::format("{:.3g} solver steps per simulated second over the last {} (limit {:.3g}) at t = {} s after {} "
                       "steps; {}",
                       measured, numerics::HybridSimulation::kRateWindow, m.opt.max_step_rate, t, res.steps_completed,
                       stiffness_hint(w, m.opt.method)));
    }
  }
  double stop_time() const override { return std::min(m.opt.max_time, last_touchdown + m.opt.max_step_time); }
  void sample(double t, std::span<const double> y) override { log_sample(t, y); }
  void stepped(double t, std::span<const double> y) override {
    std::copy(y.begin(), y.end(), m.y.begin());
    m.flow.arm_cleared(m.y);
    step_begin = step_end;
    step_end = t;
  }
  double event_time(double t, std::span<double> y, std::span<const int> fired,
                    const numerics::OdeIntegrator& integrator) override;
  bool smooth_step(double t, std::span<const double>, numerics::StepStatus status) override;
  // One foot down, balanced at the vertical (simulation.hpp).
  bool balanced_at_vertical() const {
    const ContactSet& down = m.flow.contacts();
    return down.count == 1 &&
           rimless::balanced_at_vertical(w, leg_angle(w, down.leg[0], m.y[S::theta]), m.y[S::thetad]);
  }
  numerics::HybridNext guards_crossed(double t, std::span<const double> y, std::span<const int> fired,
                                      const numerics::OdeIntegrator& integrator,
                                      std::vector<numerics::HybridEvent>& events) override;
  // docs/theory/rimless.md, "Events and contact modes": rolled back, a landing with β > 0 while θ̇ < 0 and ẋ < 0.
  bool admissible(double t, std::span<const double>, const numerics::HybridEvent& e) override {
    if (static_cast<EventKind>(e.kind) != EventKind::Touchdown) return true;
    const double beta = leg_angle(w, e.unit, m.y[S::theta]);
    if (beta > 0 && m.y[S::thetad] < 0 && m.y[S::xd] < 0) {
      fail(t, FailureReason::RolledBack, fmt::format("leg {}, beta = {}", e.unit, beta));
      return false;
    }
    return true;
  }
  numerics::HybridNext reset(double t, std::span<double> y, std::span<const numerics::HybridEvent> events) override;
  std::span<const int> directions() const override { return m.directions; }
  std::span<const double> restart_sensitivities() const override {
    if (!m.opt.sensitivities) return {};
    return {sens.data(), static_cast<std::size_t>(sens.size())};
  }
  void restarted(double t, std::span<const double>) override {
    step_end = t;
    sink.on_restart(t, m.y, m.flow.contacts());
  }
  std::string describe(const numerics::HybridEvent& e) const override {
    return fmt::format("leg {} {}", e.unit, event_name(static_cast<EventKind>(e.kind)));
  }

  // The section's sensitivity ∂y(t_section)/∂y(0): the saltation of the crossing time, no reset.
  Eigen::MatrixXd section_sensitivity() const {
    if (!m.opt.sensitivities) return Eigen::MatrixXd();
    const Eigen::Index n = static_cast<Eigen::Index>(m.y.size());
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
    Eigen::MatrixXd S = saltation(I, f_minus, Eigen::VectorXd::Zero(n), g_y) * S_minus;
    if (m.parameter) S.col(n) -= f_minus * (g_p / g_y.dot(f_minus));  // the crossing time's shift in p
    return S;
  }
  // The reset's postcondition (mode_selection.hpp): a foot whose lift-off, stick→slip or fall-over
  // guard fired does not keep its mode (else the same guard fires again at the restart).
  void check_reset(std::span<const GuardEvent> events, const ModeDecision& dec) const {
    for (const GuardEvent& e : events) {
      if (e.kind != EventKind::LiftOff && e.kind != EventKind::StickToSlip && e.kind != EventKind::FallOver) continue;
      const int was = before.find(e.leg), now = dec.contacts.find(e.leg);
      if (was >= 0 && now >= 0 && dec.contacts.mode[now] == before.mode[was])
        throw std::logic_error(fmt::format("choose_modes kept leg {} in {} after its {} guard fired", e.leg,
                                           mode_name(before.mode[was]), event_name(e.kind)));
    }
  }
};

bool FlexibleWheelSimulator::Run::start() {
  // Modes at t = 0: the pending events (a foot landing now) are handled like any event.
  for (int k = 0; k < w.legs; ++k) {
    if (spec.contacts.find(k) >= 0) continue;
    bool landing = false;
    for (const auto& e : spec.pending) landing = landing || (e.leg == k && e.kind == EventKind::Touchdown);
    if (!landing && foot_height(w, k, m.y) < -1e-12 * w.L0) {  // an outcome of the start, not a broken contract
      fail(0.0, FailureReason::InitialFootBelowGround, std::to_string(k));
      res.final_state = m.y;
      return false;
    }
  }
  m.directions.assign(static_cast<std::size_t>(guard_count(w)), -1);
  if (upright_stop) m.directions.push_back(+1);
  m.set_mode(spec.contacts);
  m.flow.clear_all();
  const Eigen::Index n_state = static_cast<Eigen::Index>(m.y.size());
  sens = Eigen::MatrixXd::Identity(n_state, m.columns());  // [I | 0]
  if (!spec.pending.empty()) {
    const std::vector<double> y_before = m.y;
    const ModeDecision dec = choose_modes(w, spec.contacts, spec.pending, m.y);
    if (dec.failure) {
      fail(0.0, *dec.failure, dec.detail);
      res.final_state = m.y;
      return false;
    }
    m.set_mode(dec.contacts);
    m.flow.start_clearing(spec.contacts, spec.pending);
    res.jams += dec.jammed_feet;
    // The section state lies on the landing guard by construction: no timing term, reset only.
    if (m.opt.sensitivities) {
      Eigen::MatrixXd R;
      if (auto e = m.reset_jacobian(spec.contacts, spec.pending, dec, y_before, R)) {
        fail(0.0, FailureReason::Sensitivities, *e);
        res.final_state = m.y;
        return false;
      }
      sens.leftCols(n_state) = R;
      if (m.parameter) sens.col(n_state) = m.reset_parameter_derivative(spec.contacts, spec.pending, dec, y_before);
    }
  }
  // The next leg to pass upright: the one with β in [-2α, 0).
  m.flow.set_upright_leg(-1);
  if (upright_stop) {
    for (int k = 0; k < w.legs; ++k) {
      const double beta = leg_angle(w, k, m.y[S::theta]);
      if (beta < 0 && beta >= -2.0 * w.alpha() * (1 + 1e-12)) m.flow.set_upright_leg(k);
    }
  }
  res.energy_initial = mechanical_energy(w, m.flow.contacts(), m.y).total();
  ke0 = kinetic_energy(w, m.y);
  int stance = spec.stance_leg;  // else a foot landing at t = 0 is the stance foot of the first step
  for (const auto& e : spec.pending)
    if (stance < 0 && e.kind == EventKind::Touchdown && m.flow.contacts().find(e.leg) >= 0) stance = e.leg;
  tracker.start(0.0, m.y[S::x], res.energy_initial, m.flow.contacts(), w.legs, stance);
  sink.on_start(res.energy_initial);
  record_event(0.0, RunEvent::Start, m.flow.contacts().count > 0 ? m.flow.contacts().leg[0] : -1);
  if (m.opt.log) log_sample(0.0, m.y);
  m.restart(0.0, m.y, sens);
  sink.on_restart(0.0, m.y, m.flow.contacts());
  return true;
}

// A foot that left the ground and came back before it cleared it by the clearance (WheelFlow)
// is detected at h = -clearance; it lands where h last fell through 0, found on the step's dense
// output: from the step's start if the foot was above the ground there, else from the first of
// kBounceSamples samples of the step that is (a micro-bounce that rose and fell within it). A foot
// that never rose above the round-off of h in the step (it left with the ground pushing it back)
// lands where it was detected. Only a crossing of that guard alone moves back (other
// guards that fired at t have not crossed earlier).
double FlexibleWheelSimulator::Run::event_time(double t, std::span<double> y, std::span<const int> fired,
                                               const numerics::OdeIntegrator& integrator) {
  constexpr int kBounceSamples = 16;
  int leg = -1, count = 0;
  for (std::size_t i = 0; i < fired.size(); ++i) {
    if (fired[i] == 0) continue;
    ++count;
    const int k = static_cast<int>(i) / kGuardsPerLeg;
    if (static_cast<int>(i) < guard_count(w) && i % kGuardsPerLeg == 0 && m.flow.contacts().find(k) < 0 &&
        m.flow.clearing(k))
      leg = k;
  }
  if (leg < 0 || count != 1 || !(step_begin < t)) return t;
  std::vector<double>& s = m.y_minus;  // scratch
  const auto height = [&](double ts) {
    integrator.interpolate(ts, s);
    return foot_height(w, leg, s);
  };
  const double rose = 64.0 * std::numeric_limits<double>::epsilon() * w.L0;  // above the round-off of h
  double t_up = step_begin, h_up = height(step_begin);
  for (int j = 1; j < kBounceSamples && !(h_up > rose); ++j) {
    const double ts = step_begin + (t - step_begin) * j / kBounceSamples;
    const double h = height(ts);
    if (h > h_up) t_up = ts, h_up = h;
  }
  const double h_end = height(t);
  if (!(h_up > rose) || !(h_end < 0)) return t;
  const double tol = 100.0 * std::numeric_limits<double>::epsilon() * (std::abs(t) + std::abs(t - t_up));
  const double landing = numerics::locate_root(height, t_up, t, h_up, h_end, tol);
  integrator.interpolate(landing, y);
  std::copy(y.begin(), y.end(), m.y.begin());
  return landing;
}

bool FlexibleWheelSimulator::Run::smooth_step(double t, std::span<const double>, numerics::StepStatus status) {
  std::string detail;
  if (const auto why = m.check_consistency(m.y, detail)) {
    fail(t, *why, detail);
    return false;
  }
  if (m.at_rest(m.y)) {
    fail(t, FailureReason::AtRest);
    return false;
  }
  bool accelerating = false;
  std::string motion;
  const bool translation = m.is_translation(m.y, accelerating, motion);
  // A translation is a relative equilibrium; it must hold for kTranslationHold to be named.
  if (translation && accelerating) {
    if (translating_since < 0) translating_since = t;
    if (t - translating_since >= kTranslationHold) {
      fail(t, FailureReason::SlidAway, motion);
      return false;
    }
  } else {
    translating_since = -1.0;
  }
  if (status == numerics::StepStatus::StopTime) {
    const std::string also = translation ? "; " + motion : "";
    if (t >= m.opt.max_time)
      fail(t, FailureReason::TimeLimit, fmt::format("{} s{}", m.opt.max_time, also));
    else if (balanced_at_vertical())
      fail(t, FailureReason::BalancedAtVertical, fmt::format("{} s{}", m.opt.max_step_time, also));
    else
      fail(t, FailureReason::NoLanding, fmt::format("{} s{}", m.opt.max_step_time, also));
    return false;
  }
  return true;
}

numerics::HybridNext FlexibleWheelSimulator::Run::guards_crossed(double t, std::span<const double>,
                                                                 std::span<const int> fired,
                                                                 const numerics::OdeIntegrator&,
                                                                 std::vector<numerics::HybridEvent>& events) {
  translating_since = -1.0;
  before = m.flow.contacts();
  m.events.clear();
  if (m.opt.sensitivities) {
    int first = 0;
    while (fired[static_cast<std::size_t>(first)] == 0) ++first;
    S_minus = m.sensitivities_now();
    f_minus = m.flow_at(before, m.y);
    g_y = m.guard_gradient(first, m.y);
    g_p = m.guard_parameter_derivative(first, m.y);
  }
  if (upright_stop && fired[static_cast<std::size_t>(guard_count(w))] != 0) {
    const int k = m.flow.upright_leg();
    if (!(before.count == 1 && before.leg[0] == k)) {
      fail(t, FailureReason::UprightOutsideSingleSupport, describe_contacts(before));
      return numerics::HybridNext::Stop;
    }
    if (section != nullptr) *section = {t, m.y, before, k, section_sensitivity()};
    record_event(t, RunEvent::Section, k);
    hit = true;
    return numerics::HybridNext::Stop;
  }
  for (int k = 0; k < w.legs; ++k) {
    const int i = before.find(k);
    for (int slot = 0; slot < kGuardsPerLeg; ++slot) {
      if (fired[static_cast<std::size_t>(kGuardsPerLeg * k + slot)] == 0) continue;
      m.events.push_back({k, guard_event(slot, i >= 0, i >= 0 ? before.mode[i] : FootMode::Stick)});
    }
  }
  if (m.opt.log) log_sample(t, m.y);
  if (touchdown_stop) {
    for (const auto& e : m.events) {
      const bool counts =
          tracker.is_new_leg(e.leg) || (spec.section_includes_legs_behind && e.leg != tracker.stance_leg());
      if (e.kind == EventKind::Touchdown && counts && !hit) {
        if (section != nullptr) *section = {t, m.y, before, e.leg, section_sensitivity()};
        record_event(t, RunEvent::Section, e.leg);
        hit = true;
      }
    }
    if (hit) return numerics::HybridNext::Stop;
  }
  for (const auto& e : m.events) events.push_back({e.leg, static_cast<int>(e.kind)});
  return numerics::HybridNext::Restart;
}

numerics::HybridNext FlexibleWheelSimulator::Run::reset(double t, std::span<double> y,
                                                        std::span<const numerics::HybridEvent>) {
  const std::vector<GuardEvent>& events = m.events;
  std::copy(m.y.begin(), m.y.end(), m.y_minus.begin());
  const ModeDecision dec = choose_modes(w, before, events, m.y);
  if (dec.failure) {
    for (const auto& e : events) record_event(t, run_event(e.kind), e.leg);
    fail(t, *dec.failure, dec.detail);
    return numerics::HybridNext::Stop;
  }
  check_reset(events, dec);
  if (m.opt.sensitivities) {
    Eigen::MatrixXd R;
    if (auto e = m.reset_jacobian(before, events, dec, m.y_minus, R)) {
      fail(t, FailureReason::Sensitivities, *e);
      return numerics::HybridNext::Stop;
    }
    const Eigen::VectorXd f_plus = m.flow_at(dec.contacts, m.y);
    sens = saltation(R, f_minus, f_plus, g_y) * S_minus;
    if (m.parameter) {  // ParameterDirection: the reset's and the event time's own dependence on p
      const Eigen::Index n = R.rows();
      sens.col(n) += m.reset_parameter_derivative(before, events, dec, m.y_minus) +
                     (f_plus - R * f_minus) * (g_p / g_y.dot(f_minus));
    }
  }
  m.set_mode(dec.contacts);
  m.flow.start_clearing(before, events);
  if (dec.consistent > 1) ++res.ambiguous_choices;
  res.jams += dec.jammed_feet;
  if (dec.jammed_feet > 0) record_event(t, RunEvent::Jam, events.front().leg);
  record_events(t, events, dec.contacts);

  const double energy = mechanical_energy(w, dec.contacts, m.y).total();
  bool new_step = false;
  for (const auto& e : events) {
    if (e.kind == EventKind::Touchdown && tracker.is_new_leg(e.leg) && dec.contacts.find(e.leg) >= 0) {
      tracker.touchdown(t, m.y[S::x], energy, e.leg, dec.contacts);
      ++res.steps_completed;
      last_touchdown = t;
      new_step = true;
    }
  }
  if (new_step)
    release_steps();
  else
    tracker.observe(dec.contacts);
  if (m.opt.log) log_sample(t, m.y);
  std::copy(m.y.begin(), m.y.end(), y.begin());
  return numerics::HybridNext::Restart;
}

void FlexibleWheelSimulator::Run::finish(double t) {
  res.t_final = t;
  res.final_state = m.y;
  res.final_contacts = m.flow.contacts();
  if (m.opt.log && (!logged_any || last_logged_t < t)) log_sample(t, m.y);
  tracker.finish(t, m.y[S::x]);
  const StepRecord* last_complete = tracker.last_complete();
  const double x_end = last_complete != nullptr ? last_complete->x_end : m.y[S::x];
  res.gaits = tracker.gaits();
  if (!tracker.steps().empty()) res.last_step = tracker.steps().back();
  for (const StepRecord& st : tracker.steps()) sink.on_step(st);
  res.energy_final = mechanical_energy(w, m.flow.contacts(), m.y).total();
  res.work_damping = m.y[S::w_damp];
  res.work_friction = m.y[S::w_fric];
  const double scale = ke0 + w.m * w.g * w.L0 + res.work_damping + res.work_friction;
  res.energy_balance_error =
      std::abs(res.energy_final + res.work_damping + res.work_friction - res.energy_initial) / scale;
  const double t_end = res.steps_completed > 0 ? last_touchdown : t;
  res.mean_speed = t_end > 0 ? (x_end - spec.y0[S::x]) / t_end : 0.0;
}

void FlexibleWheelSimulator::run_into(const RunSpec& spec, SectionHit* section, RunSink& sink, SimulationResult& res) {
  Impl& m = *impl_;
  const numerics::OdeStats stats0 = m.integrator.stats();  // the integrator may have run before
  if (static_cast<int>(spec.y0.size()) != state_size(m.w)) throw std::invalid_argument("RunSpec: wrong state size");
  std::copy(spec.y0.begin(), spec.y0.end(), m.y.begin());
  Run run(m, spec, section, sink, res);
  if (!run.start()) return;
  numerics::HybridLimits limits;
  limits.sample = m.opt.log;
  limits.sample_dt = m.opt.sample_dt;
  limits.max_wall_time = m.opt.max_wall_time;
  limits.max_step_rate = m.opt.max_step_rate;
  limits.poll = m.opt.poll;
  run.finish(m.loop.run(run, limits, 0.0));
  const numerics::OdeStats st = m.integrator.stats();
  res.solver_steps = st.steps - stats0.steps;
  res.rhs_evals = st.rhs_evals - stats0.rhs_evals;
}

SimulationResult simulate_flexible(const WheelParams& w, const InitialState& initial,
                                   const SimulationOptions& options) {
  FlexibleWheelSimulator sim(w, options);
  return sim.run(default_run(w, initial));
}

SimulationResult simulate_flexible(const WheelParams& w, const InitialState& initial, const SimulationOptions& options,
                                   RunSink& sink) {
  FlexibleWheelSimulator sim(w, options);
  return sim.run(default_run(w, initial), sink);
}

}  // namespace flexgait::rimless
