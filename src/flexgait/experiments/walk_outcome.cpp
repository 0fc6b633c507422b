#include "flexgait/experiments/walk_outcome.hpp"

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
