// Walking controller benchmarks: one controller update (issue 6, target ≤ 20 µs on this machine),
// the update with both deformation compensators (issue 7, target ≤ 30 µs), each compensator
// alone, and the closed-loop walk's real-time factor (controller + compensators + twin), 1.0 s
// per step.
#include <benchmark/benchmark.h>

#include <string>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/compensation/stiffness_estimator.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/walking/walking_controller.hpp"

namespace {

using namespace flexgait;

// update() over a whole 10-step plan with plausible standing sensor readings (the cost does not
// depend on the readings' values).
// Argument: walking::BalanceMode (0 pd, 1 dcm).
void ControllerUpdate(benchmark::State& state) {
  walking::WalkParams w;
  walking::BalanceParams balance;
  balance.mode = static_cast<walking::BalanceMode>(state.range(0));
  walking::WalkingController c(humanoid::RobotParams{}, w, balance, 0.004);
  state.SetLabel(std::string("balance.mode = ") + std::string(name_of(balance.mode)));
  humanoid::SensorReadings s;
  for (auto& ft : s.ft) ft.force = {0, 0, -250.0};
  const long ticks = static_cast<long>(c.plan().duration / 0.004);
  long k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.update(s, static_cast<double>(k) * 0.004));
    if (++k == ticks) k = 0;
  }
}
BENCHMARK(ControllerUpdate)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The thesis's Fig. 2 loop in one control period: update, input compensator (eqs. 8-9), output
// compensator (Newton, eqs. 10-13) on encoders that carry the model's deflection.
// Arguments: compensation::WeightSplit, compensation::LoadModel (issue 20: ≤ 30 µs with dynamic),
// balance (0 pd, 1 dcm with step adjustment; issue 19: ≤ 30 µs with dcm and both compensators),
// compensation::NewtonJacobian (0 each iterate, 1 reused), k estimation (1: control.k_estimation on, with
// the stance offsets, after the update; issue 20).
void ControllerUpdateWithCompensators(benchmark::State& state) {
  walking::BalanceParams balance;
  if (state.range(2) == 1) {
    balance.mode = walking::BalanceMode::kDcm;
    balance.step_adjustment = true;
  }
  walking::WalkingController c(humanoid::RobotParams{}, walking::WalkParams{}, balance, 0.004);
  compensation::CompensationParams p;
  p.split = static_cast<compensation::WeightSplit>(state.range(0));
  p.load_model = static_cast<compensation::LoadModel>(state.range(1));
  p.newton.jacobian = static_cast<compensation::NewtonJacobian>(state.range(3));
  p.k_estimation_stance_offset = true;
  compensation::DeformationCompensator comp(c.model(), p, 0.004);
  compensation::StiffnessEstimator estimator(c.model(), p, 0.004);
  const bool estimate_k = state.range(4) == 1;
  c.set_plan_motion(p.load_model == compensation::LoadModel::kDynamic);
  humanoid::SensorReadings s;
  for (auto& ft : s.ft) ft.force = {0, 0, -250.0};
  const long ticks = static_cast<long>(c.plan().duration / 0.004);
  long k = 0, iterations = 0, calls = 0;
  for (auto _ : state) {
    const humanoid::JointVector& desired = c.update(s, static_cast<double>(k) * 0.004);
    const walking::ControllerStatus& st = c.status();
    const compensation::SupportPlan plan{st.swinging, st.sole, st.zmp_ref, st.pelvis, -1.0, st.motion};
    if (p.load_model != compensation::LoadModel::kGravity) comp.sense(s.ft);
    const humanoid::JointVector& command = comp.input(desired, st.pelvis.R, plan);
    const compensation::OutputEstimate& e = comp.output(command, st.pelvis.R, plan);
    benchmark::DoNotOptimize(e.newton.data());
    if (estimate_k) {
      for (auto& ft : s.ft) ft.stamp = static_cast<double>(k) * 0.004;
      estimator.update(static_cast<double>(k) * 0.004, command, st.pelvis.R, s.imu, e.gravity_torque, s.ft, plan, true);
      benchmark::DoNotOptimize(estimator.estimate().data());
    }
    iterations += e.iterations;
    ++calls;
    if (++k == ticks) k = 0;
  }
  state.counters["newton_iterations"] = static_cast<double>(iterations) / static_cast<double>(std::max(1L, calls));
  state.SetLabel(std::string(state.range(0) == 0 ? "split about the COM" : "split about the reference ZMP") +
                 ", load_model = " + std::string(name_of(p.load_model)) + ", balance.mode = " +
                 std::string(name_of(balance.mode)) + (balance.step_adjustment ? " with step adjustment" : "") +
                 ", newton_jacobian = " + std::string(name_of(p.newton.jacobian)) +
                 (estimate_k ? ", k_estimation on" : ""));
}
BENCHMARK(ControllerUpdateWithCompensators)
    ->Args({0, 0, 0, 0, 0})
    ->Args({1, 0, 0, 0, 0})
    ->Args({1, 1, 0, 0, 0})
    ->Args({1, 2, 0, 0, 0})
    ->Args({1, 0, 1, 0, 0})
    ->Args({1, 2, 1, 0, 0})
    ->Args({1, 0, 0, 1, 0})
    ->Args({1, 2, 0, 1, 0})
    ->Args({1, 0, 1, 1, 0})
    ->Args({1, 2, 1, 1, 0})
    ->Args({1, 2, 0, 1, 1})
    ->Args({1, 2, 1, 1, 1})
    ->Unit(benchmark::kMicrosecond);

void ClosedLoopWalk(benchmark::State& state) {
  experiments::WalkRunParams p;
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
