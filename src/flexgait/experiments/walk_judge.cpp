#include "flexgait/experiments/walk_judge.hpp"

#include <algorithm>
#include <cmath>

#include "flexgait/walking/rotation.hpp"

namespace flexgait::experiments {

std::optional<FallReason> WalkJudge::check(const SupportSample& s, const PlannedSupport& plan) {
  const JudgeLimits& L = limits_;
  // (the pelvis's z axis pointing down: over on its back or front, or thrown end over end)
  // (the order of the fall check before the judge: sunk, tilted, a non-sole body down)
  if (s.pelvis_height < L.pelvis_height - L.fall_height) return FallReason::kPelvisTooLow;
  // (the pelvis's z axis pointing down: over on its back or front, or thrown end over end)
  if (s.pelvis_R(2, 2) < 0) return FallReason::kFlipped;
  if (std::abs(walking::roll_of(s.pelvis_R)) > L.fall_tilt || std::abs(walking::pitch_of(s.pelvis_R)) > L.fall_tilt)
    return FallReason::kPelvisTilted;
  if (s.other_contact) return FallReason::kNonSoleContact;
  const bool down = s.sole_contact[0] || s.sole_contact[1];
  if (down || !last_contact_) last_contact_ = s.t;  // (the walk starts standing)
  if (!down && s.t - *last_contact_ > L.airborne_time) return FallReason::kAirborne;
  for (int side = 0; side < 2; ++side) {
    if (plan.swinging[side] || !s.sole_contact[side]) {
      anchored_[side] = false;
      continue;
    }
    if (!anchored_[side]) {  // it came down now
      anchor_[side] = s.sole[side];
      anchored_[side] = true;
    }
    const double slide = (s.sole[side] - anchor_[side]).norm();
    support_error_max_ = std::max(support_error_max_, slide);
    if (slide > L.position_tolerance) return FallReason::kSlid;
  }
  return std::nullopt;
}

std::optional<FallReason> WalkJudge::landing(const SupportSample& s, int side, const PlannedSupport& plan) const {
  const int other = 1 - side;
  const Eigen::Vector2d step = s.sole[side] - s.sole[other], planned = plan.sole[side] - plan.sole[other];
  if (!s.sole_contact[side] || (step - planned).norm() > limits_.position_tolerance) return FallReason::kMissedStep;
  return std::nullopt;
}

std::optional<FallReason> WalkJudge::at_end(const SupportSample& s, const PlannedSupport& plan) const {
  if (!s.sole_contact[0] && !s.sole_contact[1]) return FallReason::kAirborne;
  for (int side = 0; side < 2; ++side)
    if (!plan.swinging[side] && (!s.sole_contact[side] || s.sole_height[side] > limits_.sole_lift_tolerance))
      return FallReason::kUnsupported;
  return std::nullopt;
}

}  // namespace flexgait::experiments
