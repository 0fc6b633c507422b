#pragma once
/// \file simulation_failure.hpp
/// Why the twin's simulation itself failed: the closed loop stops there (closed_loop.hpp).
#include <array>

#include "flexgait/core/enum_names.hpp"

namespace flexgait::loop {

/// Why the simulation itself failed (the loop stops there).
enum class SimulationFailure {
  kMuJoCoWarning,  ///< MuJoCo warned (it reset an unstable state or dropped contacts); HumanoidPlant::warnings_text
  kDiverged,       ///< the true state is no longer finite
};
constexpr std::array<EnumName<SimulationFailure>, 2> enum_names(SimulationFailure) {
  return {{{SimulationFailure::kMuJoCoWarning, "mujoco_warning"}, {SimulationFailure::kDiverged, "diverged"}}};
}

}  // namespace flexgait::loop
