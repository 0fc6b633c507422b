#pragma once
/// \file walk_outcome.hpp
/// How a humanoid walk ended early, as reasons with their names (docs/guide/library.md:
/// a run that stops early says why): a fall (FallReason) or a failure of the simulation itself (WalkFailure). The
/// text that summary.json and the console show is made from the reason (and its detail).
#include <array>
#include <string>
#include <string_view>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/loop/simulation_failure.hpp"
#include "flexgait/robot/sensor_ids.hpp"
#include "flexgait/walking/sensor_health.hpp"

namespace flexgait::experiments {

/// Why the walk did not walk: the robot fell or lost the support its plan stands on (checked
/// every control period and at each landing by WalkJudge, walk_judge.hpp).
enum class FallReason {
  kPelvisTooLow,    ///< pelvis above the floor lower than walk.pelvis_height − fall_height
  kPelvisTilted,    ///< |roll| or |pitch| of the pelvis beyond fall_tilt
  kNonSoleContact,  ///< a body other than a sole touched the floor
  kFlipped,         ///< the pelvis turned upside down (its z axis points down)
  kAirborne,        ///< no body touched the floor for longer than a walking gait allows
  kSlid,            ///< a standing sole slid away from its planned place
  kMissedStep,      ///< a step's sole did not land (off the floor, or away from its planned place)
  kUnsupported,     ///< at the end, a sole the plan stands on was off the floor or on an edge
};
constexpr std::array<EnumName<FallReason>, 8> enum_names(FallReason) {
  return {{{FallReason::kPelvisTooLow, "pelvis_too_low"},
           {FallReason::kPelvisTilted, "pelvis_tilted"},
           {FallReason::kNonSoleContact, "non_sole_contact"},
           {FallReason::kFlipped, "flipped"},
           {FallReason::kAirborne, "airborne"},
           {FallReason::kSlid, "slid"},
           {FallReason::kMissedStep, "missed_step"},
           {FallReason::kUnsupported, "unsupported"}}};
}
/// summary.json's fall_reason: "pelvis too low", "pelvis tilted beyond the limit", "a body other
/// than a sole touched the floor", "airborne: ...", ...
std::string_view fall_sentence(FallReason reason);

using loop::SimulationFailure;  ///< why the simulation itself failed (the walk ends there)

struct WalkFailure {
  SimulationFailure reason = SimulationFailure::kDiverged;
  std::string detail;  ///< MuJoCo's warnings (kMuJoCoWarning); empty otherwise
  /// "MuJoCo: <warnings>" or "the simulation diverged: a non-finite state" (summary.json's failure).
  std::string text() const;
};

/// Why the controller stopped the walk safely (walking::SafeStop): a sensor it uses stayed bad for
/// longer than health.hold_time; the plan was cut at the next double support.
struct SafeStopReason {
  humanoid::SensorId sensor = humanoid::kSensors;          ///< the sensor that failed
  walking::SignalFault fault = walking::SignalFault::kOk;  ///< how it failed (nan, stale, stuck)
  double hold_time = 0;                                    ///< health.hold_time [s]
  int steps_kept = 0;                                      ///< steps of the plan still taken
  int steps_planned = 0;                                   ///< steps of the plan
  /// summary.json's safe_stop_reason: "sensor ft_right nan for longer than health.hold_time =
  /// 0.3 s; walk cut to 3 of 10 steps".
  std::string text() const;
};

}  // namespace flexgait::experiments
