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

/// off, both (full form), both (thesis form), robotis, talos, both-measured, both-dynamic,
/// both-dynamic-horizontal (control.plan_horizontal_force 0.5) and both-dynamic-horizontal-lag (the same
/// with the gears' lag believed: control.gear_damping = plant.gear_damping, control.load_filter_time
/// 0.02 s), from `base` (its other settings kept).
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
