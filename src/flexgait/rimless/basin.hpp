#pragma once
/// \file basin.hpp
/// Basin of attraction of the wheel's gait (docs/guide/rimless.md, "Orbit diagram and basin of attraction"; Schwab &
/// Wisse 2001): a grid of initial
/// states over two keys of the initial state (initial.omega × initial.beta), each simulated step
/// by step on the Poincaré section until it converges to the reference gait, falls or stops, or
/// reaches the step limit. The reference is the fixed point Newton finds from the configured
/// initial state (fixed_point.hpp), found once before the grid. Cells are independent: the
/// command line runs them on the sweep runner (all cores, resumable, the same bytes for any
/// number of threads). sim.max_time does not limit a cell: --steps-limit does.
#include <array>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/enum_names.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/rimless/outcome.hpp"
#include "flexgait/rimless/poincare.hpp"

namespace flexgait::rimless {

/// The cells' limits (keys analysis.basin.*; --steps-limit and --tolerance set them).
struct BasinOptions {
  int steps_limit = 200;    ///< section crossings simulated per cell at most
  double tolerance = 1e-6;  ///< converged: max_i |z_i - z*_i| / scale_i <= tolerance (scale: SectionState::scale)
  double no_landing_limit = 10.0;  ///< a cell's step without a new landing ends after this [s] (its sim.max_step_time)

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("analysis.basin.steps_limit", s.steps_limit,
      {.doc = "basin: section crossings simulated per cell at most (--steps-limit)", .bounds = closed(1, 100000000)});
    v("analysis.basin.tolerance", s.tolerance,
      {.doc = "basin: converged when every section-state component is within this fraction of its scale "
              "(sqrt(g L0), sqrt(g/L0), alpha) of the gait's (--tolerance)",
       .bounds = positive()});
    v("analysis.no_landing_limit", s.no_landing_limit,
      {.unit = "s",
       .doc = "basin: a cell whose step lands no new leg within this time ends (balanced_at_vertical on one foot, "
              "else stopped); replaces sim.max_step_time in the cells' runs",
       .bounds = positive()});
  }
};
inline Schema basin_schema() {
  return schema_of<BasinOptions>();
}

/// One axis of the grid: `count` values of `key` from `from` to `to`, ends included.
struct BasinAxis {
  std::string key;  ///< a real key of the initial state (initial.omega, initial.beta)
  double from = 0, to = 0;
  int count = 0;
  double value(int i) const { return from + (to - from) * i / (count - 1); }
  double spacing() const { return (to - from) / (count - 1); }
};

struct BasinSpec {
  BasinAxis x, y;
  int steps_limit = BasinOptions{}.steps_limit;               ///< section crossings simulated per cell at most
  double tolerance = BasinOptions{}.tolerance;                ///< converged: max_i |z_i - z*_i| / scale_i <= tolerance
  double no_landing_limit = BasinOptions{}.no_landing_limit;  ///< [s] the cells' sim.max_step_time
  Section section = Section::Touchdown;
  /// x.count × y.count in 64 bits (each count is at most 100000: up to 1e10).
  std::int64_t cells() const { return static_cast<std::int64_t>(x.count) * y.count; }
};

/// The most cells a basin may have: at ~1 ms of CPU per cell, 1e8 cells are ~28 h on one core;
/// the cells are numbered by int on the sweep runner.
inline constexpr std::int64_t kMaxBasinCells = 100'000'000;

/// "A:B:N" as an axis of `key`; throws UsageError naming `option` (A, B finite, A != B, N an
/// integer >= 2).
BasinAxis parse_basin_axis(const std::string& option, const std::string& key, const std::string& text);

/// Throws ConfigError naming the option unless both keys are distinct real keys of the initial
/// state, the limits positive, the grid at most kMaxBasinCells cells (naming --x-range and
/// --y-range), and every cell's configuration valid. O(1): the configuration of the grid's four
/// corners is checked (each key's bounds are an interval, which holds every value of its axis
/// when it holds the axis's ends).
void check_basin(const Config& base, const BasinSpec& spec);

/// The gait the cells are compared with.
struct BasinReference {
  bool found = false;
  SectionState point;  ///< the fixed point (when found)
  std::string gait;
  bool stable = false;
  double max_multiplier = 0;
  std::string failure;  ///< why Newton found none
};
BasinReference basin_reference(const Config& base, Section section);

/// What became of one cell (basin.csv's outcome column, BasinOutcome's names):
///   converged   — reached the reference fixed point within the tolerance;
///   other_gait  — settled on another period-1 orbit (successive crossings within tolerance/100,
///                 farther than 100 × tolerance from the reference);
///   rolled_back — fell back onto the previous leg; stopped — came to rest or no leg landed within
///   no_landing_limit in double support; balanced_at_vertical — no leg landed within
///   no_landing_limit, the wheel on one foot (at its unstable equilibrium); slid_away; time_limit; failed — any other
///   failure (named in `failure`); step_limit  — none of these within steps_limit crossings; infeasible  — the initial
///   state cannot be simulated (a foot below the ground; in `failure`).
enum class BasinOutcome {
  Converged,
  OtherGait,
  RolledBack,
  Stopped,
  BalancedAtVertical,
  SlidAway,
  TimeLimit,
  Failed,
  StepLimit,
  Infeasible
};
constexpr std::array<EnumName<BasinOutcome>, 10> enum_names(BasinOutcome) {
  return {{{BasinOutcome::Converged, "converged"},
           {BasinOutcome::OtherGait, "other_gait"},
           {BasinOutcome::RolledBack, "rolled_back"},
           {BasinOutcome::Stopped, "stopped"},
           {BasinOutcome::BalancedAtVertical, "balanced_at_vertical"},
           {BasinOutcome::SlidAway, "slid_away"},
           {BasinOutcome::TimeLimit, "time_limit"},
           {BasinOutcome::Failed, "failed"},
           {BasinOutcome::StepLimit, "step_limit"},
           {BasinOutcome::Infeasible, "infeasible"}}};
}
std::string basin_header();  ///< x, y, outcome, gait, steps, distance, failure
std::string basin_row(const Config& base, const BasinSpec& spec, const BasinReference& ref, int cell);
/// Whether `cells` (a resumed row, after its index) could be basin_row(…, cell): the cell's x and
/// y, an outcome of basin_outcomes(), steps in [0, steps_limit + 1], the distance a number.
bool basin_row_valid(const BasinSpec& spec, int cell, const std::vector<std::string>& cells);

/// The outcome class of a failure on the way (whatever its stage): rolled_back, stopped, slid_away,
/// time_limit, or failed for any other reason.
BasinOutcome failure_outcome(const Failure& failure);

/// The outcomes above, in that order.
const std::vector<std::string>& basin_outcomes();

/// Counts of each outcome in basin.csv's text (with its index column); every outcome present, 0
/// when no cell has it.
std::map<std::string, int> basin_counts(const std::string& basin_csv);

/// The basin's size from its counts: converged cells, their fraction of the grid, one cell's area
/// (one grid spacing by the other; each grid point stands for one cell) and the basin's area.
struct BasinSize {
  int converged = 0;
  double fraction = 0;
  double cell_area = 0;
  double area() const { return converged * cell_area; }
};
BasinSize basin_size(const BasinSpec& spec, const std::map<std::string, int>& counts);

/// summary.json of the basin: the axes (`x`, `y`: key, from, to, count), `section`, `steps_limit`,
/// `tolerance`, the `reference` gait (found; state, mode, gait, stable, max_multiplier, or its
/// failure), the `outcomes` counted (basin_counts), `cells`, `basin_fraction` (converged cells over
/// all), `cell_area` (one grid spacing by the other), `basin_area` (converged cells × cell_area) in
/// `area_unit`.
nlohmann::ordered_json basin_summary(const BasinSpec& spec, const BasinReference& ref,
                                     const std::map<std::string, int>& counts, const std::string& area_unit);
/// summary.json: basin_summary's text.
std::string basin_summary_json(const BasinSpec& spec, const BasinReference& ref,
                               const std::map<std::string, int>& counts, const std::string& area_unit);

}  // namespace flexgait::rimless
