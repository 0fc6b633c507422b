#include "flexgait/rimless/gait_branch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "flexgait/core/text.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/gait_branch_maps.hpp"
#include "flexgait/rimless/sweep.hpp"

namespace flexgait::rimless {
namespace {

using detail::cross_section_mode;
using detail::family_for;
using detail::MapCache;
using detail::Segment;

numerics::ContinuationOptions continuation_options(const GaitContinuationSpec& spec, const AnalysisOptions& a) {
  const GaitContinuationOptions& t = spec.tuning;
  numerics::ContinuationOptions o;
  const double width = std::abs(spec.to - spec.from);
  o.initial_step = spec.step > 0 ? spec.step / width : t.initial_step;
  o.max_step = t.max_step_factor * o.initial_step;
  o.min_step = t.min_step;
  o.max_points = t.max_points;
  o.tolerance = a.newton.tolerance;
  o.fd_relative_step = a.newton.fd_relative_step;
  o.parameter_scale = 1;
  o.locate_tolerance = t.locate_tolerance;
  o.label_tolerance = t.label_tolerance;  // in q: |Δp| <= label_tolerance |to - from|
  if (spec.on_point) o.on_point = [on_point = spec.on_point](const numerics::BranchPoint& b) { on_point(b.p); };
  return o;
}

void assemble(const std::shared_ptr<MapCache>& cache, const std::vector<Segment>& segments, const std::string& end_note,
              GaitBranch& out);

/// The branch from `like` (a fixed point of P^k at q = 0) into `out`: its segments, one per section
/// mode, joined where the fixed point is continuous across the change, and its rows.
void build(const std::shared_ptr<MapCache>& cache, SectionState like, numerics::ContinuationOptions o,
           GaitBranch& out) {
  const GaitContinuationSpec& spec = cache->spec;
  const WheelParams w0 = cache->wheel_at(0.0);
  std::vector<Segment> segments;
  double q0 = 0;
  std::string boundary, end_note;
  int points = 0;
  for (;;) {
    cache->arrived.reset();
    const numerics::MapFamily f = family_for(cache, like, out.exact_jacobian);
    o.state_scale = like.scale(w0);
    o.max_points = spec.tuning.max_points - points;
    Segment seg{like, numerics::continue_fixed_points(f, like.z, q0, 1.0, o), boundary};
    if (seg.branch.start_failure) {
      if (segments.empty()) {
        out.failure = seg.branch.failure();
        return;
      }
      end_note = fmt::format("the section's mode changes to {} but the new segment does not start: {}", mode_text(like),
                             seg.branch.failure());
      break;
    }
    points += static_cast<int>(seg.branch.points.size());
    segments.push_back(std::move(seg));
    const Segment& last = segments.back();
    // A change of the section's mode ends the segment when the map arrived in another mode next to
    // its last point (within the parameter's difference step; earlier such failures were passed).
    if (last.branch.reached_end || !cache->arrived || points >= spec.tuning.max_points ||
        std::abs(cache->arrived_q - last.branch.points.back().p) > spec.tuning.mode_change_distance)
      break;
    const SectionState to = *cache->arrived;
    numerics::BranchPoint next;
    if (auto e = cross_section_mode(cache, last, to, out.exact_jacobian, o, next)) {
      end_note = fmt::format("the section's foot mode changes from {} to {} here and {}", mode_text(last.like),
                             mode_text(to), *e);
      break;
    }
    boundary = fmt::format("section mode {} -> {}", mode_text(last.like), mode_text(to));
    like = to;
    like.z = next.z;
    q0 = next.p;
  }
  assemble(cache, segments, end_note, out);
}

/// Joins `segments` into out.branch and out.rows (points and special points in the order of
/// arclength, each with its cycle's quantities: k applications of the map for period k).
void assemble(const std::shared_ptr<MapCache>& cache, const std::vector<Segment>& segments, const std::string& end_note,
              GaitBranch& out) {
  const GaitContinuationSpec& spec = cache->spec;
  out.segments = static_cast<int>(segments.size());
  for (const Segment& seg : segments)
    if (seg.like.z.size() > static_cast<Eigen::Index>(out.state_names.size())) out.state_names = seg.like.names();

  // The joined branch, and the rows: points and special points in the order of arclength, each
  // with its step's quantities.
  out.branch.period = 1;
  double s_offset = 0;
  struct Ordered {
    numerics::BranchPoint point;
    std::string event;
    const Segment* segment;
  };
  std::vector<Ordered> ordered;
  for (const Segment& seg : segments) {
    const std::size_t offset = out.branch.points.size();
    std::size_t k = 0;
    for (std::size_t i = 0; i < seg.branch.points.size(); ++i) {
      numerics::BranchPoint pt = seg.branch.points[i];
      pt.arclength += s_offset;
      std::string ev = i > 0 ? "" : seg.boundary.empty() ? "start" : seg.boundary;
      if (i == 0 && !seg.boundary.empty() && !ordered.empty() && ordered.back().point.label != pt.label)
        ev += fmt::format(" (gait {} -> {})", ordered.back().point.label, pt.label);
      ordered.push_back({pt, ev, &seg});
      out.branch.points.push_back(pt);
      for (; k < seg.branch.special.size() && seg.branch.special[k].after == i; ++k) {
        numerics::SpecialPoint sp = seg.branch.special[k];
        sp.after += offset;
        sp.point.arclength += s_offset;
        ev = numerics::to_string(sp.kind);
        if (sp.kind == numerics::SpecialKind::LabelChange)
          ev = fmt::format("gait {} -> {}", sp.label_before, sp.label_after);
        ordered.push_back({sp.point, ev, &seg});
        out.branch.special.push_back(std::move(sp));
      }
    }
    s_offset = out.branch.points.back().arclength;
  }
  const numerics::Branch& tail = segments.back().branch;
  out.branch.reached_end = tail.reached_end;
  out.branch.end = tail.end;
  out.branch.stop_reason = tail.stop_reason;
  if (tail.end == numerics::BranchEnd::Vertical) {
    // The physical reason where it is the sliding gait's: μ_k = tan φ.
    const WheelParams w = cache->wheel_at(tail.points.back().p);
    const SectionState& m = segments.back().like;
    if (!m.flight && m.mode != FootMode::Stick &&
        std::abs(w.mu_k - std::tan(w.slope)) <= 1e-8 * std::max(1.0, w.mu_k)) {
      out.end = GaitBranchEnd::SlideBalance;
      out.branch.stop_reason = fmt::format(
          "mu_k = tan(slope) = {}: kinetic friction on the sliding foot balances gravity along the slope, so a slide "
          "at any speed is a gait (a multiplier +1, the branch vertical) and below it the slide accelerates: no gait; "
          "{}",
          format_number(std::tan(w.slope)), tail.stop_reason);
    }
  }
  if (!end_note.empty()) {
    out.end = GaitBranchEnd::ModeChangeNotContinued;
    out.branch.reached_end = false;
    out.branch.stop_reason = end_note + " (" + tail.stop_reason + ")";
  }
  out.stop_reason = out.branch.reached_end
                        ? fmt::format("reached {} = {}", spec.param, format_number(spec.to))
                        : fmt::format("ended at {} = {} (q = (p - from)/(to - from) = {}): {}", spec.param,
                                      format_number(cache->value(out.branch.points.back().p)),
                                      format_number(out.branch.points.back().p), out.branch.stop_reason);
  if (!out.branch.reached_end) ordered.back().event = "end: " + out.stop_reason;
  for (auto& [pt, ev, seg] : ordered) {
    GaitBranchRow r;
    r.p = cache->value(pt.p);
    r.event = ev;
    r.section = seg->like;
    r.section.z = pt.z;
    std::string why;
    const WheelParams w = cache->wheel_at(pt.p);
    SectionState widest = segments.front().like;
    for (const Segment& sg : segments)
      if (sg.like.z.size() == static_cast<Eigen::Index>(out.state_names.size())) widest = sg.like;
    r.state = in_mode(w, r.section, widest).z;
    if (PoincareMap* m = cache->at(pt.p, why)) {
      SectionState at = r.section;
      double period = 0, distance = 0, dissipated = 0;
      std::string gait;
      bool ok = true;
      for (int k = 0; k < out.period && ok; ++k) {
        const MapStep step = m->apply(at, out.period == 1);
        ok = !step.failure;
        period += step.period;
        distance += step.distance;
        dissipated += step.dissipated;
        gait += (k > 0 ? " / " : "") + step.gait;
        at = step.next;
      }
      if (ok) {
        r.gait = gait;
        r.period = period;
        r.speed = period > 0 ? distance / period : 0.0;
        r.dissipated = dissipated;
      }
    }
    r.point = std::move(pt);
    out.rows.push_back(std::move(r));
  }
}

/// The period-2k branch born at the first period doubling of `out` (Kuznetsov §10.3: the corrector
/// on P^{2k} along the critical eigenvector), continued towards q = 1 (or back to 0 when it lies on
/// that side), into out.switched.
void switch_at_first_period_doubling(const std::shared_ptr<MapCache>& cache, const numerics::ContinuationOptions& o,
                                     GaitBranch& out) {
  for (const GaitBranchRow& r : out.rows) {
    if (r.event != numerics::to_string(numerics::SpecialKind::PeriodDoubling)) continue;
    numerics::SpecialPoint pd;
    for (const auto& sp : out.branch.special)
      if (sp.kind == numerics::SpecialKind::PeriodDoubling && sp.point.p == r.point.p) pd = sp;
    const numerics::MapFamily f = family_for(cache, r.section, out.exact_jacobian);
    GaitBranch child;
    child.param = out.param;
    child.section = out.section;
    child.computed_at = out.computed_at;
    child.period = 2 * out.period;
    child.exact_jacobian = out.exact_jacobian;
    child.state_names = r.section.names();
    child.mode = mode_text(r.section);
    numerics::ContinuationOptions oc = o;
    oc.state_scale = r.section.scale(cache->wheel_at(r.point.p));
    numerics::Branch b = numerics::switch_at_period_doubling(f, pd, 1.0, oc);
    if (!b.start_failure && b.points.size() < 3 && b.end == numerics::BranchEnd::OtherSide && pd.point.p > 0)
      b = numerics::switch_at_period_doubling(f, pd, 0.0, oc);
    if (b.start_failure) {
      child.failure = fmt::format("no period-{} branch at the period doubling at {} = {}: {}", child.period, out.param,
                                  format_number(r.p), b.failure());
    } else {
      std::vector<Segment> one{Segment{r.section, std::move(b), ""}};
      one.front().like.z = pd.point.z;
      assemble(cache, one, "", child);
      if (!child.rows.empty())
        child.rows.front().event = fmt::format("period doubling of the period-{} branch", out.period);
    }
    out.switched.push_back(std::move(child));
    return;
  }
}

/// The value text of a scalar key, as config.yaml writes it (format_value).
std::string value_text(const Config& config, const ParamSpec& p) {
  switch (p.type) {
    case ParamType::Real:
      return format_value(config.real(p.key));
    case ParamType::Integer:
      return format_value(config.integer(p.key));
    case ParamType::Boolean:
      return format_value(config.boolean(p.key));
    case ParamType::Choice:
      return format_value(config.choice(p.key));
    case ParamType::Text:
      return format_value(config.text(p.key));
    case ParamType::List:
    case ParamType::Reals:
      break;
  }
  return {};
}

bool identifies_branch(const ParamSpec& p) {
  return (p.key == "sim.model" || p.key.starts_with("rimless.")) && p.type != ParamType::List &&
         p.type != ParamType::Reals;
}

}  // namespace

std::string branch_computed_at(const Config& config, const std::string& param) {
  const std::vector<std::string> varied = param_keys(config.schema(), param);
  std::string out;
  for (const ParamSpec& p : config.schema().params()) {
    if (!identifies_branch(p) || std::find(varied.begin(), varied.end(), p.key) != varied.end()) continue;
    out += (out.empty() ? "" : ";") + p.key + "=" + value_text(config, p);
  }
  return out;
}

std::vector<std::string> computed_at_differences(const std::string& recorded, const Config& config,
                                                 const std::string& param) {
  const std::vector<std::string> varied = param_keys(config.schema(), param);
  std::vector<std::string> out;
  for (const std::string& entry : split_text(recorded, ';')) {
    const std::optional<KeyValue> kv = split_key_value(entry);
    const std::string key = kv ? kv->key : entry;
    if (std::find(varied.begin(), varied.end(), key) != varied.end()) continue;
    const ParamSpec* p = kv ? config.schema().find(key) : nullptr;
    if (p == nullptr || !identifies_branch(*p)) {
      out.push_back(fmt::format("'{}' (not a key of this configuration's wheel)", one_line(entry, 80)));
      continue;
    }
    const std::string here = value_text(config, *p), text = kv->value;
    std::string canonical;
    try {
      canonical = format_value(parse_value(*p, text, "--branch"));
    } catch (const ConfigError&) {
      canonical = text;  // not a value of the key: differs from any
    }
    if (canonical != here) out.push_back(fmt::format("{} = {} (here: {})", key, one_line(text, 40), here));
  }
  return out;
}

GaitContinuationOptions gait_continuation_from_config(const Config& config) {
  const GaitContinuationOptions o = record_from_config<GaitContinuationOptions>(config);
  check_with_origin(config, [&] {
    if (o.min_step > o.initial_step)
      throw ConfigError("analysis.continuation.min_step",
                        fmt::format("key 'analysis.continuation.min_step' = '{}': above analysis.continuation."
                                    "initial_step = {}; allowed: a value <= it",
                                    format_number(o.min_step), format_number(o.initial_step)));
  });
  return o;
}

GaitBranch continue_gait(const Config& base, const GaitContinuationSpec& spec) {
  check_sweep_param(base.schema(), spec.param);
  // The branch's maps share the start's integration, initial-state and analysis settings: a key
  // outside the wheel's would vary nothing and draw a flat branch.
  if (spec.param.rfind("rimless.", 0) != 0)
    throw ConfigError("--param", fmt::format("--param {}: a branch follows a parameter of the wheel; allowed: a real "
                                             "rimless.* key (sweep other keys with rimless sweep)",
                                             spec.param));
  if (!(spec.from != spec.to) || !std::isfinite(spec.from) || !std::isfinite(spec.to))
    throw ConfigError("--to", fmt::format("the interval is empty: --from {} --to {}", spec.from, spec.to));
  if (spec.step < 0 || spec.step > std::abs(spec.to - spec.from))
    throw ConfigError("--step", fmt::format("--step {} is not in (0, |to - from|]", spec.step));
  if (spec.period < 1 || spec.period > 64)
    throw ConfigError("--period", fmt::format("--period {} is not an integer in [1, 64]", spec.period));
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
  out.section = spec.section;
  out.computed_at = branch_computed_at(base, spec.param);
  const WheelParams w0 = wheel_from_config(start_config);
  out.period = spec.period;
  numerics::ContinuationOptions o = continuation_options(spec, cache->opt);
  SectionState like;
  if (spec.period == 1) {
    const FixedPointReport start =
        find_fixed_point(w0, cache->sim, cache->opt, cache->model, spec.section, initial_from_config(start_config));
    out.state_names = start.point.names();
    out.mode = mode_text(start.point);
    if (!start.converged) {
      out.failure = fmt::format("no fixed point at {} = {}: {}", spec.param, format_number(spec.from), start.failure());
      return out;
    }
    out.exact_jacobian = start.jacobian_exact;
    like = start.point;
  } else {
    // Newton on P^k from the state the transient reached (a period-1 gait is a fixed point of P^k too).
    const AnalysisOptions& a = cache->opt;
    if (auto e = settle_on_section(w0, map_options(cache->sim, a), cache->model, spec.section,
                                   initial_from_config(start_config), a.transient_steps, like)) {
      out.failure = fmt::format("no period-{} orbit at {} = {}: {}", spec.period, spec.param, format_number(spec.from),
                                e->text());
      return out;
    }
    out.state_names = like.names();
    out.mode = mode_text(like);
    out.exact_jacobian = false;  // P^k's modes in between may differ (family_for)
    o.state_scale = like.scale(w0);
    numerics::BranchPoint pk;
    if (auto e = numerics::fixed_point_at(family_for(cache, like, out.exact_jacobian), like.z, 0.0, o, pk)) {
      out.failure = fmt::format("no period-{} orbit at {} = {} from the transient's state: {}", spec.period, spec.param,
                                format_number(spec.from), *e);
      return out;
    }
    like.z = pk.z;
  }
  build(cache, like, o, out);
  if (spec.switch_at_period_doubling) switch_at_first_period_doubling(cache, o, out);
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
  for (const char* c : {"stable", "residual", "event", "key", "section", "computed_at"}) cols.emplace_back(c);
  CsvWriter csv(cols);
  const std::string section{name_of(b.section)};
  for (const GaitBranchRow& r : b.rows) {
    csv.cell(r.p);
    for (Eigen::Index i = 0; i < r.state.size(); ++i) csv.cell(r.state(i));
    csv.cell(mode_text(r.section)).cell(r.period).cell(r.speed).cell(r.dissipated).cell(r.gait);
    for (std::size_t k = 0; k < b.state_names.size(); ++k) {
      const bool has = k < r.point.multipliers.size();
      csv.cell(has ? std::abs(r.point.multipliers[k]) : NAN).cell(has ? std::arg(r.point.multipliers[k]) : NAN);
    }
    csv.cell(r.point.stable ? "true" : "false").cell(r.point.residual).cell(r.event);
    csv.cell(b.param).cell(section).cell(b.computed_at);
    csv.end_row();
  }
  return csv.str();
}

nlohmann::ordered_json gait_branch_summary(const GaitBranch& b) {
  nlohmann::ordered_json j;
  j["param"] = b.param;
  j["points"] = b.branch.points.size();
  j["reached_end"] = b.branch.reached_end;
  j["stop_reason"] = b.stop_reason;
  j["exact_jacobian"] = b.exact_jacobian;
  j["period"] = b.period;
  j["segments"] = b.segments;
  j["mode"] = b.mode;
  j["section"] = name_of(b.section);
  j["failure"] = b.failure.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(b.failure);
  nlohmann::ordered_json events = nlohmann::ordered_json::array();
  for (const auto& r : b.rows)
    if (!r.event.empty()) events.push_back({{"parameter", r.p}, {"event", r.event}, {"gait", r.gait}});
  j["events"] = events;
  return j;
}

}  // namespace flexgait::rimless
