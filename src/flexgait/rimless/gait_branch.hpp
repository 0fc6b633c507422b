#pragma once
/// \file gait_branch.hpp
/// Continuation of the wheel's periodic gait in one real configuration key (docs/guide/rimless.md, "Orbit diagram and
/// basin of attraction"): the fixed
/// point of the Poincaré map followed by pseudo-arclength continuation (numerics/continuation.hpp)
/// in the normalised parameter q = (p - from)/(to - from) ∈ [0, 1], so that one arclength unit is
/// the whole interval whatever the key's unit. ∂P/∂z is the exact (variational) Jacobian when the
/// map has one at the start, else central differences; ∂P/∂q then comes from the same variational
/// run (the sensitivities' parameter column, flexible_wheel.hpp ParameterDirection) for a wheel
/// key (rimless.*), else by central differences.
/// The gait label (stance-foot phases over the cycle) is watched: where it changes (a non-smooth
/// boundary: a phase appears or vanishes) the change is located by bisection. The map keeps the
/// section's discrete mode (the stance foot's mode just before the touchdown), so a boundary where
/// that mode changes (e.g. a slip phase that starts ever later reaches the section: the gait
/// slip-stick becomes slip-stick-slip and the section state stick becomes slip-) ends a segment of
/// the branch: its last point is within the corrector's smallest step of the boundary (∂P/∂q by
/// sensitivity: no evaluation leaves the point; by central differences: within their step). There
/// the branch is carried over to the new mode (cross_section_mode in gait_branch.cpp): the last
/// point written in the new mode (in_mode), Newton on the new mode's map a little beyond, the new
/// segment continued back until it ends at the boundary from its side; when both ends meet (the
/// fixed point is continuous there, as at the μ thresholds between behaviours) the branch goes on
/// from there in the new mode, and the boundary is an event "section mode A -> B"; otherwise the
/// branch ends and says why.
#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/enum_names.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/numerics/continuation.hpp"
#include "flexgait/rimless/poincare.hpp"

namespace flexgait::rimless {

/// The continuation's tuning, keys `analysis.continuation.*` (`rimless continuation`), in the
/// normalised parameter q = (p - from)/(to - from): the defaults are the values it always used.
/// Guards against round-off (a division by zero, a grid's last bit) stay literals.
struct GaitContinuationOptions {
  int max_points = 2000;               ///< points on the branch, all segments together, at most
  double initial_step = 0.02;          ///< first arclength step without --step (0.02: 50 steps over the interval)
  double max_step_factor = 2;          ///< the step adapts up to this × the first
  double min_step = 1e-9;              ///< the branch ends where a step this small fails; a segment's end at a
                                       ///< change of the section's mode is within it of the boundary
  double locate_tolerance = 1e-9;      ///< folds, period doublings, Neimark-Sacker points located to this in q
  double label_tolerance = 1e-7;       ///< gait changes located to this in q
  double parameter_step = 6e-6;        ///< ∂P/∂p by sensitivity: the wheel at p ± this × max(|p|, |to - from|)
  double mode_change_distance = 1e-3;  ///< a segment ends at a change of the section's mode when the map
                                       ///< arrived in the other mode within this (in q) of its last point
  std::vector<double> mode_probes{3e-4, 1e-3, 3e-3, 1e-2};  ///< Newton in the new mode this far (in q) beyond
                                                            ///< the boundary, each in turn
  double back_distance = 0.05;   ///< the new mode's branch is continued back to the boundary, at most this behind it
  int back_max_points = 200;     ///< ... in at most this many points
  double join_tolerance = 1e-3;  ///< both ends meet: in q, and in the state scaled by its typical size

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("analysis.continuation.max_points", s.max_points,
      {.doc = "continuation: points on the branch (all its segments), at most", .bounds = closed(2, 10000000)});
    v("analysis.continuation.initial_step", s.initial_step,
      {.doc = "continuation: first arclength step as a fraction of |to - from| when --step is not given",
       .bounds = left_open(0, 1)});
    v("analysis.continuation.max_step_factor", s.max_step_factor,
      {.doc = "continuation: the step adapts up to this multiple of the first", .bounds = closed(1, 1e6)});
    v("analysis.continuation.min_step", s.min_step,
      {.doc = "continuation: the branch ends where a step this small (fraction of |to - from|) fails; a change of "
              "the section's mode is reached to it",
       .bounds = open(0, 1)});
    v("analysis.continuation.locate_tolerance", s.locate_tolerance,
      {.doc = "continuation: folds, period doublings and Neimark-Sacker points located to this fraction of "
              "|to - from|",
       .bounds = open(0, 1)});
    v("analysis.continuation.label_tolerance", s.label_tolerance,
      {.doc = "continuation: gait changes located to this fraction of |to - from|", .bounds = open(0, 1)});
    v("analysis.continuation.parameter_step", s.parameter_step,
      {.doc = "continuation: dP/dp by sensitivity from the wheel at p +- this x max(|p|, |to - from|)",
       .bounds = open(0, 0.1)});
    v("analysis.continuation.mode_change_distance", s.mode_change_distance,
      {.doc = "continuation: a segment ends at a change of the section's mode when the map arrived in the other mode "
              "within this fraction of |to - from| of its last point",
       .bounds = open(0, 1)});
    v("analysis.continuation.mode_probes", s.mode_probes,
      {.doc = "continuation: at a change of the section's mode, Newton in the new mode this far beyond the boundary "
              "(fractions of |to - from|), each in turn",
       .bounds = left_open(0, 1)});
    v("analysis.continuation.back_distance", s.back_distance,
      {.doc = "continuation: the new mode's branch is continued back to the boundary, at most this fraction of "
              "|to - from| behind it",
       .bounds = closed(0, 1)});
    v("analysis.continuation.back_max_points", s.back_max_points,
      {.doc = "continuation: points of that backward branch, at most", .bounds = closed(2, 1000000)});
    v("analysis.continuation.join_tolerance", s.join_tolerance,
      {.doc = "continuation: the two modes' branches join when their ends meet to this, in q and in the scaled "
              "state",
       .bounds = open(0, 1)});
  }
};
inline Schema gait_continuation_schema() {
  return schema_of<GaitContinuationOptions>();
}
/// The tuning of a resolved configuration; throws ConfigError (key named) if min_step exceeds initial_step.
GaitContinuationOptions gait_continuation_from_config(const Config& config);

struct GaitContinuationSpec {
  std::string param;        ///< a real configuration key, or "rimless.mu" (μ_s = μ_k)
  double from = 0, to = 0;  ///< the interval, in the key's unit; the start at `from`
  double step = 0;          ///< first step in the key's unit (0: |to - from| / 50)
  Section section = Section::Touchdown;
  int period = 1;                          ///< continue fixed points of P^period (a period-k orbit)
  bool switch_at_period_doubling = false;  ///< also the period-2k branch born at the first period doubling
  /// ∂P/∂p by sensitivity (the variational equations' parameter column) where the map has an
  /// exact Jacobian and the key is a wheel parameter; false: central differences of the map.
  bool parameter_sensitivity = true;
  GaitContinuationOptions tuning{};  ///< analysis.continuation.* (gait_continuation_from_config)
  /// Called after each point of the branch with its q = (p - from)/(to - from) (e.g. to show progress).
  std::function<void(double q)> on_point = {};
};

/// One row of branch.csv: a point of the branch or a special point on it.
struct GaitBranchRow {
  double p = 0;                 ///< parameter value (key's unit)
  numerics::BranchPoint point;  ///< z, multipliers, stability (its p is q)
  SectionState section;         ///< the point on the section (its mode; z as in point)
  Eigen::VectorXd state;        ///< the point in the branch's columns (state_names)
  std::string gait;
  double period = 0;      ///< [s]
  double speed = 0;       ///< mean hub speed along the slope [m/s]
  double dissipated = 0;  ///< energy dissipated per step [J]
  std::string event;      ///< "start", "end: …", a special point's kind, or empty
};

/// Why a gait branch ended where the numerics' end (branch.end) does not say it all.
enum class GaitBranchEnd {
  AsContinued,             ///< branch.end says it
  SlideBalance,            ///< a vertical branch where μ_k = tan φ: a slide at any speed is a gait
  ModeChangeNotContinued,  ///< the section's mode changes and the new segment does not start or cross
};
constexpr std::array<EnumName<GaitBranchEnd>, 3> enum_names(GaitBranchEnd) {
  return {{{GaitBranchEnd::AsContinued, "as_continued"},
           {GaitBranchEnd::SlideBalance, "slide_balance"},
           {GaitBranchEnd::ModeChangeNotContinued, "mode_change_not_continued"}}};
}

struct GaitBranch {
  std::string param;
  std::vector<std::string> state_names;  ///< the columns: the largest mode's components (a sticking
                                         ///< point's ẋ is the one ċ = 0 gives)
  std::string mode;                      ///< the section's discrete mode at the start
  bool exact_jacobian = false;
  numerics::Branch branch;                         ///< in q, all segments joined (z in each segment's mode)
  int segments = 1;                                ///< pieces of the branch between changes of the section's mode
  int period = 1;                                  ///< fixed points of P^period
  std::vector<GaitBranch> switched;                ///< the period-2k branch switched to at the first period doubling
  std::vector<GaitBranchRow> rows;                 ///< points and special points in the order of arclength
  GaitBranchEnd end = GaitBranchEnd::AsContinued;  ///< with branch.end: how the branch ended
  std::string stop_reason;                         ///< why the branch ended, in the key's unit
  std::string failure;                             ///< nonempty when the start has no fixed point
  Section section = Section::Touchdown;            ///< the Poincaré section of its fixed points
  std::string computed_at;                         ///< branch_computed_at of the configuration it was continued in
};

/// What identifies a branch besides its key and section: sim.model and the wheel's keys
/// (rimless.*), each `key=value` (config.yaml's value text), joined by ';' in schema order, the keys
/// `param` sets (param_keys: they vary along the branch) left out. branch.csv's computed_at column.
std::string branch_computed_at(const Config& config, const std::string& param);

/// The keys of a computed_at text whose values differ from `config`'s, as "key = recorded (here:
/// value)", those `param` sets skipped; a key `config` does not know, or an entry that is not
/// `key=value`, is a difference too. Empty: the same wheel.
std::vector<std::string> computed_at_differences(const std::string& recorded, const Config& config,
                                                 const std::string& param);

/// The branch from the gait found at `from` (find_fixed_point from the configured initial state;
/// for period k > 1, Newton on P^k from the state the transient reaches). A row's period, speed,
/// dissipated energy and gait ("a / b" for the k steps) are those of the k steps.
/// Throws ConfigError when param is not a real key, from = to, or either end is not a valid value.
GaitBranch continue_gait(const Config& base, const GaitContinuationSpec& spec);

/// branch.csv: parameter, the state's components (state_names), mode (of each row), period, speed, dissipated_per_step,
/// gait, abs_lambda_k and arg_lambda_k for every multiplier (largest first), stable, residual, event, and what the
/// branch is of, the same on every row: key (the continued key), section, computed_at.
std::string gait_branch_csv(const GaitBranch& b);

/// The branch's summary record: param, points, reached_end, stop_reason, exact_jacobian, period,
/// segments, mode, section, failure (null when the start has a fixed point), and events (each
/// special point's parameter, event and gait). `rimless continuation --json` prints it and the
/// Python binding returns it.
nlohmann::ordered_json gait_branch_summary(const GaitBranch& b);

}  // namespace flexgait::rimless
