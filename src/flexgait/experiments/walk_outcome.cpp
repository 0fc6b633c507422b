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
