#include "flexgait/rimless/gait_branch_maps.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "flexgait/core/text.hpp"
#include "flexgait/rimless/sweep.hpp"

namespace flexgait::rimless::detail {

Config MapCache::config_at(double p) const {
  return sweep_point_config(base, SweepSpec{spec.param, p, p, 1}, 0);
}

WheelParams MapCache::wheel_at(double q) const {
  return wheel_from_config(config_at(value(q)));
}

bool MapCache::valid(double q) const {
  try {
    config_at(value(q));
    return true;
  } catch (const ConfigError&) {
    return false;
  }
}

PoincareMap* MapCache::at(double q, std::string& why) {
  for (auto& [key, map] : maps)
    if (key == q) return map.get();
  try {
    const Config c = config_at(value(q));
    maps.emplace_back(q,
                      std::make_unique<PoincareMap>(wheel_from_config(c), map_options(sim, opt), model, spec.section));
    if (const auto d = direction_at(q)) maps.back().second->set_parameter(*d);
  } catch (const ConfigError& e) {
    why = fmt::format("{} = {} is not valid: {}", spec.param, format_number(value(q)), e.what());
    return nullptr;
  }
  if (maps.size() > 4) maps.pop_front();
  return maps.back().second.get();
}

std::optional<ParameterDirection> MapCache::direction_at(double q) const {
  // Not for a key the map's wheel does not depend on (an initial state's, a solver's).
  if (!spec.parameter_sensitivity || !spec.param.starts_with("rimless.")) return std::nullopt;
  const double width = std::abs(spec.to - spec.from);
  const double hq = spec.tuning.parameter_step * std::max(std::abs(value(q)), width) / width;
  try {
    const double up = q + hq, down = q - hq;
    return ParameterDirection{wheel_at(up), wheel_at(down), 0.5 * (up - down)};
  } catch (const ConfigError&) {
    return std::nullopt;  // e.g. at a bound of the key: ∂P/∂q by central differences of the map
  }
}

namespace {

/// The map at q (null when q's value is not valid: `why`) and the section point in like's mode at z.
PoincareMap* map_and_point(MapCache& cache, const SectionState& like, const Eigen::VectorXd& z, double q,
                           SectionState& pt, std::string& why) {
  pt = like;
  pt.z = z;
  return cache.at(q, why);
}

}  // namespace

/// The family of maps in q with the discrete section mode of `like`.
numerics::MapFamily family_in_mode(const std::shared_ptr<MapCache>& cache, const SectionState& like, bool exact) {
  numerics::MapFamily family;
  family.valid = [cache](double q) { return cache->valid(q); };
  family.map = [cache, like](const Eigen::VectorXd& z, double q, Eigen::VectorXd& o) -> std::optional<std::string> {
    std::string why;
    SectionState pt;
    PoincareMap* m = map_and_point(*cache, like, z, q, pt, why);
    if (m == nullptr) return why;
    const MapStep s = m->apply(pt);
    if (s.failure) {
      if (s.next.z.size() > 0 && (s.next.flight != like.flight || s.next.mode != like.mode)) {
        cache->arrived = s.next;
        cache->arrived_q = q;
      }
      return s.failure->text();
    }
    o = s.next.z;
    return std::nullopt;
  };
  family.label = [cache, like](const Eigen::VectorXd& z, double q) -> std::string {
    std::string why;
    SectionState pt;
    PoincareMap* m = map_and_point(*cache, like, z, q, pt, why);
    if (m == nullptr) return "invalid";
    const MapStep s = m->apply(pt);
    return s.failure ? "failed" : s.gait;
  };
  if (exact) {
    family.state_jacobian = [cache, like](const Eigen::VectorXd& z, double q,
                                          Eigen::MatrixXd& J) -> std::optional<std::string> {
      std::string why;
      SectionState pt;
      PoincareMap* m = map_and_point(*cache, like, z, q, pt, why);
      return m == nullptr ? std::optional<std::string>(why) : m->jacobian(pt, J);
    };
    // ∂P/∂q by sensitivity from the same run where the map has its parameter direction;
    // otherwise differences of the map in q (as numerics::continuation would).
    const numerics::MapFamily plain = family;
    family.jacobians = [cache, like, plain](const Eigen::VectorXd& z, double q, Eigen::MatrixXd& J,
                                            Eigen::VectorXd& J_p) -> std::optional<std::string> {
      std::string why;
      SectionState pt;
      PoincareMap* m = map_and_point(*cache, like, z, q, pt, why);
      if (m == nullptr) return why;
      if (m->has_parameter()) return m->jacobian_and_parameter_derivative(pt, J, J_p);
      if (auto e = m->jacobian(pt, J)) return e;  // m is not used below (the cache may drop it)
      return numerics::parameter_derivative(plain, z, q,
                                            cache->opt.newton.fd_relative_step * std::max(std::abs(q), 1.0), J_p);
    };
  }
  return family;
}

/// The family of P^k (k = the spec's period) starting and ending in the mode of `like`. The k - 1
/// crossings in between may arrive in any mode (a period-k orbit's section points need not share
/// theirs), so P^k has no exact Jacobian (the variational one holds the mode): central differences.
numerics::MapFamily family_for(const std::shared_ptr<MapCache>& cache, const SectionState& like, bool exact) {
  const int k = cache->spec.period;
  if (k == 1) return family_in_mode(cache, like, exact);
  const auto steps = [cache, like, k](const Eigen::VectorXd& z, double q, SectionState& end,
                                      std::string& gait) -> std::optional<std::string> {
    std::string why;
    PoincareMap* m = cache->at(q, why);
    if (m == nullptr) return why;
    end = like;
    end.z = z;
    for (int i = 0; i < k; ++i) {
      const MapStep s = m->apply(end, false);
      if (s.failure) return fmt::format("step {} of {}: {}", i + 1, k, s.failure->text());
      gait += (i > 0 ? " / " : "") + s.gait;
      end = s.next;
    }
    return std::nullopt;
  };
  numerics::MapFamily family;
  family.period = k;
  family.valid = [cache](double q) { return cache->valid(q); };
  family.map = [cache, like, steps, k](const Eigen::VectorXd& z, double q,
                                       Eigen::VectorXd& o) -> std::optional<std::string> {
    SectionState end;
    std::string gait;
    if (auto e = steps(z, q, end, gait)) return e;
    if (end.flight != like.flight || end.mode != like.mode) {
      cache->arrived = end;
      cache->arrived_q = q;
      return fmt::format("arrived at the section after {} steps in another mode ({} instead of {})", k, mode_text(end),
                         mode_text(like));
    }
    o = end.z;
    return std::nullopt;
  };
  family.label = [steps](const Eigen::VectorXd& z, double q) -> std::string {
    SectionState end;
    std::string gait;
    return steps(z, q, end, gait) ? "failed" : gait;
  };
  return family;
}

/// Carries the branch across a change of the section's mode after `from` ended at its last point
/// (mode `to` is where the map arrived). Returns the new segment's start (the new mode's end at
/// the boundary), or why the branch ends there.
std::optional<std::string> cross_section_mode(const std::shared_ptr<MapCache>& cache, const Segment& from,
                                              const SectionState& to, bool exact,
                                              const numerics::ContinuationOptions& o, numerics::BranchPoint& start) {
  const numerics::BranchPoint& a = from.branch.points.back();
  const double qa = a.p;
  const Eigen::Index n = a.z.size();
  if (!(a.tangent.size() == n + 1 && a.tangent(n) > 0))
    return std::string("the branch heads back (after a fold) where the section's mode changes");
  SectionState old = from.like;
  old.z = a.z;
  SectionState guess = in_mode(cache->wheel_at(qa), old, to);
  const numerics::MapFamily g = family_for(cache, to, exact);
  // Newton in the new mode a little beyond the boundary (the end is within the difference step of it).
  numerics::BranchPoint beyond;
  std::string why = "no step";
  bool found = false;
  const GaitContinuationOptions& tuning = cache->spec.tuning;
  for (const double dq : tuning.mode_probes) {
    if (qa + dq > 1.0) break;
    if (auto e = numerics::fixed_point_at(g, guess.z, qa + dq, o, beyond)) {
      why = *e;
      continue;
    }
    found = true;
    break;
  }
  if (!found) return fmt::format("no fixed point in the new mode ({}) next to it: {}", mode_text(to), why);
  // Back to the boundary in the new mode: the new segment's own end there.
  numerics::ContinuationOptions back = o;
  back.detect = false;
  back.max_points = tuning.back_max_points;
  back.initial_step = std::min(o.initial_step, 0.5 * (beyond.p - qa));
  const numerics::Branch b =
      numerics::continue_fixed_points(g, beyond.z, beyond.p, std::max(0.0, qa - tuning.back_distance), back);
  if (b.start_failure || b.points.empty()) return "continuing the new mode back to the boundary: " + b.failure();
  const numerics::BranchPoint& end = b.points.back();
  // Continuous: both ends meet (to join_tolerance, a few difference steps, in q and in the scaled states).
  const Eigen::VectorXd scale = to.scale(cache->wheel_at(end.p));
  const double gap_q = std::abs(end.p - qa);
  const double gap_z = (end.z - guess.z).cwiseQuotient(scale).lpNorm<Eigen::Infinity>();
  if (gap_q > tuning.join_tolerance || gap_z > tuning.join_tolerance)
    return fmt::format(
        "the fixed point is not continuous there: the new mode's ({}) branch ends at {} = {} with a "
        "state {} (scaled) away ({})",
        mode_text(to), cache->spec.param, format_number(cache->value(end.p)), format_number(gap_z), b.stop_reason);
  start = end;
  return std::nullopt;
}

}  // namespace flexgait::rimless::detail
