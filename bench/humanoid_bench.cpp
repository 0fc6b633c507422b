// Humanoid twin benchmarks: one plant physics step (elastic drives + sensors) against a
// bare mj_step of the same model (target: the actuator and sensor layer adds at most 20 %), and
// the real-time factor of standing.
#include <benchmark/benchmark.h>

#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/plant.hpp"

namespace {

using namespace flexgait::humanoid;
using namespace flexgait::twin;

PlantParams plant_params() {
  PlantParams p;
  return p;
}

// A control period of the plant (4 physics steps), per physics step.
void PlantStep(benchmark::State& state) {
  HumanoidPlant plant(RobotParams{}, plant_params());
  const JointVector pose = standing_pose(RobotParams{}, 0.75);
  plant.reset(pose);
  for (auto _ : state) plant.step(pose);
  state.counters["us/physics_step"] = benchmark::Counter(static_cast<double>(state.iterations() * 4),
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["real_time_factor"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * plant.params().control_period, benchmark::Counter::kIsRate);
}
BENCHMARK(PlantStep)->Unit(benchmark::kMicrosecond);

// The same model and state advanced by bare mj_step (no gear springs: the plant applies them).
void BareMujocoStep(benchmark::State& state) {
  HumanoidPlant plant(RobotParams{}, plant_params());
  plant.reset(standing_pose(RobotParams{}, 0.75));
  mjModel* m = mj_copyModel(nullptr, plant_model(plant));
  mjData* d = mj_copyData(nullptr, m, plant_data(plant));
  for (auto _ : state) {
    for (int k = 0; k < 4; ++k) mj_step(m, d);
  }
  state.counters["us/physics_step"] = benchmark::Counter(static_cast<double>(state.iterations() * 4),
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  mj_deleteData(d);
  mj_deleteModel(m);
}
BENCHMARK(BareMujocoStep)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
