#pragma once
/// \file walk_judge.hpp
/// Whether a walk walked, judged from the ground truth alone (evaluation code: the controller
/// never sees it). A walk is walked only if every planned step landed — the swing sole on the
/// floor once the foot has settled (at the latest when the next step lifts: landing_due in
/// walk_scorer.hpp), placed relative to the standing sole within
/// `position_tolerance` of the plan's step — and the robot stayed supported: some body touches
/// the floor at least every `airborne_time`, no standing sole slides more than
/// `position_tolerance` from where it came down, the pelvis is neither sunk nor tilted nor upside
/// down, and at the end every sole the plan stands on is on the floor. The first violation is the walk's named outcome
/// (FallReason); the walk ends there.
///
/// Steps are judged relative to the standing sole, not in the world: the controller walks in its
/// own frame (it has no global position), so a walk that drifts as a whole — 4.5 cm over 10 steps
/// at 1 s/step on the flat, more on rough floors — still takes the steps it planned (the worst
/// step relative to its stance foot: 1.0–3.5 cm over the bundled walk configurations).
///
/// The limits and why:
///  - position_tolerance: half the sole's narrower side. The plan puts the ZMP reference under
///    the planned sole; a sole farther than this from its planned place relative to its support
///    has that reference at or beyond its edge, so the plan's support no longer exists.
///  - airborne_time: a walking gait has no flight phase (one sole is always down); a robot with
///    nothing on the floor for this long (0.1 s: free fall of 4.9 cm from rest) was thrown.
///  - sole_lift_tolerance: a tenth of the sole's length. A sole whose centre is higher than this
///    above the floor at the end rests on an edge (tilted by more than ~0.2 rad), not flat.
///  - fall_height, fall_tilt: the pelvis sunk or tilted (the thresholds of the fall check).
#include <Eigen/Core>

#include <array>
#include <optional>

#include "flexgait/experiments/walk_outcome.hpp"

namespace flexgait::experiments {

struct JudgeLimits {
  double pelvis_height = 0;        ///< the walk's pelvis height above the floor [m]
  double fall_height = 0.2;        ///< fallen when the pelvis sinks this far below it [m]
  double fall_tilt = 0.6;          ///< or its roll or pitch exceeds this [rad]
  double airborne_time = 0.1;      ///< longest time with no body on the floor [s]
  double position_tolerance = 0;   ///< largest slide of a standing sole, and error of a step [m]
  double sole_lift_tolerance = 0;  ///< at the end, a standing sole's centre above the floor, at most [m]
};

/// The ground truth of one control period, in the plan's frame (horizontal positions).
struct SupportSample {
  double t = 0;                                            ///< [s]
  std::array<bool, 2> sole_contact{};                      ///< each sole touches the floor
  bool other_contact = false;                              ///< a body other than a sole touches the floor
  double pelvis_height = 0;                                ///< pelvis above the floor under it [m]
  Eigen::Matrix3d pelvis_R = Eigen::Matrix3d::Identity();  ///< pelvis attitude (world)
  std::array<Eigen::Vector2d, 2> sole{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};  ///< true sole centres [m]
  std::array<double, 2> sole_height{};  ///< each sole centre above the floor under it [m]
};

/// The plan at that period: where each sole should be, and which swings.
struct PlannedSupport {
  std::array<Eigen::Vector2d, 2> sole{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};  ///< [m]
  std::array<bool, 2> swinging{};
};

/// Judges a walk period by period. Keeps only the time of the last floor contact and where each
/// standing sole came down (and the largest slide, a score): constant memory whatever the walk's
/// length.
class WalkJudge {
 public:
  explicit WalkJudge(const JudgeLimits& limits) : limits_(limits) {}

  /// The outcome this period's truth shows, if the walk must end here (checked in the order:
  /// sunk, flipped, tilted, a non-sole body down, airborne, a standing sole slid).
  std::optional<FallReason> check(const SupportSample& s, const PlannedSupport& plan);
  /// A step's landing, once the foot has settled: kMissedStep when the swing sole `side` is not
  /// on the floor, or its place relative to the other sole differs from the plan's (`plan`, both
  /// soles where the plan has them now) by more than position_tolerance.
  std::optional<FallReason> landing(const SupportSample& s, int side, const PlannedSupport& plan) const;
  /// At the walk's end: kAirborne when no sole is on the floor, kUnsupported when a sole the plan
  /// stands on (`plan`, not swinging) is off it or rests on an edge (its centre higher than
  /// sole_lift_tolerance).
  std::optional<FallReason> at_end(const SupportSample& s, const PlannedSupport& plan) const;

  /// Largest slide of a standing sole (on the floor, not swinging) from where it came down [m].
  double support_error_max() const { return support_error_max_; }
  const JudgeLimits& limits() const { return limits_; }

 private:
  JudgeLimits limits_;
  std::optional<double> last_contact_;  ///< time of the last period with a body on the floor [s]
  std::array<Eigen::Vector2d, 2> anchor_{Eigen::Vector2d::Zero(),
                                         Eigen::Vector2d::Zero()};  ///< where each standing sole came down [m]
  std::array<bool, 2> anchored_{};                                  ///< the sole is down and standing: anchor_ holds
  double support_error_max_ = 0;
};

}  // namespace flexgait::experiments
