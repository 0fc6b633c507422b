#pragma once
/// \file compensation_study.hpp
/// The thesis's walking experiments 2-4 (docs/theory/humanoid.md) as sets of walks that differ in one
/// thing, and their comparison:
///  - compensation study: the same gait with compensation off, both compensators with the full
///    gravity torque, and both with the thesis form (eq. 4 only) — pelvis error (Fig. 13), ZMP
///    tracking (Fig. 14), estimated against true joint angles, Newton against the conventional
///    estimate (Fig. 15) — and beside them the field's baselines (robotis, talos) and ours with
///    the measured and dynamic loads (docs/guide/compensation.md), in one table;
///  - stiffness mismatch: the twin's true stiffness scaled against the controller's belief
///    (control.k_joint), compensation off and both, balance controller as configured.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flexgait/experiments/walk_experiment.hpp"

namespace flexgait::experiments {

struct StudyCase {
  std::string name;  ///< directory name of its run
  WalkRunParams params;
};

/// The name of the compensation case a run's settings make (summary.json's compensation_case, the
/// compensation study's directories): off, robotis, talos, or the compensators (input, output, both)
/// followed by what they believe beyond the thesis's gravity loads — -thesis-form (eq. 4 only), -measured or
/// -dynamic (control.load_model), -horizontal (control.plan_horizontal_force 1; another share f: -horizontal-f),
/// -lag (control.gear_damping at plant.gear_damping; another value d: -lag-d). The default of
/// `humanoid walk` is both-dynamic-horizontal-lag.
std::string compensation_case_name(const WalkRunParams& params);

/// off, both (full form), both (thesis form), robotis, talos, both-measured, both-dynamic,
/// both-dynamic-horizontal (control.plan_horizontal_force 1) and both-dynamic-horizontal-lag (the same
/// with the gears' lag believed: control.gear_damping = plant.gear_damping, control.load_filter_time
/// 0.02 s: the default of `humanoid walk`), from `base`. Each case sets every compensation key that names it
/// (the cases without the lag: no damping believed, the F/T low-pass 0.1 s); the other settings are the base's.
std::vector<StudyCase> compensation_cases(const WalkRunParams& base);
/// For each scale s: the twin's k_joint = s × its configured value, compensation off and both.
std::vector<StudyCase> mismatch_cases(const WalkRunParams& base, const std::vector<double>& scales);

/// A compensation study's record (its comparison.json): each case's summary and the headline
/// numbers (cut of the peak pelvis roll error, single-support ZMP tracking, the estimator's error share).
nlohmann::ordered_json compensation_comparison(const std::vector<StudyCase>& cases,
                                               const std::vector<WalkResult>& results);
/// A mismatch study's record (its comparison.json): per scale, off against both.
nlohmann::ordered_json mismatch_comparison(const std::vector<StudyCase>& cases, const std::vector<WalkResult>& results);

}  // namespace flexgait::experiments
