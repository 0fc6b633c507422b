#include "rimless_commands.hpp"

#include <fmt/format.h>

#include <memory>

#include "flexgait/core/run_directory.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/output.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "options.hpp"

namespace flexgait::cli {
namespace {

struct SimulateArgs {
  RunOptions run;
  std::string model;
  int steps = 0;
  double omega0 = 0;
  bool has_omega0 = false;
};

int simulate(const SimulateArgs& a, const CLI::App& cmd) {
  std::vector<std::string> extra;
  if (!a.model.empty()) extra.push_back("sim.model=" + a.model);
  if (cmd.count("--steps") > 0) extra.push_back(fmt::format("sim.steps={}", a.steps));
  if (cmd.count("--omega0") > 0) extra.push_back(fmt::format("initial.omega={}", a.omega0));
  const Config config = resolve(rimless::rimless_schema(), a.run, extra);
  const rimless::WheelParams wheel = rimless::wheel_from_config(config);
  const rimless::InitialState initial = rimless::initial_from_config(config);
  rimless::validate(wheel, initial);
  const rimless::SimulationOptions sim = rimless::simulation_from_config(config);
  const std::string model = config.choice("sim.model");

  const rimless::SimulationResult result =
      model == "rigid" ? rimless::simulate_rigid(wheel, initial, sim) : rimless::simulate_flexible(wheel, initial, sim);

  const RunDirectory dir(a.run.out);
  dir.write_config(config);
  rimless::write_run(dir, result, model);
  if (a.run.plot) run_plot_script("plot_rimless.py", {dir.path().string()});
  if (a.run.json) {
    fmt::print("{}", rimless::summary_json(result, model));
  } else {
    std::string gaits;
    for (const auto& s : result.steps)
      if (s.complete) gaits += (gaits.empty() ? "" : " ") + rimless::gait_label(s.single_support);
    fmt::print("rimless {} wheel: {} steps in {:.3f} s, mean speed {:.4f} m/s\n", model, result.steps_completed,
               result.t_final, result.mean_speed);
    fmt::print("gaits: {}\n", gaits.empty() ? "-" : gaits);
    fmt::print("energy: initial {:.6f} J, final {:.6f} J, damping {:.6f} J, friction {:.6f} J, balance error {:.2e}\n",
               result.energy_initial, result.energy_final, result.work_damping, result.work_friction,
               result.energy_balance_error);
    if (result.failure) fmt::print("stopped early: {}\n", *result.failure);
    fmt::print("results in {}\n", dir.path().string());
  }
  return 0;
}

}  // namespace

void add_rimless_commands(CLI::App& app, std::function<int()>& action) {
  CLI::App* rimless = app.add_subcommand("rimless", "Flexible-leg rimless wheel with stick-slip friction");
  rimless->require_subcommand(1);

  auto args = std::make_shared<SimulateArgs>();
  CLI::App* sim = rimless->add_subcommand("simulate", "Simulate the wheel for a number of steps and write a run directory");
  add_run_options(*sim, args->run, "runs/rimless-simulate");
  sim->add_option("--model", args->model, "flexible (spring-damper legs, stick-slip) or rigid (McGeer's wheel); sets sim.model")
      ->check(CLI::IsMember({"flexible", "rigid"}));
  sim->add_option("--steps", args->steps, "number of steps (touchdowns of new legs); sets sim.steps");
  sim->add_option("--omega0", args->omega0, "initial angular velocity (rad/s); sets initial.omega");
  sim->callback([args, sim, &action] { action = [args, sim] { return simulate(*args, *sim); }; });
}

}  // namespace flexgait::cli
