// Rimless-wheel benchmarks. Target (issue 3): one step of the flexible wheel at rtol 1e-10 with
// the spec's measured parameter set at μ = 0.6 in at most 120 µs.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "flexgait/core/sweep_runner.hpp"
#include "flexgait/rimless/dynamics.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/flow.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "flexgait/rimless/sweep.hpp"

namespace {

using namespace flexgait::rimless;

WheelParams wheel(double mu) {
  WheelParams w;
  w.mu_s = w.mu_k = mu;
  return w;
}

// Steps of the flexible wheel (no log) with the given integrator, timed per step; events per
// second and right-hand-side evaluations per step as counters.
void time_flexible_steps(benchmark::State& state, flexgait::numerics::OdeMethod method) {
  const WheelParams w = wheel(static_cast<double>(state.range(0)) / 1000.0);
  SimulationOptions o;
  o.steps = 20;
  o.log = false;
  o.rtol = 1e-10;
  o.method = method;
  FlexibleWheelSimulator sim(w, o);
  const RunSpec spec = default_run(w, InitialState{});
  long long steps = 0, events = 0, rhs = 0;
  for (auto _ : state) {
    const SimulationResult r = sim.run(spec);
    steps += r.steps_completed;
    events += r.event_count;
    rhs += r.rhs_evals;
    benchmark::DoNotOptimize(r.final_state.data());
  }
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["events/s"] = benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
  state.counters["rhs/step"] = static_cast<double>(rhs) / static_cast<double>(steps);
  state.counters["us/step"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
void FlexibleWheelStep(benchmark::State& state) {
  time_flexible_steps(state, flexgait::numerics::OdeMethod::Adams);
}
BENCHMARK(FlexibleWheelStep)->Arg(600)->Arg(130)->Arg(5000)->Unit(benchmark::kMicrosecond);
void FlexibleWheelStepDop853(benchmark::State& state) {
  time_flexible_steps(state, flexgait::numerics::OdeMethod::Dop853);
}
BENCHMARK(FlexibleWheelStepDop853)->Arg(600)->Arg(130)->Arg(5000)->Unit(benchmark::kMicrosecond);

void RigidWheelStep(benchmark::State& state) {
  WheelParams w = wheel(0.6);
  SimulationOptions o;
  o.steps = 20;
  o.log = false;
  long long steps = 0;
  for (auto _ : state) {
    const SimulationResult r = simulate_rigid(w, InitialState{}, o);
    steps += r.steps_completed;
    benchmark::DoNotOptimize(r.final_state.data());
  }
  state.counters["us/step"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(RigidWheelStep)->Unit(benchmark::kMicrosecond);

// One evaluation of the flow in double support (stick + slip).
void FlowDerivative(benchmark::State& state) {
  const WheelParams w = wheel(0.6);
  std::vector<double> y = initial_state(w, InitialState{0.0, -0.3});
  ContactSet c;
  c.count = 1;
  c.leg[0] = 0;
  std::vector<double> yd(y.size());
  for (auto _ : state) {
    benchmark::DoNotOptimize(flow_derivative(w, c, y, yd));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(FlowDerivative);

// The touchdown-section map at the analyses' tolerances, and its fixed point.
struct MapAtFixedPoint {
  PoincareMap map;
  SectionState point;
};
MapAtFixedPoint map_at_fixed_point(const WheelParams& w,
                                   flexgait::numerics::OdeMethod method = flexgait::numerics::OdeMethod::Adams) {
  SimulationOptions sim;
  sim.method = method;
  const AnalysisOptions opt;
  const FixedPointReport fp = find_fixed_point(w, sim, opt, Model::Flexible, Section::Touchdown, InitialState{});
  SimulationOptions map_opt = sim;
  map_opt.rtol = opt.rtol;
  map_opt.atol = opt.atol;
  return {PoincareMap(w, map_opt, Model::Flexible, Section::Touchdown), fp.point};
}

// Poincaré-map evaluations (touchdown section, rtol 1e-12 as in the analyses) at the fixed point,
// with the integrator given as the second argument (OdeMethod's index: 0 adams, 2 dop853).
void PoincareMapEvaluation(benchmark::State& state) {
  auto [map, point] = map_at_fixed_point(wheel(static_cast<double>(state.range(0)) / 1000.0),
                                         static_cast<flexgait::numerics::OdeMethod>(state.range(1)));
  for (auto _ : state) {
    const MapStep s = map.apply(point);
    benchmark::DoNotOptimize(s.next.z.data());
  }
  state.counters["maps/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(PoincareMapEvaluation)
    ->Args({600, 0})
    ->Args({105, 0})
    ->Args({600, 2})
    ->Args({105, 2})
    ->Unit(benchmark::kMillisecond);

// The variational (exact) Jacobian of the map at the fixed point (argument: the integrator).
void PoincareMapJacobian(benchmark::State& state) {
  auto [map, point] = map_at_fixed_point(wheel(0.6), static_cast<flexgait::numerics::OdeMethod>(state.range(0)));
  Eigen::MatrixXd J;
  for (auto _ : state) {
    benchmark::DoNotOptimize(map.jacobian(point, J));
  }
}
BENCHMARK(PoincareMapJacobian)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);

// A 200-point μ sweep on all cores (the figure of merit), one iteration; the argument
// is solver.method.
void FrictionSweep200(benchmark::State& state, const char* method) {
  const flexgait::Schema schema = [] {
    flexgait::Schema s = rimless_schema();
    return s.merge(analysis_schema());
  }();
  const flexgait::Config base =
      flexgait::resolve_config(schema, std::nullopt, {std::string("solver.method=") + method});
  const SweepSpec spec{"rimless.mu", 0.1, 1.5, 200, Section::Touchdown};
  const auto dir = std::filesystem::temp_directory_path() / "flexgait_bench_sweep";
  for (auto _ : state) {
    std::filesystem::remove_all(dir);
    flexgait::SweepJob job;
    job.dir = dir;
    job.header = sweep_header();
    job.count = spec.count;
    job.signature = "bench";
    job.row = [&](int i) { return sweep_row(base, spec, i); };
    benchmark::DoNotOptimize(flexgait::run_sweep(job));
  }
}
BENCHMARK_CAPTURE(FrictionSweep200, adams, "adams")->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK_CAPTURE(FrictionSweep200, dop853, "dop853")->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
