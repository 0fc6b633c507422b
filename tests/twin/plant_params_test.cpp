// The twin's plant parameters from a configuration (twin/plant_params.hpp): the defaults are
// accepted; a control period that is not a whole number of physics steps and a latency fault
// without a delay are refused, naming their keys.
#include "flexgait/twin/plant_params.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace flexgait::twin {
namespace {

std::string refused_key(const std::vector<std::string>& sets) {
  try {
    plant_from_config(resolve_config(plant_schema(), std::nullopt, sets));
  } catch (const ConfigError& e) {
    return e.key();
  }
  return "";
}

TEST(PlantParams, DefaultsAreAccepted) {
  const PlantParams p = plant_from_config(resolve_config(plant_schema(), std::nullopt, {}));
  EXPECT_EQ(p.k_joint, PlantParams{}.k_joint);
  EXPECT_EQ(refused_key({}), "");
}

TEST(PlantParams, ControlPeriodMustBeAWholeNumberOfPhysicsSteps) {
  EXPECT_EQ(refused_key({"plant.physics_dt=0.001", "plant.control_period=0.004"}), "");
  EXPECT_EQ(refused_key({"plant.physics_dt=0.001", "plant.control_period=0.0045"}), "plant.control_period");
}

TEST(PlantParams, LatencyFaultNeedsADelay) {
  EXPECT_EQ(refused_key({"plant.faults.gyro.kind=latency"}), "plant.faults.gyro.delay");
  EXPECT_EQ(refused_key({"plant.faults.gyro.kind=latency", "plant.faults.gyro.delay=0.01"}), "");
  EXPECT_EQ(refused_key({"plant.faults.encoder.kind=dropout"}), "");
}

}  // namespace
}  // namespace flexgait::twin
