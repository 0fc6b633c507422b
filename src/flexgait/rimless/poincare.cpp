#include "flexgait/rimless/poincare.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "flexgait/rimless/rigid_wheel.hpp"

namespace flexgait::rimless {
namespace {

bool sticks(const SectionState& p) {
  return !p.flight && p.mode == FootMode::Stick;
}

// Phases of two partial steps, joined and merged ("stick" + "stick-slip" -> "stick-slip"), labelled
// as the first (the one that began with a landing).
std::string joined_label(const StepRecord& first, const StepRecord& second) {
  std::vector<Phase> all;
  for (const auto* part : {&first.single_support, &second.single_support})
    for (Phase p : *part)
      if (all.empty() || all.back() != p) all.push_back(p);
  return step_gait(first, all);
}

// The gait of one cycle between two crossings: the stance foot's phases of the step that ended at
// a touchdown crossing, or of the two partial steps around an upright crossing, joined.
std::string cycle_gait(Section section, const SimulationResult& r) {
  if (section == Section::Touchdown || r.steps.size() < 2) return r.steps.empty() ? "" : step_gait(r.steps.front());
  return joined_label(r.steps[1], r.steps[0]);
}

}  // namespace

std::string mode_text(const SectionState& p) {
  return p.flight ? "flight" : mode_name(p.mode);
}

SectionState in_mode(const WheelParams& w, const SectionState& point, const SectionState& like) {
  using S = StateIndex;
  SectionState out = like;
  if (point.model == Model::Rigid || (point.flight == like.flight && point.mode == like.mode)) {
    out.z = point.z;
    return out;
  }
  const std::vector<double> y = section_run(w, point).y0;
  const std::vector<std::string> names = like.names();
  out.z.resize(static_cast<Eigen::Index>(names.size()));
  out.z(0) = point.z(0);  // β (touchdown) or y (upright): the same in every mode
  for (std::size_t i = 1; i < names.size(); ++i) {
    const int k = names[i] == "xd" ? S::xd : names[i] == "yd" ? S::yd : S::thetad;
    out.z(static_cast<Eigen::Index>(i)) = y[static_cast<std::size_t>(k)];
  }
  return out;
}

std::vector<std::string> SectionState::names() const {
  if (model == Model::Rigid) return {"thetad"};
  const std::string first = section == Section::Touchdown ? "beta" : "y";
  if (sticks(*this)) return {first, "yd", "thetad"};
  return {first, "xd", "yd", "thetad"};
}

Eigen::VectorXd SectionState::scale(const WheelParams& w) const {
  const double v = std::sqrt(w.g * w.L0), omega = v / w.L0;
  if (model == Model::Rigid) return Eigen::VectorXd::Constant(1, omega);
  const double first = section == Section::Touchdown ? w.alpha() : w.L0;
  if (sticks(*this)) return Eigen::Vector3d(first, v, omega);
  return Eigen::Vector4d(first, v, v, omega);
}

RunSpec section_run(const WheelParams& w, const SectionState& p) {
  using S = StateIndex;
  RunSpec spec;
  spec.y0.assign(static_cast<std::size_t>(state_size(w)), 0.0);
  auto& y = spec.y0;
  const Eigen::VectorXd& z = p.z;
  const bool stick = sticks(p);
  double theta = 0;
  if (p.section == Section::Touchdown) {
    const double beta_new = z(0);
    theta = beta_new + 2.0 * w.alpha();
    y[S::y] = w.L0 * std::cos(beta_new);
    y[S::x] = p.flight ? 0.0 : y[S::y] * std::tan(theta);
    spec.pending = {{w.legs - 1, EventKind::Touchdown}};
  } else {
    y[S::y] = z(0);
    y[S::x] = 0.0;
  }
  y[S::theta] = theta;
  y[S::yd] = z(stick ? 1 : 2);
  y[S::thetad] = z(stick ? 2 : 3);
  if (stick) {  // ċ = ẋ - ẏ tan θ - y θ̇ / cos² θ = 0 on leg 0
    const double c = std::cos(theta);
    y[S::xd] = y[S::yd] * std::tan(theta) + y[S::y] * y[S::thetad] / (c * c);
  } else {
    y[S::xd] = z(1);
  }
  if (!p.flight) {
    spec.contacts.count = 1;
    spec.contacts.leg[0] = 0;
    spec.contacts.mode[0] = p.mode;
    spec.contacts.anchor[0] = 0.0;
  }
  return spec;
}

std::optional<std::string> reduce_crossing(const WheelParams& w, Section section, const SectionHit& hit,
                                           SectionState& out) {
  using S = StateIndex;
  out.model = Model::Flexible;
  out.section = section;
  const auto& y = hit.state;
  out.flight = hit.contacts.count == 0;
  if (hit.contacts.count > 1)
    return fmt::format("{} feet on the ground at the {} section", hit.contacts.count, name_of(section));
  if (section == Section::Upright && out.flight) return std::string("flight at the upright section");
  out.mode = out.flight ? FootMode::Stick : hit.contacts.mode[0];
  if (!out.flight) {
    const int stance = hit.contacts.leg[0];
    const int expected = section == Section::Touchdown ? (stance + w.legs - 1) % w.legs : stance;
    if (hit.leg != expected)
      return fmt::format("leg {} crossed the {} section, leg {} expected", hit.leg, name_of(section), expected);
  }
  const bool stick = sticks(out);
  out.z.resize(stick ? 3 : 4);
  out.z(0) = section == Section::Touchdown ? leg_angle(w, hit.leg, y[S::theta]) : y[S::y];
  if (!stick) out.z(1) = y[S::xd];
  out.z(stick ? 1 : 2) = y[S::yd];
  out.z(stick ? 2 : 3) = y[S::thetad];
  return std::nullopt;
}

PoincareMap::PoincareMap(const WheelParams& w, const SimulationOptions& options, Model model, Section section)
    : w_(w), options_(options), model_(model), section_(section) {
  options_.log = false;
  if (model_ == Model::Flexible) sim_ = std::make_unique<FlexibleWheelSimulator>(w_, options_);
}
PoincareMap::~PoincareMap() = default;
PoincareMap::PoincareMap(PoincareMap&&) noexcept = default;

MapStep PoincareMap::apply(const SectionState& p, bool keep_mode) {
  MapStep out;
  out.next = p;
  if (model_ == Model::Rigid) {
    SimulationOptions o = options_;
    o.steps = 2;
    const InitialState start{p.z(0), section_ == Section::Touchdown ? -w_.alpha() : 0.0};
    const SimulationResult r = simulate_rigid(w_, start, o, section_);
    if (r.failure) {
      out.failure = r.failure;
      return out;
    }
    out.next.z = Eigen::VectorXd::Constant(1, r.final_state[5]);
    out.gait = "stick";
    out.period = r.t_final;
    out.distance = r.steps.empty() ? 0.0 : r.final_state[0] - r.steps.front().x_start;
    out.dissipated = r.work_damping;
    return out;
  }
  RunSpec spec = section_run(w_, p);
  spec.stop_at = section_;
  spec.steps = 3;  // a cycle between two crossings holds one touchdown (upright) or none (touchdown)
  SectionHit hit;
  hit.leg = -1;
  const SimulationResult r = sim_->run(spec, &hit);
  if (r.failure) {
    // e.g. a perturbed point with a foot below the ground
    out.failure = r.failure->reason == FailureReason::InitialFootBelowGround
                      ? r.failure->in_stage("infeasible section point")
                      : *r.failure;
    return out;
  }
  if (hit.leg < 0) {
    out.failure = Failure{FailureReason::SectionNotReached, std::string(name_of(section_)), {}};
    return out;
  }
  if (auto e = reduce_crossing(w_, section_, hit, out.next)) {
    out.failure = Failure{FailureReason::IrreducibleCrossing, *e, {}};
    return out;
  }
  if (keep_mode && (out.next.flight != p.flight || out.next.mode != p.mode)) {
    out.failure =
        Failure{FailureReason::OtherMode, fmt::format("{} instead of {}", mode_text(out.next), mode_text(p)), {}};
    return out;
  }
  using S = StateIndex;
  out.period = hit.t;
  out.distance = hit.state[S::x] - spec.y0[S::x];
  // Energy that left the wheel's body: dissipated, or still stored in relaxing free legs (which
  // the reduced state drops; see the header). On a periodic orbit it equals m g sin φ Δx.
  out.dissipated = hit.state[S::w_damp] + hit.state[S::w_fric];
  for (int k = 0; k < w_.legs; ++k) {
    if (hit.contacts.find(k) >= 0) continue;
    const double d = hit.state[static_cast<std::size_t>(S::free_delta + k)];
    out.dissipated += 0.5 * w_.K * d * d;
  }
  out.jams = r.jams;
  out.gait = cycle_gait(section_, r);
  return out;
}

std::optional<std::string> PoincareMap::jacobian(const SectionState& p, Eigen::MatrixXd& J) {
  return linearise(p, J, nullptr);
}

void PoincareMap::set_parameter(const ParameterDirection& parameter) {
  parameter_ = parameter;
  sens_sim_.reset();  // made again with the parameter column
}

std::optional<std::string> PoincareMap::jacobian_and_parameter_derivative(const SectionState& p, Eigen::MatrixXd& J,
                                                                          Eigen::VectorXd& J_p) {
  if (!parameter_) return std::string("no parameter set");
  return linearise(p, J, &J_p);
}

std::optional<std::string> PoincareMap::linearise(const SectionState& p, Eigen::MatrixXd& J, Eigen::VectorXd* J_p) {
  using S = StateIndex;
  if (model_ == Model::Rigid) {
    if (section_ != Section::Touchdown)
      return std::string("the rigid wheel's exact Jacobian is given at the touchdown section");
    J = Eigen::MatrixXd::Constant(1, 1, rigid_step_map(w_).derivative(p.z(0)));
    if (J_p != nullptr) {
      const double up = rigid_step_map(parameter_->plus).next(p.z(0)),
                   down = rigid_step_map(parameter_->minus).next(p.z(0));
      *J_p = Eigen::VectorXd::Constant(1, (up - down) / (2.0 * parameter_->step));
    }
    return std::nullopt;
  }
  if (w_.I == 0) return std::string("no variational Jacobian for I = 0 (theta-dot is algebraic there)");
  const Eigen::Index d = p.z.size();
  const Eigen::Index n = state_size(w_);
  // Y_z: the section reconstruction, differentiated centrally.
  Eigen::MatrixXd Yz(n, d);
  const Eigen::VectorXd sc = p.scale(w_);
  for (Eigen::Index i = 0; i < d; ++i) {
    const double h = 6e-6 * std::max(std::abs(p.z(i)), sc(i));
    SectionState a = p, b = p;
    a.z(i) += h;
    b.z(i) -= h;
    const RunSpec ra = section_run(w_, a), rb = section_run(w_, b);
    for (Eigen::Index r = 0; r < n; ++r)
      Yz(r, i) = (ra.y0[static_cast<std::size_t>(r)] - rb.y0[static_cast<std::size_t>(r)]) / (2 * h);
  }
  if (!sens_sim_) {
    SimulationOptions o = options_;
    o.sensitivities = true;
    sens_sim_ = parameter_ ? std::make_unique<FlexibleWheelSimulator>(w_, o, *parameter_)
                           : std::make_unique<FlexibleWheelSimulator>(w_, o);
  }
  RunSpec spec = section_run(w_, p);
  spec.stop_at = section_;
  spec.steps = 3;
  SectionHit hit;
  hit.leg = -1;
  const SimulationResult r = sens_sim_->run(spec, &hit);
  if (r.failure) return r.failure->text();
  if (hit.leg < 0 || hit.S.size() == 0)
    return Failure{FailureReason::SectionNotReached, std::string(name_of(section_)), {}}.text();
  SectionState next;
  if (auto e = reduce_crossing(w_, section_, hit, next)) return e;
  if (next.flight != p.flight || next.mode != p.mode || next.z.size() != d)
    return Failure{FailureReason::OtherMode, {}, {}}.text();
  // Z_y: z's components are state components (β = θ + const at the touchdown section).
  std::vector<int> rows{section_ == Section::Touchdown ? S::theta : S::y};
  if (!sticks(p)) rows.push_back(S::xd);
  rows.push_back(S::yd);
  rows.push_back(S::thetad);
  J.resize(d, d);
  const Eigen::MatrixXd SY = hit.S.leftCols(n) * Yz;
  for (Eigen::Index i = 0; i < d; ++i) J.row(i) = SY.row(rows[static_cast<std::size_t>(i)]);
  if (J_p != nullptr) {
    if (hit.S.cols() != n + 1) return std::string("the sensitivities have no parameter column");
    // Y_p: the section reconstruction at the same z with the wheel at p ± h.
    const RunSpec up = section_run(parameter_->plus, p), down = section_run(parameter_->minus, p);
    Eigen::VectorXd Yp(n);
    for (Eigen::Index r = 0; r < n; ++r)
      Yp(r) = (up.y0[static_cast<std::size_t>(r)] - down.y0[static_cast<std::size_t>(r)]) / (2.0 * parameter_->step);
    const Eigen::VectorXd dy = hit.S.leftCols(n) * Yp + hit.S.col(n);
    J_p->resize(d);
    for (Eigen::Index i = 0; i < d; ++i) (*J_p)(i) = dy(rows[static_cast<std::size_t>(i)]);
  }
  return std::nullopt;
}

std::optional<std::string> PoincareMap::operator()(const SectionState& like, const Eigen::VectorXd& z,
                                                   Eigen::VectorXd& out) {
  SectionState p = like;
  p.z = z;
  const MapStep s = apply(p);
  if (s.failure) return s.failure->text();
  out = s.next.z;
  return std::nullopt;
}

SectionWalk::SectionWalk(const WheelParams& w, const SimulationOptions& options, Model model, Section section)
    : map_(w, options, model, section) {}
SectionWalk::~SectionWalk() = default;
SectionWalk::SectionWalk(SectionWalk&&) noexcept = default;

std::optional<Failure> SectionWalk::to_section(const SimulationResult& r, const SectionHit& hit, SectionState& out) {
  const Section section = map_.section();
  if (hit.leg < 0) return Failure{FailureReason::SectionNotReached, std::string(name_of(section)), {}};
  if (auto e = reduce_crossing(map_.params(), section, hit, out))
    return Failure{FailureReason::IrreducibleCrossing, *e, {}};
  // The next run starts at the crossing: at a touchdown the landing is its first event (and the
  // landing leg its stance leg, as in a continuous run); at the upright crossing no event.
  next_ = RunSpec{};
  next_.y0 = hit.state;
  next_.contacts = hit.contacts;
  if (section == Section::Touchdown)
    next_.pending = {{hit.leg, EventKind::Touchdown}};
  else
    next_.stance_leg = r.last_step.stance_leg;
  next_.stop_at = section;
  next_.steps = 3;  // a cycle holds one touchdown (upright) or none (touchdown), as the map's
  point_ = out;
  return std::nullopt;
}

void SectionWalk::start_at(const SectionState& point) {
  point_ = point;
  if (map_.model() == Model::Rigid) return;
  next_ = section_run(map_.params(), point);
  next_.stop_at = map_.section();
  next_.steps = 3;
}

std::optional<Failure> SectionWalk::settle(const InitialState& initial, int transient_steps, SectionState& out) {
  const WheelParams& w = map_.params();
  out.model = map_.model();
  out.section = map_.section();
  if (map_.model() == Model::Rigid) {
    SimulationOptions o = map_.options();
    o.steps = std::max(1, transient_steps);
    const SimulationResult r = simulate_rigid(w, initial, o);
    if (r.failure) return r.failure;
    out.z = Eigen::VectorXd::Constant(1, r.final_state[5]);  // ω⁺ after the last impact
    if (out.section == Section::Upright) {
      SimulationOptions o2 = o;
      o2.steps = 2;
      const SimulationResult u = simulate_rigid(w, InitialState{out.z(0), -w.alpha()}, o2, Section::Upright);
      if (u.failure) return u.failure;
      out.z(0) = u.final_state[5];
    }
    point_ = out;
    return std::nullopt;
  }
  RunSpec first = default_run(w, initial);
  first.steps = std::max(1, transient_steps);
  FlexibleWheelSimulator& sim = *map_.simulator();
  const SimulationResult r = sim.run(first);
  if (r.failure) {  // an infeasible start is no failure of the transient: its reason alone
    if (r.failure->reason == FailureReason::InitialFootBelowGround) return r.failure;
    return r.failure->in_stage("transient");
  }
  RunSpec next;
  next.y0 = r.final_state;
  next.contacts = r.final_contacts;
  next.stance_leg = r.steps.empty() ? -1 : r.steps.back().stance_leg;
  next.stop_at = out.section;
  next.steps = 3;
  SectionHit hit;
  const SimulationResult r2 = sim.run(next, &hit);
  if (r2.failure) return r2.failure->in_stage("reaching the section");
  return to_section(r2, hit, out);
}

MapStep SectionWalk::step() {
  if (map_.model() == Model::Rigid) {
    MapStep s = map_.apply(point_, false);
    if (!s.failure) point_ = s.next;
    return s;
  }
  MapStep out;
  out.next = point_;
  if (next_.y0.empty()) throw std::logic_error("SectionWalk::step before settle or start_at");
  SectionHit hit;
  hit.leg = -1;
  const RunSpec spec = next_;
  const SimulationResult r = map_.simulator()->run(spec, &hit);
  if (r.failure) {
    // a start_at point with a foot below the ground, as the map's
    out.failure = r.failure->reason == FailureReason::InitialFootBelowGround
                      ? r.failure->in_stage("infeasible section point")
                      : *r.failure;
    return out;
  }
  if (auto f = to_section(r, hit, out.next)) {
    out.failure = f;
    return out;
  }
  using S = StateIndex;
  out.period = hit.t;
  out.distance = hit.state[S::x] - spec.y0[S::x];
  out.dissipated = hit.state[S::w_damp] + hit.state[S::w_fric] - spec.y0[S::w_damp] - spec.y0[S::w_fric];
  out.jams = r.jams;
  out.gait = cycle_gait(map_.section(), r);
  return out;
}

std::optional<Failure> settle_on_section(const WheelParams& w, const SimulationOptions& options, Model model,
                                         Section section, const InitialState& initial, int transient_steps,
                                         SectionState& out) {
  SectionWalk walk(w, options, model, section);
  return walk.settle(initial, transient_steps, out);
}

}  // namespace flexgait::rimless
