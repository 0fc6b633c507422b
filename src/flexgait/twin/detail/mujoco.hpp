#pragma once
/// \file mujoco.hpp
/// MuJoCo's types behind the twin's public headers, for the twin's own sources and the tests (not
/// installed: MuJoCo is a private dependency of flexgait::twin).
#include <mujoco/mujoco.h>

#include <string>

namespace flexgait::twin {

class HumanoidPlant;

/// Loads MJCF text into a model (through MuJoCo's virtual file system). Throws std::runtime_error
/// with MuJoCo's message on failure. The caller owns the model (mj_deleteModel).
mjModel* load_mjcf(const std::string& xml);

/// The number of warnings counted in `d` so far (all kinds).
int mujoco_warning_count(const mjData* d);

/// The warnings counted in `d` so far, as one line ("" if none), e.g. "Nan, Inf or huge value
/// in QACC at DOF 0. The simulation is unstable. (3 times)"; kinds joined by "; ".
std::string mujoco_warnings_text(const mjData* d);

/// The plant's model and state (for rendering, benchmarks and tests; nothing here feeds a controller).
const mjModel* plant_model(const HumanoidPlant& plant);
const mjData* plant_data(const HumanoidPlant& plant);

}  // namespace flexgait::twin
