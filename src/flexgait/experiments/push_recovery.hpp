#pragma once
/// \file push_recovery.hpp
/// The largest recoverable push (docs/guide/campaigns.md): bisection on the impulse of a push of fixed duration
/// and direction, each trial a whole run of the twin from the same configuration; beside it the
/// capture-point bound of the same situation (summary.json's capture_point_bound), so the result
/// reads as a fraction of the physical limit of an ankle strategy.
///
/// As an experiment (`flexgait campaign humanoid-push-recovery`, `push_recovery.*` keys): a
/// situation — standing, or walking at mid single support of a given step — and a direction in
/// the plan's frame, the push's body and duration from disturbance.push.*.
#include <Eigen/Dense>
#include <array>
#include <functional>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/experiments/walk_experiment.hpp"

namespace flexgait::experiments {

struct PushRecovery {
  double recovered = 0;  ///< largest impulse recovered (no fall) [N s]
  double fell = 0;       ///< smallest impulse seen to fall [N s] (recovered < fell ≤ recovered + tolerance)
  double bound = 0;      ///< capture-point bound for the push's direction [N s]
  int runs = 0;
  bool bracketed = true;  ///< false: `upper` itself was recovered (recovered = upper, fell = NaN)
};

/// The bracket of a fall threshold on the impulse [N s], given `falls(J)` (one run of the twin per
/// call), `lower` (an impulse known to be recovered; 0 for none) and `upper`:
/// - scan_step = 0: bisection on [lower, upper] to `tolerance`, `upper` tried first. It assumes
///   one threshold (every push below it recovered, every push above it falls). Where the outcome
///   is not monotone in the impulse, it can end on an island of recovery above the first fall.
/// - scan_step > 0: `falls` at lower + scan_step, lower + 2 scan_step, ... (below upper) until the
///   first fall, then bisection between it and the scan point before it; no fall on the scan:
///   upper is tried. `recovered` is then the first fall's lower end: every scan point below it was
///   recovered (a window of falls narrower than scan_step can still lie between them).
/// If upper is recovered (the bracket is too narrow), `bracketed` is false, recovered = upper and
/// fell = NaN.
PushRecovery bracket_first_fall(const std::function<bool(double)>& falls, double lower, double upper, double tolerance,
                                double scan_step = 0);

/// Pushes `base.push.body` at `base.push.time` for `base.push.duration` in the horizontal
/// `direction`: bracket_first_fall on the impulse from `lower` (recovered) to `upper`, to
/// `tolerance` [N s]; `bound` is the capture-point bound of the push's situation.
PushRecovery largest_recoverable_push(WalkRunParams base, const Eigen::Vector2d& direction, double upper,
                                      double tolerance = 1.0, double scan_step = 0, double lower = 0);

enum class PushSituation { kStanding, kWalking };
constexpr std::array<EnumName<PushSituation>, 2> enum_names(PushSituation) {
  return {{{PushSituation::kStanding, "standing"}, {PushSituation::kWalking, "walking"}}};
}

/// Horizontal push directions in the world frame (the plan walks along +x, the robot's left is +y).
enum class PushDirection { kForward, kBackward, kLeft, kRight };
constexpr std::array<EnumName<PushDirection>, 4> enum_names(PushDirection) {
  return {{{PushDirection::kForward, "forward"},
           {PushDirection::kBackward, "backward"},
           {PushDirection::kLeft, "left"},
           {PushDirection::kRight, "right"}}};
}

/// The unit vector of a direction.
Eigen::Vector2d push_direction_vector(PushDirection d);

/// What one largest-recoverable-push measurement varies (keys push_recovery.*).
struct PushRecoveryParams {
  PushSituation situation = PushSituation::kStanding;
  PushDirection direction = PushDirection::kForward;
  double stand_time = 4.0;   ///< standing: the push starts then (the dcm mode's COM bias has settled) [s]
  double settle_time = 3.0;  ///< standing: simulated after the push starts (a fall shows within it) [s]
  int step = 3;              ///< walking: the push starts at mid single support of this step (1 = the first)
  double upper = 100.0;      ///< first upper end of the bisection; doubled while recovered, at most 3 times [N s]
  double tolerance = 1.0;    ///< bisection to this width [N s]
  double scan_step = 0;      ///< > 0: scan up at this step to the first fall, then bisect (bracket_first_fall) [N s]

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("push_recovery.situation", s.situation,
      {.doc = "standing (walk.steps 0, the push at stand_time) or walking (the push at mid single support of step)"});
    v("push_recovery.direction", s.direction, {.doc = "horizontal push direction, world frame (the walk goes +x)"});
    v("push_recovery.stand_time", s.stand_time,
      {.unit = "s", .doc = "standing: start of the push", .bounds = closed(0.5, 100)});
    v("push_recovery.settle_time", s.settle_time,
      {.unit = "s", .doc = "standing: simulated after the push starts", .bounds = closed(0.5, 100)});
    v("push_recovery.step", s.step,
      {.doc = "walking: the push starts at mid single support of this step (1: the first)", .bounds = closed(1, 1000)});
    v("push_recovery.upper", s.upper,
      {.unit = "N s",
       .doc = "first upper end of the bisection (doubled while recovered, at most 3 times)",
       .bounds = closed(1, 1e4)});
    v("push_recovery.tolerance", s.tolerance,
      {.unit = "N s", .doc = "width the bisection ends at", .bounds = closed(0.01, 100)});
    v("push_recovery.scan_step", s.scan_step,
      {.unit = "N s",
       .doc = "0: bisection on [0, upper] (assumes one threshold); > 0: scan up at this step to the first fall, "
              "then bisect between it and the scan point before",
       .bounds = closed(0, 1e4)});
  }
};

/// A push-recovery measurement: the run (its disturbance.push.body and duration) and the test.
struct PushRecoveryRunParams {
  WalkRunParams run;
  PushRecoveryParams test;

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    WalkRunParams::visit_fields(s.run, v);
    PushRecoveryParams::visit_fields(s.test, v);
  }
};

inline Schema push_recovery_schema() {
  return schema_of<PushRecoveryRunParams>();
}

/// The measurement's parameters; throws ConfigError as walk_run_from_config, and naming the key
/// when disturbance.push.force_* or disturbance.push.time is set (the test sets them), when
/// push_recovery.scan_step is finer than push_recovery.tolerance (but not 0), when
/// disturbance.push.duration is 0, or when walking and push_recovery.step is not a step before
/// the last (walk.steps).
PushRecoveryRunParams push_recovery_from_config(const Config& config);

/// The result (summary.json of a point).
struct PushRecoveryResult {
  PushSituation situation = PushSituation::kStanding;
  PushDirection direction = PushDirection::kForward;
  double push_time = 0;  ///< [s]
  double recovered = 0;  ///< largest impulse recovered (with a scan: below the first fall) [N s]
  double fell_at = 0;    ///< smallest impulse seen to fall [N s]; null if none fell (recovered is then a lower bound)
  double bound = 0;      ///< capture-point bound of the situation in the push's direction [N s]
  double fraction = 0;   ///< recovered / bound
  int runs = 0;          ///< runs of the twin

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("situation", s.situation, {.doc = "push_recovery.situation"});
    v("direction", s.direction, {.doc = "push_recovery.direction"});
    v("push_time", s.push_time, {.unit = "s", .doc = "start of the push"});
    v("recovered", s.recovered, {.unit = "N s", .doc = "largest impulse recovered without a fall"});
    v("fell_at", s.fell_at, {.unit = "N s", .doc = "smallest impulse seen to fall (null: none fell up to 8 x upper)"});
    v("bound", s.bound, {.unit = "N s", .doc = "capture-point bound m w0 d in the push's direction at its start"});
    v("fraction", s.fraction, {.doc = "recovered / bound"});
    v("runs", s.runs, {.doc = "runs of the twin"});
  }
};

/// The push's start time of a measurement [s].
double push_recovery_time(const PushRecoveryRunParams& p);

/// The measurement: the push at push_recovery_time, bracket_first_fall on [0, upper] (with
/// push_recovery.scan_step), upper doubled while it is recovered (at most 3 times; then fell_at
/// is NaN, null in JSON; a scan goes on from the last upper, a bisection starts again from 0).
PushRecoveryResult run_push_recovery(const PushRecoveryRunParams& p);

}  // namespace flexgait::experiments
