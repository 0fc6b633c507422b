#include "flexgait/experiments/walk_outcome.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace flexgait::experiments {

std::string_view fall_sentence(FallReason reason) {
  switch (reason) {
    case FallReason::kPelvisTooLow:
      return "pelvis too low";
    case FallReason::kPelvisTilted:
      return "pelvis tilted beyond the limit";
    case FallReason::kNonSoleContact:
      return "a body other than a sole touched the floor";
    case FallReason::kFlipped:
      return "the pelvis turned upside down";
    case FallReason::kAirborne:
      return "airborne: no body touched the floor for longer than a walking gait allows";
    case FallReason::kSlid:
      return "a standing sole slid away from its planned place";
    case FallReason::kMissedStep:
      return "a step did not land where planned";
    case FallReason::kUnsupported:
      return "at the end a sole the plan stands on was off the floor or on an edge";
  }
  throw std::logic_error("FallReason without a sentence");
}

std::string SafeStopReason::text() const {
  return fmt::format("sensor {} {} for longer than health.hold_time = {} s; walk cut to {} of {} steps",
                     humanoid::kSensorNames[sensor], name_of(fault), hold_time, steps_kept, steps_planned);
}

std::string WalkFailure::text() const {
  switch (reason) {
    case SimulationFailure::kMuJoCoWarning:
      return "MuJoCo: " + detail;
    case SimulationFailure::kDiverged:
      return "the simulation diverged: a non-finite state";
  }
  throw std::logic_error("SimulationFailure without a text");
}

}  // namespace flexgait::experiments
