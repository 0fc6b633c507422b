#include "flexgait/rimless/fixed_point.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

namespace flexgait::rimless {

SimulationOptions map_options(const SimulationOptions& sim, const AnalysisOptions& opt) {
  SimulationOptions o = sim;
  o.rtol = opt.rtol;
  o.atol = opt.atol;
  o.log = false;
  return o;
}

FixedPointReport find_fixed_point_from(const WheelParams& w, const SimulationOptions& sim, const AnalysisOptions& opt,
                                       const SectionState& guess) {
  FixedPointReport rep;
  rep.point = guess;
  PoincareMap map(w, map_options(sim, opt), guess.model, guess.section);
  const numerics::VectorMap P = [&](const Eigen::VectorXd& z, Eigen::VectorXd& out) { return map(guess, z, out); };
  const numerics::NewtonResult nr = numerics::newton_fixed_point(P, guess.z, guess.scale(w), opt.newton);
  rep.converged = nr.converged;
  rep.failure = nr.failure;
  rep.iterations = nr.iterations;
  rep.residual = nr.residual;
  rep.history = nr.history;
  rep.point.z = nr.z;
  rep.jacobian_fd = nr.jacobian;
  rep.jacobian = nr.jacobian;
  if (nr.converged) {
    Eigen::MatrixXd exact;
    if (auto why = map.jacobian(rep.point, exact)) {
      rep.jacobian_note = *why;
    } else {
      rep.jacobian = exact;
      rep.jacobian_exact = true;
      rep.jacobian_difference = (exact - nr.jacobian).lpNorm<Eigen::Infinity>();
    }
  }
  if (rep.jacobian.size() > 0) {
    rep.multipliers = numerics::floquet_multipliers(rep.jacobian);
    rep.multipliers_fd = numerics::floquet_multipliers(rep.jacobian_fd);
    rep.stable = nr.converged;
    for (const auto& m : rep.multipliers) rep.stable = rep.stable && std::abs(m) < 1.0;
  }
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
    rep.failure = "no initial guess: " + *e;
    return rep;
  }
  return find_fixed_point_from(w, sim, opt, guess);
}

std::string fixed_point_json(const FixedPointReport& r) {
  nlohmann::ordered_json j;
  j["converged"] = r.converged;
  j["iterations"] = r.iterations;
  j["residual"] = r.residual;
  j["model"] = r.point.model == Model::Rigid ? "rigid" : "flexible";
  j["section"] = std::string(name_of(r.point.section));
  j["mode"] = r.point.flight ? "flight" : mode_name(r.point.mode);
  j["state_names"] = r.point.names();
  j["state"] = std::vector<double>(r.point.z.data(), r.point.z.data() + r.point.z.size());
  nlohmann::ordered_json mult = nlohmann::ordered_json::array();
  for (const auto& m : r.multipliers) mult.push_back({m.real(), m.imag()});
  j["multipliers"] = mult;
  nlohmann::ordered_json mult_fd = nlohmann::ordered_json::array();
  for (const auto& m : r.multipliers_fd) mult_fd.push_back({m.real(), m.imag()});
  j["multipliers_fd"] = mult_fd;
  j["jacobian_exact"] = r.jacobian_exact;
  j["jacobian_difference"] = r.jacobian_difference;
  if (!r.jacobian_note.empty()) j["jacobian_note"] = r.jacobian_note;
  j["stable"] = r.stable;
  j["gait"] = r.gait;
  j["period"] = r.period;
  j["speed"] = r.speed;
  j["dissipated_per_cycle"] = r.dissipated;
  nlohmann::ordered_json hist = nlohmann::ordered_json::array();
  for (const auto& h : r.history)
    hist.push_back({{"iteration", h.iteration}, {"residual", h.residual}, {"step", h.step_norm}, {"damping", h.damping}});
  j["history"] = hist;
  j["failure"] = r.failure.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.failure);
  return j.dump(2) + "\n";
}

}  // namespace flexgait::rimless
