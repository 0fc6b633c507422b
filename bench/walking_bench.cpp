// Walking controller benchmarks: one controller update (target ≤ 20 µs on the 2-core reference machine),
// the update with both deformation compensators (target ≤ 30 µs), each compensator
// alone, and the closed-loop walk's real-time factor (controller + compensators + twin), 1.0 s
// per step, beside bare mj_step on the same walk's states (the closed loop's share of the time).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <string>
#include <vector>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/compensation/stiffness_estimator.hpp"
#include "flexgait/core/config.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/walking/walking_controller.hpp"

namespace {

using namespace flexgait;

/// The parameters of a plain `flexgait humanoid walk` (10 steps at 1 s/step, the default compensation case
/// both-dynamic-horizontal-lag), as the command resolves them.
experiments::WalkRunParams default_walk() {
  return experiments::walk_run_from_config(resolve_config(experiments::walk_run_schema(), std::nullopt, {}));
}

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
// Arguments: compensation::WeightSplit, compensation::LoadModel (≤ 30 µs with dynamic),
// balance (0 pd, 1 dcm with step adjustment; ≤ 30 µs with dcm and both compensators),
// compensation::NewtonJacobian (0 each iterate, 1 reused, 2 kept: the default), k estimation (1: control.k_estimation
// on, with the stance offsets, after the update), the default case's physics (1: control.plan_horizontal_force,
// control.gear_damping and control.load_filter_time as `humanoid walk` resolves them for its default case
// both-dynamic-horizontal-lag: the plan's whole-body Newton–Euler, the gears' lag, the short F/T low-pass).
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
  const bool default_case = state.range(5) == 1;
  if (default_case) {
    const compensation::CompensationParams resolved = default_walk().control;
    p.plan_horizontal_force = resolved.plan_horizontal_force;
    p.gear_damping = resolved.gear_damping;
    p.load_filter_time = resolved.load_filter_time;
  }
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
                 (estimate_k ? ", k_estimation on" : "") + (default_case ? ", the default case's physics" : ""));
}
BENCHMARK(ControllerUpdateWithCompensators)
    ->Args({0, 0, 0, 0, 0, 0})
    ->Args({1, 0, 0, 0, 0, 0})
    ->Args({1, 1, 0, 0, 0, 0})
    ->Args({1, 2, 0, 0, 0, 0})
    ->Args({1, 0, 1, 0, 0, 0})
    ->Args({1, 2, 1, 0, 0, 0})
    ->Args({1, 0, 0, 1, 0, 0})
    ->Args({1, 2, 0, 1, 0, 0})
    ->Args({1, 0, 1, 1, 0, 0})
    ->Args({1, 2, 1, 1, 0, 0})
    ->Args({1, 2, 0, 1, 1, 0})
    ->Args({1, 2, 1, 1, 1, 0})

    ->Args({1, 2, 0, 1, 0, 1})
    ->Args({1, 2, 1, 1, 1, 1})
    ->Args({1, 2, 0, 2, 0, 1})
    ->Args({1, 2, 1, 2, 1, 1})
    ->Unit(benchmark::kMicrosecond);

// The default `humanoid walk` (10 steps at 1 s/step, both-dynamic-horizontal-lag), end to end with its scorer.
void ClosedLoopWalk(benchmark::State& state) {
  const experiments::WalkRunParams p = default_walk();
  double simulated = 0;
  for (auto _ : state) {
    const experiments::WalkResult r = experiments::run_walk(p);
    simulated += r.metrics.simulated_time;
    if (r.metrics.fell) state.SkipWithError("the walk fell");
  }
  state.counters["real_time_factor"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
}
BENCHMARK(ClosedLoopWalk)->Unit(benchmark::kMillisecond)->Iterations(3);

// The closed loop's periods (loop::HumanoidLoop::step: controller, compensators, drives, sensors, the
// loop's checks; not the twin's making) against bare mj_step of the same model on the same walk's states: each
// control period, the walk's state at its start (positions, velocities, warm start, the drives' and pushes'
// forces, held over the period's physics steps) is copied into a bare mjData, the loop steps the period, then bare
// mj_step steps the copy as many physics steps, so that the contacts and the solver's work are the walk's. The two
// alternate period by period (~0.3 ms each), so both see the same machine load: a shared machine's load moves over
// seconds, and timed a whole walk apart their ratio read 0.70-0.97 from run to run. Counters: both real-time
// factors and their ratio, closed loop / bare (1: the loop's own work costs nothing), by the thread's CPU time
// (rtf_*, ratio; on a shared machine the wall clock also counts the time other processes run) and by the wall
// clock (*_wall). The default `humanoid walk`: 10 steps at 1 s/step, both-dynamic-horizontal-lag.
void ClosedLoopAgainstBareMujoco(benchmark::State& state) {
  const experiments::WalkRunParams p = default_walk();
  using Clock = std::chrono::steady_clock;
  const auto cpu_now = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  };
  double loop_seconds = 0, bare_seconds = 0, loop_cpu = 0, bare_cpu = 0, simulated = 0;
  for (auto _ : state) {
    state.PauseTiming();
    experiments::WalkLoop w = experiments::make_walk_loop(p);
    const double end = w.control->controller().plan().duration;
    const mjModel* pm = twin::plant_model(w.loop->plant());
    const mjData* pd = twin::plant_data(w.loop->plant());
    mjModel* m = mj_copyModel(nullptr, pm);
    mjData* d = mj_makeData(m);
    const int substeps = static_cast<int>(std::lround(p.plant.control_period / m->opt.timestep));
    state.ResumeTiming();
    while (w.loop->time() < end) {
      d->time = pd->time;
      std::copy(pd->qpos, pd->qpos + m->nq, d->qpos);
      std::copy(pd->qvel, pd->qvel + m->nv, d->qvel);
      std::copy(pd->act, pd->act + m->na, d->act);
      std::copy(pd->qacc_warmstart, pd->qacc_warmstart + m->nv, d->qacc_warmstart);
      std::copy(pd->qfrc_applied, pd->qfrc_applied + m->nv, d->qfrc_applied);
      std::copy(pd->xfrc_applied, pd->xfrc_applied + 6 * m->nbody, d->xfrc_applied);
      const Clock::time_point t0 = Clock::now();
      const double c0 = cpu_now();
      const bool stopped = w.loop->step().has_value();
      const double c1 = cpu_now();
      const Clock::time_point t1 = Clock::now();
      for (int k = 0; k < substeps; ++k) mj_step(m, d);
      bare_cpu += cpu_now() - c1;
      bare_seconds += std::chrono::duration<double>(Clock::now() - t1).count();
      loop_cpu += c1 - c0;
      loop_seconds += std::chrono::duration<double>(t1 - t0).count();
      if (stopped) break;
    }
    simulated += w.loop->time();
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  state.counters["rtf_closed_loop"] = simulated / loop_cpu;
  state.counters["rtf_bare_mj_step"] = simulated / bare_cpu;
  state.counters["ratio"] = bare_cpu / loop_cpu;
  state.counters["rtf_closed_loop_wall"] = simulated / loop_seconds;
  state.counters["rtf_bare_mj_step_wall"] = simulated / bare_seconds;
  state.counters["ratio_wall"] = bare_seconds / loop_seconds;
}
BENCHMARK(ClosedLoopAgainstBareMujoco)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
