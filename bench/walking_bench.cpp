// Walking controller benchmarks (issue 6): one controller update (target ≤ 20 µs on this
// machine) and the closed-loop walk's real-time factor (controller + twin), 1.0 s per step.
#include <benchmark/benchmark.h>

#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/walking/walking_controller.hpp"

namespace {

using namespace flexgait;

// update() over a whole 10-step plan with plausible standing sensor readings (the cost does not
// depend on the readings' values).
void ControllerUpdate(benchmark::State& state) {
  walking::WalkParams w;
  walking::WalkingController c(humanoid::RobotParams{}, w, walking::BalanceParams{}, 0.004);
  humanoid::SensorReadings s;
  for (auto& ft : s.ft) ft.force = {0, 0, -250.0};
  const long ticks = static_cast<long>(c.plan().duration / 0.004);
  long k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.update(s, static_cast<double>(k) * 0.004));
    if (++k == ticks) k = 0;
  }
}
BENCHMARK(ControllerUpdate)->Unit(benchmark::kMicrosecond);

void ClosedLoopWalk(benchmark::State& state) {
  experiments::WalkRunParams p;
  p.plant.k_joint.fill(1000.0);
  p.walk.steps = 10;
  p.walk.step_time = 1.0;
  double simulated = 0;
  for (auto _ : state) {
    const experiments::WalkResult r = experiments::run_walk(p);
    simulated += r.metrics.simulated_time;
    if (r.metrics.fell) state.SkipWithError("the walk fell");
  }
  state.counters["real_time_factor"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
}
BENCHMARK(ClosedLoopWalk)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
