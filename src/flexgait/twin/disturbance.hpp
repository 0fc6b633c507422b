#pragma once
/// \file disturbance.hpp
/// A push on the twin (docs/guide/humanoid.md): a constant force in the world frame on one body, from a start
/// time for a duration, applied through MuJoCo's `xfrc_applied` at the body's centre of mass
/// (so it adds no moment about that centre). None by default: no push while the force is zero.
///
/// The push acts over whole physics steps: step n (from t_n = n dt to t_n + dt) carries the force
/// when round(time/dt) <= n < round((time + duration)/dt), so the applied impulse is exactly
/// F dt (round((time + duration)/dt) − round(time/dt)) — F × duration when both are multiples of dt.
///
/// Pushes are given as a list, `disturbance.pushes: [{time: 4.1, body: chest, force: [0, 120, 0],
/// duration: 0.1}, ...]`, and one more by the keys disturbance.push.*; a push starts at its `time`
/// or, given `step` n ≥ 1, at the fraction `phase` of the walk's n-th single support
/// (experiments/push_timing.hpp; time, step and phase may be left out of an item);
/// `all_pushes` joins them (the single push after the list). Pushes that overlap in time add up.
#include <array>
#include <cmath>
#include <vector>

#include "flexgait/core/record.hpp"

namespace flexgait::twin {

/// Where a push acts.
enum class PushBody { kPelvis, kChest };
constexpr std::array<EnumName<PushBody>, 2> enum_names(PushBody) {
  return {{{PushBody::kPelvis, "pelvis"}, {PushBody::kChest, "chest"}}};
}

struct Push {
  double time = 0.0;  ///< start [s] (step 0)
  PushBody body = PushBody::kChest;
  std::array<double, 3> force{};  ///< world frame [N]
  double duration = 0.1;          ///< [s]
  int step = 0;                   ///< ≥ 1: start in this step's single support instead (1: the first step)
  double phase = 0.5;             ///< step ≥ 1: where in its single support (0 lift-off, 1 touchdown)

  /// A push happens: some force over some time.
  bool active() const { return duration > 0 && (force[0] != 0 || force[1] != 0 || force[2] != 0); }
  /// |F| × duration [N s] (the nominal impulse; the plant reports what it applied).
  double impulse() const { return active() ? std::hypot(force[0], force[1], force[2]) * duration : 0.0; }

  /// The fields of one item of disturbance.pushes.
  template <class Self, class Visit>
  static void visit_item_fields(Self& s, Visit& v) {
    v("time", s.time,
      {.unit = "s", .doc = "start of the push (simulated time)", .bounds = non_negative(), .optional = true});
    v("step", s.step,
      {.doc = "0: start at time; n >= 1: in the single support of the walk's n-th step",
       .bounds = closed(0, 100000),
       .optional = true});
    v("phase", s.phase,
      {.doc = "step >= 1: where in its single support the push starts (0 lift-off, 1 touchdown)",
       .bounds = closed(0, 1),
       .optional = true});
    v("body", s.body, {.doc = "body the push acts on (at its centre of mass)"});
    v("force", s.force, {.unit = "N", .doc = "push force, world frame [x, y, z]", .bounds = closed(-1e5, 1e5)});
    v("duration", s.duration, {.unit = "s", .doc = "how long the force acts", .bounds = closed(0, 1e4)});
  }

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("disturbance.push.time", s.time,
      {.unit = "s", .doc = "start of the push (simulated time)", .bounds = non_negative()});
    v("disturbance.push.step", s.step,
      {.doc = "0: the push starts at disturbance.push.time; n >= 1: in the single support of the walk's n-th step",
       .bounds = closed(0, 100000)});
    v("disturbance.push.phase", s.phase,
      {.doc = "disturbance.push.step >= 1: where in its single support the push starts (0 lift-off, 1 touchdown)",
       .bounds = closed(0, 1)});
    v("disturbance.push.body", s.body, {.doc = "body the push acts on (at its centre of mass)"});
    v("disturbance.push.force_x", s.force[0],
      {.unit = "N", .doc = "push force, world x (0 in all three: no push)", .bounds = closed(-1e5, 1e5)});
    v("disturbance.push.force_y", s.force[1], {.unit = "N", .doc = "push force, world y", .bounds = closed(-1e5, 1e5)});
    v("disturbance.push.force_z", s.force[2], {.unit = "N", .doc = "push force, world z", .bounds = closed(-1e5, 1e5)});
    v("disturbance.push.duration", s.duration,
      {.unit = "s", .doc = "how long the force acts", .bounds = closed(0, 1e4)});
  }
};

/// The pushes of `list` that happen (Push::active), then `single` if it happens.
inline std::vector<Push> all_pushes(const std::vector<Push>& list, const Push& single) {
  std::vector<Push> out;
  for (const Push& p : list)
    if (p.active()) out.push_back(p);
  if (single.active()) out.push_back(single);
  return out;
}

}  // namespace flexgait::twin
