#include "flexgait/humanoid/robot_params.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace flexgait::humanoid {
PlantParams plant_from_config(const Config& c) {
  PlantParams p = record_from_config<PlantParams>(c);
  const double ratio = p.control_period / p.physics_dt;
  if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio)
    throw ConfigError("plant.control_period",
                      fmt::format("key 'plant.control_period' = '{}': must be a whole multiple of plant.physics_dt = {} (s)",
                                  p.control_period, p.physics_dt));
  return p;
}

}  // namespace flexgait::humanoid
