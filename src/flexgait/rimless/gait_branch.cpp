#include "flexgait/rimless/gait_branch.hpp"

#include <fmt/format.h>

#include <cmath>
#include <deque>
#include <memory>

#include "flexgait/core/text.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/sweep.hpp"

namespace flexgait::rimless {
namespace {

/// Poincaré maps at the last few parameter values (a corrector step evaluates at p and p ± h_p).
struct MapCache {
  Config base;
  GaitContinuationSpec spec;
  SimulationOptions sim;
  AnalysisOptions opt;
  Model model;
  std::deque<std::pair<double, std::unique_ptr<PoincareMap>>> maps;

  double value(double q) const { return spec.from + q * (spec.to - spec.from); }
  Config config_at(double p) const { return sweep_point_config(base, SweepSpec{spec.param, p, p, 1}, 0); }
  /// The map at q, or why the parameter value is not valid.
  PoincareMap* at(double q, std::string& why) {
    for (auto& [key, map] : maps)
      if (key == q) return map.get();
    try {
      const Config c = config_at(value(q));
      maps.emplace_back(q, std::make_unique<PoincareMap>(wheel_from_config(c), map_options(sim, opt), model, spec.section));
    } catch (const ConfigError& e) {
      why = fmt::format("{} = {} is not valid: {}", spec.param, format_number(value(q)), e.what());
      return nullptr;
    }
    if (maps.size() > 4) maps.pop_front();
    return maps.back().second.get();
  }
};

}  // namespace

GaitBranch continue_gait(const Config& base, const GaitContinuationSpec& spec) {
  check_sweep_param(base.schema(), spec.param);
  if (!(spec.from != spec.to) || !std::isfinite(spec.from) || !std::isfinite(spec.to))
    throw ConfigError("--to", fmt::format("the interval is empty: --from {} --to {}", spec.from, spec.to));
  if (spec.step < 0 || spec.step > std::abs(spec.to - spec.from))
    throw ConfigError("--step", fmt::format("--step {} is not in (0, |to - from|]", spec.step));
  auto cache = std::make_shared<MapCache>();
  cache->base = base;
  cache->spec = spec;
  const Config start_config = cache->config_at(spec.from);
  cache->config_at(spec.to);  // throws when the end is not a valid value
  cache->sim = simulation_from_config(start_config);
  cache->opt = analysis_from_config(start_config);
  cache->model = cache->sim.model;

  GaitBranch out;
  out.param = spec.param;
  const WheelParams w0 = wheel_from_config(start_config);
  const FixedPointReport start = find_fixed_point(w0, cache->sim, cache->opt, cache->model, spec.section,
                                                  initial_from_config(start_config));
  out.state_names = start.point.names();
  out.mode = start.point.flight ? "flight" : mode_name(start.point.mode);
  if (!start.converged) {
    out.failure = fmt::format("no fixed point at {} = {}: {}", spec.param, format_number(spec.from), start.failure);
    return out;
  }
  const SectionState like = start.point;
  numerics::MapFamily family;
  family.map = [cache, like](const Eigen::VectorXd& z, double q, Eigen::VectorXd& o) -> std::optional<std::string> {
    std::string why;
    PoincareMap* m = cache->at(q, why);
    if (m == nullptr) return why;
    return (*m)(like, z, o);
  };
  family.label = [cache, like](const Eigen::VectorXd& z, double q) -> std::string {
    std::string why;
    PoincareMap* m = cache->at(q, why);
    if (m == nullptr) return "invalid";
    SectionState pt = like;
    pt.z = z;
    const MapStep s = m->apply(pt);
    return s.failure ? "failed" : s.gait;
  };
  if (start.jacobian_exact) {
    out.exact_jacobian = true;
    family.state_jacobian = [cache, like](const Eigen::VectorXd& z, double q, Eigen::MatrixXd& J) -> std::optional<std::string> {
      std::string why;
      PoincareMap* m = cache->at(q, why);
      if (m == nullptr) return why;
      SectionState pt = like;
      pt.z = z;
      return m->jacobian(pt, J);
    };
  }
  numerics::ContinuationOptions o;
  const double width = std::abs(spec.to - spec.from);
  o.initial_step = spec.step > 0 ? spec.step / width : 0.02;
  o.max_step = 2 * o.initial_step;
  o.min_step = 1e-9;
  o.max_points = spec.max_points;
  o.tolerance = cache->opt.newton.tolerance;
  o.fd_relative_step = cache->opt.newton.fd_relative_step;
  o.state_scale = like.scale(w0);
  o.parameter_scale = 1;
  o.locate_tolerance = 1e-9;
  o.label_tolerance = 1e-7;  // in q: |Δp| <= 1e-7 |to - from|
  out.branch = numerics::continue_fixed_points(family, start.point.z, 0.0, 1.0, o);
  if (!out.branch.failure.empty()) {
    out.failure = out.branch.failure;
    return out;
  }

  // Rows: points and special points in the order of arclength, each with its step's quantities.
  std::vector<std::pair<numerics::BranchPoint, std::string>> ordered;
  std::size_t k = 0;
  for (std::size_t i = 0; i < out.branch.points.size(); ++i) {
    ordered.emplace_back(out.branch.points[i], i == 0 ? "start" : "");
    for (; k < out.branch.special.size() && out.branch.special[k].after == i; ++k) {
      const auto& sp = out.branch.special[k];
      std::string ev = numerics::to_string(sp.kind);
      if (sp.kind == numerics::SpecialKind::LabelChange)
        ev = fmt::format("gait {} -> {}", sp.label_before, sp.label_after);
      ordered.emplace_back(sp.point, ev);
    }
  }
  out.stop_reason = out.branch.reached_end
                        ? fmt::format("reached {} = {}", spec.param, format_number(spec.to))
                        : fmt::format("ended at {} = {} (q = (p - from)/(to - from) = {}): {}", spec.param,
                                      format_number(cache->value(out.branch.points.back().p)),
                                      format_number(out.branch.points.back().p), out.branch.stop_reason);
  if (!out.branch.reached_end) ordered.back().second = "end: " + out.stop_reason;
  for (auto& [pt, ev] : ordered) {
    GaitBranchRow r;
    r.p = cache->value(pt.p);
    r.event = ev;
    std::string why;
    if (PoincareMap* m = cache->at(pt.p, why)) {
      SectionState s = like;
      s.z = pt.z;
      const MapStep step = m->apply(s);
      if (!step.failure) {
        r.gait = step.gait;
        r.period = step.period;
        r.speed = step.period > 0 ? step.distance / step.period : 0.0;
        r.dissipated = step.dissipated;
      }
    }
    r.point = std::move(pt);
    out.rows.push_back(std::move(r));
  }
  return out;
}

std::string gait_branch_csv(const GaitBranch& b) {
  std::vector<std::string> cols{"parameter"};
  for (const auto& n : b.state_names) cols.push_back(n);
  for (const char* c : {"mode", "period", "speed", "dissipated_per_step", "gait"}) cols.emplace_back(c);
  for (std::size_t k = 0; k < b.state_names.size(); ++k) {
    cols.push_back(fmt::format("abs_lambda_{}", k + 1));
    cols.push_back(fmt::format("arg_lambda_{}", k + 1));
  }
  for (const char* c : {"stable", "residual", "event"}) cols.emplace_back(c);
  CsvWriter csv(cols);
  for (const GaitBranchRow& r : b.rows) {
    csv.cell(r.p);
    for (Eigen::Index i = 0; i < r.point.z.size(); ++i) csv.cell(r.point.z(i));
    csv.cell(b.mode).cell(r.period).cell(r.speed).cell(r.dissipated).cell(r.gait);
    for (std::size_t k = 0; k < b.state_names.size(); ++k) {
      const bool has = k < r.point.multipliers.size();
      csv.cell(has ? std::abs(r.point.multipliers[k]) : NAN).cell(has ? std::arg(r.point.multipliers[k]) : NAN);
    }
    csv.cell(r.point.stable ? "true" : "false").cell(r.point.residual).cell(r.event);
    csv.end_row();
  }
  return csv.str();
}

}  // namespace flexgait::rimless
