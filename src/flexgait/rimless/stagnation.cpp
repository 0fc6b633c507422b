#include "flexgait/rimless/stagnation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "flexgait/core/text.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"

namespace flexgait::rimless {

namespace {

// The stage starts on or before the true vertical.
void check_start(double slope, double beta) {
  if (beta > -slope)
    throw ConfigError("initial.beta", fmt::format("key 'initial.beta' = '{}': the stagnation stage starts on or "
                                                  "before the vertical, beta <= -rimless.slope = {} (rad)",
                                                  beta, -slope));
}

}  // namespace

StagnationOptions stagnation_from_config(const Config& config) {
  const StagnationOptions o = record_from_config<StagnationOptions>(config);
  check_start(config.real("rimless.slope"), config.real("initial.beta"));
  if (!(o.omega_from < o.omega_to))
    throw ConfigError("stagnation.omega_to", fmt::format("key 'stagnation.omega_to' = '{}': must exceed "
                                                         "stagnation.omega_from = {}",
                                                         o.omega_to, o.omega_from));
  if (o.offset_min > o.offset_max)
    throw ConfigError("stagnation.offset_min", fmt::format("key 'stagnation.offset_min' = '{}': must not exceed "
                                                           "stagnation.offset_max = {}",
                                                           o.offset_min, o.offset_max));
  return o;
}

double hermite_time_within(double t0, double g0, double gd0, double t1, double g1, double gd1, double half_width) {
  const double h = t1 - t0;
  if (!(h > 0)) return 0.0;
  // p(s) = a + b s + c s² + d s³ on s ∈ [0, 1], the cubic Hermite interpolant in s = (t − t0)/h.
  const double a = g0, b = h * gd0, c = 3 * (g1 - g0) - h * (2 * gd0 + gd1), d = 2 * (g0 - g1) + h * (gd0 + gd1);
  auto p = [&](double s) { return a + s * (b + s * (c + s * d)); };
  // Monotone pieces: split at the roots of p'(s) = b + 2c s + 3d s² inside (0, 1).
  std::vector<double> knots{0.0, 1.0};
  if (std::abs(d) > 1e-300) {
    const double disc = c * c - 3 * d * b;
    if (disc >= 0) {
      const double r = std::sqrt(disc);
      for (double s : {(-c - r) / (3 * d), (-c + r) / (3 * d)})
        if (s > 0 && s < 1) knots.push_back(s);
    }
  } else if (std::abs(c) > 1e-300) {
    const double s = -b / (2 * c);
    if (s > 0 && s < 1) knots.push_back(s);
  }
  std::sort(knots.begin(), knots.end());
  // Crossings of ±half_width on each monotone piece, by bisection to the last bit.
  std::vector<double> cuts = knots;
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    for (double level : {-half_width, half_width}) {
      double lo = knots[i], hi = knots[i + 1];
      const double flo = p(lo) - level, fhi = p(hi) - level;
      if (flo * fhi >= 0) continue;
      for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
        const double mid = 0.5 * (lo + hi);
        if ((p(mid) - level) * flo > 0)
          lo = mid;
        else
          hi = mid;
      }
      cuts.push_back(0.5 * (lo + hi));
    }
  }
  std::sort(cuts.begin(), cuts.end());
  double inside = 0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    if (std::abs(p(0.5 * (cuts[i] + cuts[i + 1]))) < half_width) inside += cuts[i + 1] - cuts[i];
  return inside * h;
}

namespace {

// A stage's record as the run makes it: the near-vertical times of consecutive samples (the
// samples at sim.sample_dt and on both sides of every event: the stance foot's mode holds on
// each interval of positive length between consecutive samples, an event's two samples share t),
// the last sample and the last event. Two samples are kept, not the log.
class StageLog final : public RunSink {
 public:
  StageLog(const WheelParams& w, const StagnationOptions& opt, int stance, Stage& stage)
      : w_(w), opt_(opt), stance_(stance), s_(stage) {}
  void on_sample(const LogSample& b) override {
    if (samples_++ > 0) add(last_, b);
    last_ = b;
  }
  void on_event(const EventRecord& e) override { last_event_ = e; }
  bool has_samples() const { return samples_ > 0; }
  const LogSample& last_sample() const { return last_; }
  const EventRecord& last_event() const { return last_event_; }

 private:
  void add(const LogSample& a, const LogSample& b) {
    if (!(b.t > a.t)) return;
    const ContactSample* foot = nullptr;
    for (const ContactSample& c : a.contact)
      if (c.leg == stance_) foot = &c;
    if (foot == nullptr) return;  // the stance foot is in the air
    const bool slipping = foot->mode != FootMode::Stick;
    const double ga = leg_angle(w_, stance_, a.q[2]) + w_.slope, gb = leg_angle(w_, stance_, b.q[2]) + w_.slope;
    const double near = hermite_time_within(a.t, ga, a.q[5], b.t, gb, b.q[5], opt_.window);
    (slipping ? s_.slide_near_vertical : s_.stick_near_vertical) += near;
    if (slipping) s_.slide_total += b.t - a.t;
  }
  const WheelParams& w_;
  const StagnationOptions& opt_;
  int stance_;
  Stage& s_;
  long long samples_ = 0;
  LogSample last_;
  EventRecord last_event_;
};

}  // namespace

Stage run_stage(const WheelParams& w, const InitialState& start, const SimulationOptions& sim,
                const StagnationOptions& opt) {
  check_start(w.slope, start.beta);
  constexpr int stance = 0;
  SimulationOptions o = sim;
  o.model = Model::Flexible;
  o.log = true;
  o.sensitivities = false;
  o.steps = 1;
  o.max_time = opt.time_limit;
  o.max_step_time = 2 * opt.time_limit;  // the time limit, not the step limit, ends a stagnation
  FlexibleWheelSimulator simulator(w, o);
  RunSpec spec = default_run(w, start);
  spec.stop_at = Section::Touchdown;  // the stage ends when another leg lands, before its mode is chosen
  spec.section_includes_legs_behind = true;
  Stage s;
  s.omega0 = start.omega;
  StageLog log(w, opt, stance, s);
  const SimulationResult r = simulator.run(spec, log);
  if (!log.has_samples()) {
    s.failure = r.failure ? r.failure->text() : "no samples";
    return s;
  }
  const LogSample& last = log.last_sample();
  s.duration = r.t_final;
  s.energy_end = last.energy.total();
  s.kinetic_end = last.energy.kinetic;
  s.beta_end = leg_angle(w, stance, last.q[2]);
  const bool landed = r.event_count > 0 && log.last_event().kind == RunEvent::Section;
  if (landed) {
    const int leg = log.last_event().leg;
    s.end = leg == (stance + w.legs - 1) % w.legs ? StageEnd::NextLegLanded
            : leg == stance + 1                   ? StageEnd::RolledBack
                                                  : StageEnd::Failed;
    if (s.end == StageEnd::Failed) s.failure = fmt::format("leg {} landed, neither neighbour of the stance leg", leg);
  } else if (r.t_final >= opt.time_limit) {
    s.end = std::abs(s.beta_end + w.slope) < opt.window ? StageEnd::Stagnated : StageEnd::TimeLimit;
  } else if (s.kinetic_end < opt.rest_energy * w.m * w.g * w.L0) {
    s.end = StageEnd::CameToRest;
  } else {
    s.end = StageEnd::Failed;
    s.failure = r.failure ? r.failure->text() : "stopped without a landing";
  }
  return s;
}

namespace {

// Least-squares slope of y against x.
double slope_of(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  if (x.size() < 2) return 0.0;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double den = n * sxx - sx * sx;
  return den > 0 ? (n * sxy - sx * sy) / den : 0.0;
}

}  // namespace

StagnationScan scan_stagnation(const WheelParams& w, const InitialState& start, const SimulationOptions& sim,
                               const StagnationOptions& opt) {
  StagnationScan scan;
  StagnationSummary& sum = scan.summary;
  sum.beta_start = start.beta;
  sum.beta_vertical = -w.slope;
  sum.beta_friction_edge = -std::atan(w.mu_k);
  sum.window = opt.window;
  sum.estimate_sliding = std::numbers::ln10 * std::sqrt(w.I / (w.m * w.g * w.L0));
  sum.estimate_sticking = std::numbers::ln10 * std::sqrt((w.I + w.m * w.L0 * w.L0) / (w.m * w.g * w.L0));
  auto stage = [&](double omega0) {
    InitialState s = start;
    s.omega = omega0;
    ++sum.stages;
    return run_stage(w, s, sim, opt);
  };

  for (int i = 0; i < opt.count; ++i)
    scan.grid.push_back(stage(opt.omega_from + (opt.omega_to - opt.omega_from) * i / (opt.count - 1)));
  int bracket = -1;
  for (std::size_t i = 0; i + 1 < scan.grid.size(); ++i) {
    if (scan.grid[i].end != scan.grid[i + 1].end) ++sum.flips;
    if (bracket < 0 && scan.grid[i].end == StageEnd::RolledBack && scan.grid[i + 1].end == StageEnd::NextLegLanded)
      bracket = static_cast<int>(i);
  }
  sum.kind = "none";
  if (bracket < 0) return scan;

  // Bisection on the stage's end.
  sum.critical_found = true;
  double lo = scan.grid[static_cast<std::size_t>(bracket)].omega0,
         hi = scan.grid[static_cast<std::size_t>(bracket) + 1].omega0;
  while (hi - lo > opt.bisection_tol * std::abs(hi)) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    const Stage m = stage(mid);
    ++sum.bisection_steps;
    if (m.end == StageEnd::RolledBack) {
      lo = mid;
    } else if (m.end == StageEnd::NextLegLanded) {
      hi = mid;
    } else {
      sum.bisection_note = fmt::format("at omega0 = {} the stage ended {}{}", format_number(mid), name_of(m.end),
                                       m.failure.empty() ? "" : ": " + m.failure);
      break;
    }
  }
  sum.omega_c_low = lo;
  sum.omega_c_high = hi;
  sum.omega_c = 0.5 * (lo + hi);

  // Log scan of the offset d on both sides.
  const double l_max = std::log10(opt.offset_max), l_min = std::log10(opt.offset_min);
  for (int j = 0;; ++j) {
    const double l = l_max - static_cast<double>(j) / opt.per_decade;
    if (l < l_min - 1e-9) break;
    scan.offsets.push_back(std::pow(10.0, l));
  }
  for (double d : scan.offsets) {
    scan.above.push_back(stage(sum.omega_c + d));
    scan.below.push_back(stage(sum.omega_c - d));
  }

  // The interval and the growth.
  sum.slide_far = scan.above.front().slide_near_vertical;
  sum.typical_time = scan.above.front().near_vertical();
  sum.threshold = opt.factor * sum.typical_time;
  // Each bound: the offset where T(d) first reaches the threshold coming in from the largest d
  // (offsets largest first), bisected on T(d) >= threshold between the two scan offsets around it
  // to stagnation.bisection_tol relative to ω_c, as ω_c is; 0 if T never reaches it,
  // offsets.front() if it already does there.
  const auto bound = [&](const std::vector<Stage>& stages, double side) {
    for (std::size_t j = 0; j < stages.size(); ++j) {
      if (stages[j].near_vertical() < sum.threshold) continue;
      if (j == 0) return scan.offsets[0];
      double outside = scan.offsets[j - 1], inside = scan.offsets[j];
      while (outside - inside > opt.bisection_tol * std::abs(sum.omega_c)) {
        const double mid = 0.5 * (outside + inside);
        if (mid <= inside || mid >= outside) break;
        (stage(sum.omega_c + side * mid).near_vertical() >= sum.threshold ? inside : outside) = mid;
      }
      return 0.5 * (outside + inside);
    }
    return 0.0;
  };
  const double d_high = bound(scan.above, +1.0);
  const double d_low = bound(scan.below, -1.0);
  sum.interval_low = sum.omega_c - d_low;
  sum.interval_high = sum.omega_c + d_high;
  sum.interval_width = d_low + d_high;
  std::vector<double> xa, ya, xb, yb, x, slide, stick;
  for (std::size_t j = 0; j < scan.offsets.size(); ++j) {
    const double x_j = std::log10(1.0 / scan.offsets[j]);
    for (const Stage* s : {&scan.above[j], &scan.below[j]}) {
      sum.slide_near = std::max(sum.slide_near, s->slide_near_vertical);
      sum.near_time_max = std::max(sum.near_time_max, s->near_vertical());
      if (scan.offsets[j] > opt.fit_offset * (1 + 1e-9)) continue;  // 1e-9: the grid's round-off
      x.push_back(x_j);
      slide.push_back(s->slide_near_vertical);
      stick.push_back(s->stick_near_vertical);
    }
    if (scan.offsets[j] > opt.fit_offset * (1 + 1e-9)) continue;  // 1e-9: the grid's round-off
    xa.push_back(x_j);
    ya.push_back(scan.above[j].near_vertical());
    xb.push_back(x_j);
    yb.push_back(scan.below[j].near_vertical());
  }
  sum.growth_above = slope_of(xa, ya);
  sum.growth_below = slope_of(xb, yb);
  sum.growth_slide = slope_of(x, slide);
  sum.growth_stick = slope_of(x, stick);
  const double growth = std::max(sum.growth_slide, sum.growth_stick);
  // A stagnation grows by a sizeable fraction of the pendulum estimate per decade; below that it is noise.
  if (growth > opt.kind_fraction * sum.estimate_sliding)
    sum.kind = sum.growth_slide >= sum.growth_stick ? "sliding" : "sticking";
  return scan;
}

std::string stagnation_csv(const StagnationScan& scan) {
  struct Row {
    const Stage* stage;
    const char* part;
  };
  std::vector<Row> rows;
  for (const Stage& s : scan.grid) rows.push_back({&s, "grid"});
  for (const Stage& s : scan.above) rows.push_back({&s, "scan"});
  for (const Stage& s : scan.below) rows.push_back({&s, "scan"});
  std::stable_sort(rows.begin(), rows.end(),
                   [](const Row& a, const Row& b) { return a.stage->omega0 < b.stage->omega0; });
  CsvWriter csv({"omega0", "offset", "part", "end", "slide_near_vertical", "stick_near_vertical", "slide_total",
                 "duration", "energy_end", "kinetic_end", "beta_end", "failure"});
  for (const Row& r : rows) {
    const Stage& s = *r.stage;
    csv.cell(s.omega0);
    if (scan.summary.critical_found)
      csv.cell(s.omega0 - scan.summary.omega_c);
    else
      csv.cell("");
    csv.cell(r.part).cell(name_of(s.end)).cell(s.slide_near_vertical).cell(s.stick_near_vertical).cell(s.slide_total);
    csv.cell(s.duration).cell(s.energy_end).cell(s.kinetic_end).cell(s.beta_end).cell(s.failure).end_row();
  }
  return csv.str();
}

namespace {

// The summary's fields as CSV header names or cells (the map's columns after the variation).
struct CsvHeader {
  std::string& out;
  template <class T>
  void operator()(std::string_view key, const T&, const FieldInfo&) {
    out += fmt::format(",{}", key);
  }
};
struct CsvCells {
  std::string& out;
  template <class T>
  void operator()(std::string_view, const T& v, const FieldInfo& info) {
    if (!info.present) {
      out += ",";
    } else if constexpr (std::is_same_v<T, bool>) {
      out += v ? ",true" : ",false";
    } else if constexpr (std::is_same_v<T, std::string>) {
      out += "," + csv_field(v);
    } else if constexpr (std::is_same_v<T, int>) {
      out += fmt::format(",{}", v);
    } else {
      out += "," + format_number(v);
    }
  }
};

}  // namespace

std::string stagnation_map_header() {
  std::string h = "variation,mu_minus_tan_slope,I,C,K";
  CsvHeader v{h};
  const StagnationSummary defaults;
  StagnationSummary::visit_fields(defaults, v);
  return h;
}

Config stagnation_map_config(const Config& base, const std::string& variation) {
  Config c = base;
  std::size_t from = 0;
  while (from < variation.size()) {
    const std::size_t comma = std::min(variation.find(',', from), variation.size());
    const std::string kv = variation.substr(from, comma - from);
    from = comma + 1;
    const std::optional<KeyValue> item = split_key_value(kv);
    if (!item || item->key.empty())
      throw UsageError(fmt::format("stagnation map variation '{}': expected KEY=VALUE[,KEY=VALUE...]", variation));
    const std::string origin = fmt::format("stagnation map '{}'", variation);
    c.set(item->key, item->value, origin);  // an alias (rimless.mu) sets each of its parts
  }
  validate(wheel_from_config(c), initial_from_config(c));
  stagnation_from_config(c);
  return c;
}

std::string stagnation_map_row(const Config& base, const std::string& variation) {
  const Config c = stagnation_map_config(base, variation);
  const WheelParams w = wheel_from_config(c);
  const StagnationScan scan =
      scan_stagnation(w, initial_from_config(c), simulation_from_config(c), stagnation_from_config(c));
  std::string row = fmt::format("{},{},{},{},{}", csv_field(variation.empty() ? "base" : variation),
                                format_number(w.mu_k - std::tan(w.slope)), format_number(w.I), format_number(w.C),
                                format_number(w.K));
  CsvCells v{row};
  StagnationSummary::visit_fields(scan.summary, v);
  return row;
}

bool stagnation_map_row_valid(const std::string& variation, const std::vector<std::string>& cells) {
  const std::string header = stagnation_map_header();
  const auto columns = static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
  if (cells.size() != columns || cells[0] != (variation.empty() ? "base" : variation)) return false;
  return std::all_of(cells.begin() + 1, cells.begin() + 5, [](const std::string& cell) { return number_text(cell); });
}

}  // namespace flexgait::rimless
