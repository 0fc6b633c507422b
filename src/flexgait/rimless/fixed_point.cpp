#include "flexgait/rimless/fixed_point.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "flexgait/core/record_json.hpp"
#include "flexgait/numerics/continuation.hpp"

namespace flexgait::rimless {

SimulationOptions map_options(const SimulationOptions& sim, const AnalysisOptions& opt) {
  SimulationOptions o = sim;
  o.rtol = opt.rtol;
  o.atol = opt.atol;
  o.log = false;
  return o;
}

namespace {

/// Newton with the variational ∂P/∂z (numerics::fixed_point_at), which evaluates the map at its
/// iterates only: near a boundary of the section's mode (docs/guide/rimless.md, "Orbit diagram and basin of
/// attraction") a central-difference step leaves
/// the mode and the map fails there, while the fixed point is still inside it. Replaces `nr` when
/// it converges (its Jacobian then the exact one; no history).
void newton_with_exact_jacobian(PoincareMap& map, const SectionState& guess, const WheelParams& w,
                                const AnalysisOptions& opt, numerics::NewtonResult& nr) {
  Eigen::MatrixXd probe;
  if (guess.model != Model::Flexible || map.jacobian(guess, probe)) return;  // no exact Jacobian here
  numerics::MapFamily f;
  f.map = [&](const Eigen::VectorXd& z, double, Eigen::VectorXd& out) { return map(guess, z, out); };
  f.state_jacobian = [&](const Eigen::VectorXd& z, double, Eigen::MatrixXd& J) {
    SectionState at = guess;
    at.z = z;
    return map.jacobian(at, J);
  };
  f.jacobians = [&](const Eigen::VectorXd& z, double p, Eigen::MatrixXd& J, Eigen::VectorXd& J_p) {
    J_p = Eigen::VectorXd::Zero(z.size());  // no parameter here
    return f.state_jacobian(z, p, J);
  };
  numerics::ContinuationOptions o;
  o.tolerance = opt.newton.tolerance;
  o.max_corrector_iterations = opt.newton.max_iterations;
  o.state_scale = guess.scale(w);
  numerics::BranchPoint b;
  if (numerics::fixed_point_at(f, guess.z, 0.0, o, b)) return;
  nr.converged = true;
  nr.failure_detail.clear();
  nr.failure_reason.reset();
  nr.z = b.z;
  nr.residual = b.residual;
  nr.iterations = b.corrector_iterations;
  nr.jacobian = b.jacobian;
}

}  // namespace

std::string FixedPointReport::failure() const {
  if (transient_failure) return transient_failure->in_stage("no initial guess").text();
  if (newton_failure) return numerics::newton_failure_text(*newton_failure, newton_failure_detail);
  return {};
}

FixedPointReport find_fixed_point_from(const WheelParams& w, const SimulationOptions& sim, const AnalysisOptions& opt,
                                       const SectionState& guess) {
  FixedPointReport rep;
  rep.point = guess;
  PoincareMap map(w, map_options(sim, opt), guess.model, guess.section);
  const numerics::VectorMap P = [&](const Eigen::VectorXd& z, Eigen::VectorXd& out) { return map(guess, z, out); };
  numerics::NewtonResult nr = numerics::newton_fixed_point(P, guess.z, guess.scale(w), opt.newton);
  if (!nr.converged) newton_with_exact_jacobian(map, guess, w, opt, nr);
  rep.converged = nr.converged;
  if (!nr.converged) {
    rep.newton_failure = nr.failure_reason;
    rep.newton_failure_detail = nr.failure_detail;
  }
  rep.iterations = nr.iterations;
  rep.residual = nr.residual;
  rep.history = nr.history;
  rep.point.z = nr.z;
  // A failed search has no Jacobian to speak of (Newton's may stop half-filled when a difference
  // step fails): multipliers, stability and the cycle's figures belong to a fixed point only.
  if (!nr.converged) return rep;
  rep.jacobian_fd = nr.jacobian;
  rep.jacobian = nr.jacobian;
  Eigen::MatrixXd exact;
  if (auto why = map.jacobian(rep.point, exact)) {
    rep.jacobian_note = *why;
  } else {
    rep.jacobian = exact;
    rep.jacobian_exact = true;
    rep.jacobian_difference = (exact - nr.jacobian).lpNorm<Eigen::Infinity>();
  }
  rep.multipliers = numerics::floquet_multipliers(rep.jacobian);
  rep.multipliers_fd = numerics::floquet_multipliers(rep.jacobian_fd);
  rep.stable = true;
  for (const auto& m : rep.multipliers) rep.stable = rep.stable && std::abs(m) < 1.0;
  const MapStep step = map.apply(rep.point);
  if (!step.failure) {
    rep.gait = step.gait;
    rep.period = step.period;
    rep.speed = step.period > 0 ? step.distance / step.period : 0.0;
    rep.dissipated = step.dissipated;
  }
  return rep;
}

FixedPointReport find_fixed_point(const WheelParams& w, const SimulationOptions& sim, const AnalysisOptions& opt,
                                  Model model, Section section, const InitialState& initial) {
  SectionState guess;
  if (auto e = settle_on_section(w, map_options(sim, opt), model, section, initial, opt.transient_steps, guess)) {
    FixedPointReport rep;
    rep.point = guess;
    rep.transient_failure = e;
    return rep;
  }
  return find_fixed_point_from(w, sim, opt, guess);
}

nlohmann::ordered_json fixed_point_record(const FixedPointReport& r) {
  nlohmann::ordered_json j;
  j["converged"] = r.converged;
  j["iterations"] = r.iterations;
  j["residual"] = r.residual;
  j["model"] = r.point.model == Model::Rigid ? "rigid" : "flexible";
  j["section"] = std::string(name_of(r.point.section));
  j["mode"] = r.point.flight ? "flight" : mode_name(r.point.mode);
  j["state_names"] = r.point.names();
  const std::vector<double> z(r.point.z.data(), r.point.z.data() + r.point.z.size());
  // Figures of a fixed point: null when the search failed (never numbers of no meaning).
  auto if_converged = [&](auto value) {
    return r.converged ? nlohmann::ordered_json(value) : nlohmann::ordered_json();
  };
  auto pairs = [](const std::vector<std::complex<double>>& ms) {
    nlohmann::ordered_json a = nlohmann::ordered_json::array();
    for (const auto& m : ms) a.push_back({m.real(), m.imag()});
    return a;
  };
  j["state"] = if_converged(z);
  if (!r.converged && !z.empty()) j["last_iterate"] = z;
  j["multipliers"] = if_converged(pairs(r.multipliers));
  j["multipliers_fd"] = if_converged(pairs(r.multipliers_fd));
  j["jacobian_exact"] = r.jacobian_exact;
  j["jacobian_difference"] = r.jacobian_difference;
  if (!r.jacobian_note.empty()) j["jacobian_note"] = r.jacobian_note;
  j["stable"] = r.stable;
  j["gait"] = if_converged(r.gait);
  j["period"] = if_converged(r.period);
  j["speed"] = if_converged(r.speed);
  j["dissipated_per_cycle"] = if_converged(r.dissipated);
  nlohmann::ordered_json hist = nlohmann::ordered_json::array();
  for (const auto& h : r.history)
    hist.push_back(
        {{"iteration", h.iteration}, {"residual", h.residual}, {"step", h.step_norm}, {"damping", h.damping}});
  j["history"] = hist;
  const std::string failure = r.failure();
  j["failure"] = failure.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(failure);
  return j;
}

std::string fixed_point_json(const FixedPointReport& r) {
  return json_file_text(fixed_point_record(r));
}

}  // namespace flexgait::rimless
