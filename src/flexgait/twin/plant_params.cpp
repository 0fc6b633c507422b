#include "flexgait/twin/plant_params.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace flexgait::twin {
PlantParams plant_from_config(const Config& c) {
  PlantParams p = record_from_config<PlantParams>(c);
  const double ratio = p.control_period / p.physics_dt;
  if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio)
    throw ConfigError(
        "plant.control_period",
        fmt::format("key 'plant.control_period' = '{}': must be a whole multiple of plant.physics_dt = {} (s)",
                    p.control_period, p.physics_dt));
  for (int i = 0; i < humanoid::kSensors; ++i) {
    const FaultSpec& f = p.faults.sensor[i];
    if (f.kind == FaultKind::kLatency && !(f.delay > 0)) {
      const std::string key = "plant.faults." + std::string(humanoid::kSensorNames[i]) + ".delay";
      throw ConfigError(
          key, fmt::format("key '{}' = '{}': a latency fault (plant.faults.{}.kind = latency) needs a delay > 0 (s)",
                           key, f.delay, humanoid::kSensorNames[i]));
    }
  }
  return p;
}

}  // namespace flexgait::twin
