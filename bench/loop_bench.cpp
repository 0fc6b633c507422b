// The closed loop's own cost (docs/guide/loop.md): one control period of the builtin walking
// controller through loop::HumanoidLoop against the same parts called by hand (controller update,
// compensation stage, plant step) without the loop. The loop adds the true state it reads after
// each period (its soundness check and the observers' record). Target: at most 5 % more.
// Both walk a plain `flexgait humanoid walk` (the default 10-step plan at 1 s/step, the default compensation case
// both-dynamic-horizontal-lag) from its start, again and again; the loop's time per period is the mean over that
// cycle.
#include <benchmark/benchmark.h>

#include "flexgait/core/config.hpp"
#include "flexgait/experiments/walk_experiment.hpp"

namespace {

namespace fg = flexgait;

fg::experiments::WalkRunParams default_walk() {
  return fg::experiments::walk_run_from_config(
      fg::resolve_config(fg::experiments::walk_run_schema(), std::nullopt, {}));
}

void LoopPeriod(benchmark::State& state) {
  const fg::experiments::WalkRunParams params = default_walk();
  fg::experiments::WalkLoop w = fg::experiments::make_walk_loop(params);
  const double end = w.control->controller().plan().duration;
  for (auto _ : state) {
    if (w.loop->time() >= end) {
      state.PauseTiming();
      w = fg::experiments::make_walk_loop(params);
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(w.loop->step());
  }
}
BENCHMARK(LoopPeriod)->Unit(benchmark::kMicrosecond)->MinTime(3.0);

/// The same period by hand: what the loop composes, with nothing of its own.
struct ByHand {
  fg::experiments::WalkRunParams params = default_walk();
  fg::walking::WalkingController controller{fg::experiments::walk_controller_model(params),
                                            params.walk,
                                            params.balance,
                                            params.plant.control_period,
                                            params.estimator,
                                            params.health};
  fg::loop::CompensationStage stage{
      controller.model(), params.control, params.plant.control_period,
      fg::experiments::walk_loop_setup(params, controller.model(), controller.plan()).windows};
  fg::twin::HumanoidPlant plant{fg::experiments::walk_twin(params), params.plant};
  long k = 0;
  ByHand() {
    controller.set_plan_motion(params.control.load_model == fg::compensation::LoadModel::kDynamic);
    plant.reset(controller.initial_pose());
  }
  void period() {
    const double t = static_cast<double>(k++) * params.plant.control_period;
    const fg::humanoid::JointVector& desired = controller.update(stage.feedback(plant.sensors()), t);
    fg::loop::ControlContext context{controller.sensors(), fg::loop::support_plan(controller, t), controller.attitude(),
                                     controller.status().sensor_flags == 0};
    const fg::humanoid::JointVector& command = stage.command(desired, context, t);
    controller.sent(command);
    plant.step(command);
  }
};

void ByHandPeriod(benchmark::State& state) {
  auto parts = std::make_unique<ByHand>();
  const double end = parts->controller.plan().duration;
  for (auto _ : state) {
    if (parts->plant.time() >= end) {
      state.PauseTiming();
      parts = std::make_unique<ByHand>();
      state.ResumeTiming();
    }
    parts->period();
  }
}
BENCHMARK(ByHandPeriod)->Unit(benchmark::kMicrosecond)->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
