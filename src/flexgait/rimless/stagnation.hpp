#pragma once
/// \file stagnation.hpp
/// The paper's stagnation interval (Bao, Zhang, Zhou 2024, abstract and Fig. 12; spec
/// rimless.md, "What the paper does" and "Analysis"): within a very small interval of initial
/// angular velocity the first single support slides for a long time near the vertical equilibrium
/// surface, the stance leg vertical in the world,
///
///     β = −φ   (stance-leg angle from the slope normal; the hub right above the foot).
///
/// The experiment, one *stage*: start in single support on leg 0 at β0 = initial.beta ≤ −φ
/// (on or before the vertical) with θ̇ = ω0, and follow the wheel until
///   - the next leg (ahead, leg N−1) lands: the wheel passed the vertical (`next_leg_landed`);
///   - the leg behind (leg 1) lands: the wheel fell back (`rolled_back`);
///   - the wheel comes to rest (`came_to_rest`: kinetic energy below `rest_energy` m g L0);
///   - `stagnation.time_limit` is reached with the stance leg inside the window: a stagnation
///     (`stagnated`, a result, not an error), or outside it (`time_limit`);
///   - the simulation stops for another reason (`failed`, its message kept).
/// Measured: the time the stance foot slips while |β + φ| < `stagnation.window` (and the time
/// it sticks there), the total slip time, the stage's duration, and the mechanical energy at its
/// end (before the landing). Slip intervals come from the run's events (exact); inside them the
/// window crossings are roots of the cubic Hermite interpolant of θ through consecutive log
/// samples (θ, θ̇) at sim.sample_dt and at every event, so the measure is exact to the event and
/// to O(h⁴ θ⁽⁴⁾) ≈ 1e-13 s at h = 1 ms (tests compare h = 1 ms with h = 0.25 ms).
///
/// Why it stalls there: near β = −φ the wheel is an inverted pendulum. With the foot slipping
/// (μ_k ≈ tan φ) the ground force points along the leg when tan β = −μ_k s, the hub is nearly
/// free to translate, and the wheel topples about its hub at the rate λ = sqrt(m g L / I); with the
/// foot sticking it topples about the foot, λ = sqrt(m g L / (I + m L²)). Started at ω0 = ω_c ± d
/// (ω_c: where the stage's end flips from rolling back to passing) the time near the saddle grows
/// like ln(1/d)/λ: ln(10)/λ seconds per decade of d (0.40 s for I = 0.3, sliding; 0.74 s for
/// small I, sticking).
///
/// The scan: a grid of ω0 brackets ω_c (the lowest flip from `rolled_back` to `next_leg_landed`),
/// bisection on the stage's end narrows it to `stagnation.bisection_tol` relative, then stages at
/// ω_c ± d for d log-spaced from `offset_max` down to `offset_min`. The near-vertical time T(d)
/// (slip + stick in the window) at ω_c + offset_max (the wheel passes the vertical briskly) is
/// its *typical* value; the stagnation interval is where T exceeds `factor` times it, each bound
/// bisected on T between the two scan offsets around the threshold to `bisection_tol` (as ω_c;
/// the stages of this bisection count in `stages`, they are not in the scan's rows). The growth
/// per decade is the least-squares slope of T against log10(1/d) over d ≤ `fit_offset` (1e-3: the
/// asymptotic regime), per side; the larger of its slip and stick parts names the kind when it
/// exceeds `kind_fraction` (0.25) of the sliding estimate.
#include <string>
#include <vector>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/rimless/parameters.hpp"

namespace flexgait::rimless {

/// The experiment's parameters (keys stagnation.*).
struct StagnationOptions {
  double window = 0.02;          ///< half-width of the near-vertical window |β + φ| < window [rad]
  double time_limit = 30.0;      ///< a stage still going at this time is a stagnation [s]
  double omega_from = 0.2;       ///< coarse grid of ω0, first value [rad/s]
  double omega_to = 1.2;         ///< coarse grid of ω0, last value [rad/s]
  int count = 41;                ///< coarse grid of ω0, number of values (ends included)
  double bisection_tol = 1e-12;  ///< bisection on the stage's end stops at this width / ω_c
  double offset_max = 1e-1;      ///< largest |ω0 − ω_c| of the log scan [rad/s]
  double offset_min = 1e-9;      ///< smallest |ω0 − ω_c| of the log scan [rad/s]
  int per_decade = 2;            ///< offsets per decade of the log scan
  double factor = 5.0;           ///< the interval: near-vertical time > factor × its typical value
  double fit_offset = 1e-3;      ///< the growth per decade is fitted over offsets d <= this [rad/s]
  double kind_fraction = 0.25;   ///< a growth above this × the sliding estimate names a kind, else "none"
  double rest_energy = 1e-9;     ///< came to rest: kinetic energy below this × m g L0 at the end

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("stagnation.window", s.window,
      {.unit = "rad", .doc = "half-width of the window about the true vertical beta = -phi", .bounds = open(0, 1.5)});
    v("stagnation.time_limit", s.time_limit,
      {.unit = "s", .doc = "a stage still near the vertical at this time is a stagnation", .bounds = positive()});
    v("stagnation.omega_from", s.omega_from,
      {.unit = "rad/s",
       .doc = "coarse grid of the initial angular velocity: first value",
       .bounds = closed(-100, 100)});
    v("stagnation.omega_to", s.omega_to,
      {.unit = "rad/s", .doc = "coarse grid of the initial angular velocity: last value", .bounds = closed(-100, 100)});
    v("stagnation.count", s.count,
      {.doc = "coarse grid: number of values, ends included", .bounds = closed(2, 100000)});
    v("stagnation.bisection_tol", s.bisection_tol,
      {.doc = "bisection for the critical omega0 stops at this relative width", .bounds = closed(1e-15, 1e-2)});
    v("stagnation.offset_max", s.offset_max,
      {.unit = "rad/s", .doc = "largest |omega0 - omega_c| of the log scan", .bounds = open(0, 10)});
    v("stagnation.offset_min", s.offset_min,
      {.unit = "rad/s", .doc = "smallest |omega0 - omega_c| of the log scan", .bounds = open(0, 10)});
    v("stagnation.per_decade", s.per_decade, {.doc = "log scan: offsets per decade", .bounds = closed(1, 100)});
    v("stagnation.factor", s.factor,
      {.doc = "stagnation interval: near-vertical time above this multiple of its typical value", .bounds = above(1)});
    v("stagnation.fit_offset", s.fit_offset,
      {.unit = "rad/s",
       .doc = "growth per decade: least-squares fit over the scan's offsets |omega0 - omega_c| <= this "
              "(the asymptotic regime)",
       .bounds = open(0, 10)});
    v("stagnation.kind_fraction", s.kind_fraction,
      {.doc = "kind: the larger growth (slip or stick) names it when above this fraction of the sliding pendulum "
              "estimate, else none (noise)",
       .bounds = non_negative()});
    v("stagnation.rest_energy", s.rest_energy,
      {.doc = "a stage that stops with kinetic energy below this fraction of m g L0 came to rest",
       .bounds = open(0, 1)});
  }
};
inline Schema stagnation_schema() {
  return schema_of<StagnationOptions>();
}
/// The options of a resolved configuration; throws ConfigError (key named) if inconsistent
/// (omega_from >= omega_to, offset_min > offset_max, initial.beta > -rimless.slope).
StagnationOptions stagnation_from_config(const Config& config);

/// How a stage ended (see the file comment).
enum class StageEnd { NextLegLanded, RolledBack, CameToRest, Stagnated, TimeLimit, Failed };
constexpr std::array<EnumName<StageEnd>, 6> enum_names(StageEnd) {
  return {{{StageEnd::NextLegLanded, "next_leg_landed"},
           {StageEnd::RolledBack, "rolled_back"},
           {StageEnd::CameToRest, "came_to_rest"},
           {StageEnd::Stagnated, "stagnated"},
           {StageEnd::TimeLimit, "time_limit"},
           {StageEnd::Failed, "failed"}}};
}

/// One stage (the first single support from the start).
struct Stage {
  double omega0 = 0;  ///< initial angular velocity [rad/s]
  StageEnd end = StageEnd::Failed;
  std::string failure;             ///< the simulation's message when end = failed
  double slide_near_vertical = 0;  ///< time the stance foot slips with |β + φ| < window [s]
  double stick_near_vertical = 0;  ///< time it sticks there [s]
  double slide_total = 0;          ///< time the stance foot slips in the stage [s]
  double duration = 0;             ///< [s]
  double energy_end = 0;           ///< mechanical energy at the end (before a landing) [J]
  double kinetic_end = 0;          ///< kinetic energy at the end [J]
  double beta_end = 0;             ///< stance-leg angle at the end [rad]

  double near_vertical() const { return slide_near_vertical + stick_near_vertical; }
};

/// One stage from single support on leg 0 at β0 = start.beta, θ̇ = start.omega (InitialState's
/// static compression and rolling velocity), at the tolerances of `sim` (sim.steps, max_time and
/// max_step_time are replaced by the stage's own limits; the log is kept at sim.sample_dt).
/// Pure and deterministic. Throws ConfigError if start.beta > −φ (it must start on or before the vertical).
Stage run_stage(const WheelParams& w, const InitialState& start, const SimulationOptions& sim,
                const StagnationOptions& opt);

/// Measure of {t ∈ [t0, t1] : |g(t)| < half_width} for the cubic Hermite interpolant through
/// (t0, g0, ġ0) and (t1, g1, ġ1) [s]; crossings by bisection on each monotone piece.
double hermite_time_within(double t0, double g0, double gd0, double t1, double g1, double gd1, double half_width);

/// What the scan found (stagnation.json). Offsets d = |ω0 − ω_c|.
struct StagnationSummary {
  double beta_start = 0;          ///< β0 [rad]
  double beta_vertical = 0;       ///< −φ [rad]
  double beta_friction_edge = 0;  ///< −atan μ_k: where a forward-slipping foot's force lies along the leg [rad]
  double window = 0;              ///< [rad]
  bool critical_found = false;    ///< the grid bracketed a flip from rolled_back to next_leg_landed
  double omega_c = 0;             ///< critical ω0 [rad/s]
  double omega_c_low = 0, omega_c_high = 0;  ///< final bisection bracket [rad/s]
  int bisection_steps = 0;
  std::string bisection_note;  ///< why the bisection stopped early (a stage neither passed nor rolled back)
  int flips = 0;               ///< outcome changes along the grid
  double typical_time = 0;     ///< near-vertical time at ω_c + offset_max [s]
  double threshold = 0;        ///< factor × typical_time [s]
  double interval_low = 0, interval_high = 0;  ///< the stagnation interval of ω0 [rad/s]
  double interval_width = 0;                   ///< [rad/s]
  double growth_above = 0;       ///< d(near-vertical time)/d log10(1/d), ω0 > ω_c, d <= fit_offset [s per decade]
  double growth_below = 0;       ///< the same, ω0 < ω_c [s per decade]
  double growth_slide = 0;       ///< slip part of it, both sides pooled [s per decade]
  double growth_stick = 0;       ///< stick part of it, both sides pooled [s per decade]
  std::string kind;              ///< sliding | sticking | none (which part grows)
  double estimate_sliding = 0;   ///< ln 10 · sqrt(I / (m g L0)): toppling about the hub [s per decade]
  double estimate_sticking = 0;  ///< ln 10 · sqrt((I + m L0²) / (m g L0)): toppling about the foot [s per decade]
  double slide_far = 0;          ///< slip time near the vertical at ω_c + offset_max [s]
  double slide_near = 0;         ///< the largest slip time near the vertical in the scan [s]
  double near_time_max = 0;      ///< the largest near-vertical time in the scan [s]
  int stages = 0;                ///< stages simulated (grid, bisection, scan)

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("beta_start", s.beta_start, {.unit = "rad", .doc = "stance-leg angle at the start"});
    v("beta_vertical", s.beta_vertical, {.unit = "rad", .doc = "the true vertical, beta = -phi"});
    v("beta_friction_edge", s.beta_friction_edge,
      {.unit = "rad", .doc = "-atan(mu_k): a forward-slipping foot's ground force along the leg"});
    v("window", s.window, {.unit = "rad", .doc = "half-width of the near-vertical window"});
    v("critical_found", s.critical_found, {.doc = "the grid bracketed a flip from rolled_back to next_leg_landed"});
    v("omega_c", s.omega_c, {.unit = "rad/s", .doc = "critical initial angular velocity", .present = s.critical_found});
    v("omega_c_low", s.omega_c_low,
      {.unit = "rad/s", .doc = "bisection bracket: rolls back", .present = s.critical_found});
    v("omega_c_high", s.omega_c_high,
      {.unit = "rad/s", .doc = "bisection bracket: passes", .present = s.critical_found});
    v("bisection_steps", s.bisection_steps, {.doc = "bisection stages"});
    v("bisection_note", s.bisection_note,
      {.doc = "why the bisection stopped early; empty if it reached its tolerance"});
    v("flips", s.flips, {.doc = "changes of the stage's end along the grid"});
    const bool c = s.critical_found;
    v("typical_time", s.typical_time, {.unit = "s", .doc = "near-vertical time at omega_c + offset_max", .present = c});
    v("threshold", s.threshold, {.unit = "s", .doc = "factor x typical_time", .present = c});
    v("interval_low", s.interval_low, {.unit = "rad/s", .doc = "stagnation interval: lower bound", .present = c});
    v("interval_high", s.interval_high, {.unit = "rad/s", .doc = "stagnation interval: upper bound", .present = c});
    v("interval_width", s.interval_width, {.unit = "rad/s", .doc = "stagnation interval: width", .present = c});
    v("growth_above", s.growth_above,
      {.unit = "s",
       .doc = "near-vertical time per decade of omega0 - omega_c (above), d <= stagnation.fit_offset",
       .present = c});
    v("growth_below", s.growth_below,
      {.unit = "s",
       .doc = "near-vertical time per decade of omega_c - omega0 (below), d <= stagnation.fit_offset",
       .present = c});
    v("growth_slide", s.growth_slide, {.unit = "s", .doc = "slip part of the growth per decade", .present = c});
    v("growth_stick", s.growth_stick, {.unit = "s", .doc = "stick part of the growth per decade", .present = c});
    v("kind", s.kind, {.doc = "sliding, sticking or none: which part of the near-vertical time grows"});
    v("estimate_sliding", s.estimate_sliding,
      {.unit = "s", .doc = "ln10 sqrt(I/(m g L0)): per decade when toppling about the hub"});
    v("estimate_sticking", s.estimate_sticking,
      {.unit = "s", .doc = "ln10 sqrt((I + m L0^2)/(m g L0)): per decade when toppling about the foot"});
    v("slide_far", s.slide_far,
      {.unit = "s", .doc = "slip time near the vertical at omega_c + offset_max", .present = c});
    v("slide_near", s.slide_near,
      {.unit = "s", .doc = "largest slip time near the vertical in the scan", .present = c});
    v("near_time_max", s.near_time_max, {.unit = "s", .doc = "largest near-vertical time in the scan", .present = c});
    v("stages", s.stages, {.doc = "stages simulated"});
  }
};

/// Every stage of a scan, and what it found.
struct StagnationScan {
  std::vector<Stage> grid;      ///< the coarse grid of ω0
  std::vector<double> offsets;  ///< d, largest first [rad/s]
  std::vector<Stage> above;     ///< at ω_c + d (empty without a critical value)
  std::vector<Stage> below;     ///< at ω_c − d
  StagnationSummary summary;
};

/// Grid, bisection, log scan and the interval (file comment). Sequential and deterministic.
StagnationScan scan_stagnation(const WheelParams& w, const InitialState& start, const SimulationOptions& sim,
                               const StagnationOptions& opt);

/// stagnation.csv: every stage of the scan sorted by ω0. Columns: omega0, offset (ω0 − ω_c; empty
/// without ω_c), part (grid | scan), end, slide_near_vertical, stick_near_vertical, slide_total,
/// duration, energy_end, kinetic_end, beta_end, failure.
std::string stagnation_csv(const StagnationScan& scan);

/// The map (stagnation_map.csv): one row per variation of the base configuration, each a list of
/// "KEY=VALUE" settings, comma-separated (rimless.mu sets mu_s and mu_k). Columns: variation, mu_minus_tan_slope, I,
/// C, K, then the summary's numeric fields and kind.
/// The configuration of one variation, "KEY=VALUE[,KEY=VALUE...]" (validated: throws ConfigError
/// naming the key, UsageError for a malformed setting).
Config stagnation_map_config(const Config& base, const std::string& variation);
std::string stagnation_map_header();
std::string stagnation_map_row(const Config& base, const std::string& variation);
/// A resumed row is kept only if stagnation_map_row could have written it for `variation`: the
/// header's number of cells, the variation's own name first, then four numbers (μ − tan slope, I, C, K).
bool stagnation_map_row_valid(const std::string& variation, const std::vector<std::string>& cells);

}  // namespace flexgait::rimless
