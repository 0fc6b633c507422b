#pragma once
/// \file disturbance.hpp
/// A push on the twin (issue 19): a constant force in the world frame on one body, from a start
/// time for a duration, applied through MuJoCo's `xfrc_applied` at the body's centre of mass
/// (so it adds no moment about that centre). None by default: no push while the force is zero.
///
/// The push acts over whole physics steps: step n (from t_n = n dt to t_n + dt) carries the force
/// when round(time/dt) <= n < round((time + duration)/dt), so the applied impulse is exactly
/// F dt (round((time + duration)/dt) − round(time/dt)) — F × duration when both are multiples of dt.
///
/// Only the single push of the keys disturbance.push.*: the configuration reader takes a mapping
/// of scalars (core/config_file.hpp refuses lists), so the list form is not read.
#include <array>
#include <cmath>

#include "flexgait/core/record.hpp"

namespace flexgait::humanoid {

/// Where a push acts.
enum class PushBody { kPelvis, kChest };
constexpr std::array<EnumName<PushBody>, 2> enum_names(PushBody) {
  return {{{PushBody::kPelvis, "pelvis"}, {PushBody::kChest, "chest"}}};
}

struct Push {
  double time = 0.0;                     ///< start [s]
  PushBody body = PushBody::kChest;
  std::array<double, 3> force{};         ///< world frame [N]
  double duration = 0.1;                 ///< [s]

  /// A push happens: some force over some time.
  bool active() const { return duration > 0 && (force[0] != 0 || force[1] != 0 || force[2] != 0); }
  /// |F| × duration [N s] (the nominal impulse; the plant reports what it applied).
  double impulse() const { return active() ? std::hypot(force[0], force[1], force[2]) * duration : 0.0; }

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("disturbance.push.time", s.time, {.unit = "s", .doc = "start of the push (simulated time)", .bounds = non_negative()});
    v("disturbance.push.body", s.body, {.doc = "body the push acts on (at its centre of mass)"});
    v("disturbance.push.force_x", s.force[0], {.unit = "N", .doc = "push force, world x (0 in all three: no push)",
                                               .bounds = closed(-1e5, 1e5)});
    v("disturbance.push.force_y", s.force[1], {.unit = "N", .doc = "push force, world y", .bounds = closed(-1e5, 1e5)});
    v("disturbance.push.force_z", s.force[2], {.unit = "N", .doc = "push force, world z", .bounds = closed(-1e5, 1e5)});
    v("disturbance.push.duration", s.duration, {.unit = "s", .doc = "how long the force acts", .bounds = closed(0, 1e4)});
  }
};

}  // namespace flexgait::humanoid
