#include "humanoid_commands.hpp"

#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/humanoid/stiffness_bench.hpp"
#include "options.hpp"

namespace flexgait::cli {
namespace {

int bench(const RunOptions& run) {
  const Config config = resolve(humanoid::bench_schema(), run);
  const humanoid::BenchParams params = humanoid::bench_from_config(config);
  const humanoid::BenchResult r = humanoid::run_stiffness_bench(params);

  CsvWriter csv({"compensated", "command", "encoder", "link", "gravity_torque", "error_link_minus_encoder",
                 "error_link_minus_command"});
  for (const auto* set : {&r.uncompensated, &r.compensated}) {
    for (const auto& b : *set) {
      csv.cell(set == &r.compensated ? "true" : "false").cell(b.command).cell(b.encoder).cell(b.link);
      csv.cell(b.gravity_torque).cell(b.link - b.encoder).cell(b.link - b.command).end_row();
    }
  }
  nlohmann::ordered_json j;
  j["k_true"] = params.actuator.k;
  j["k_fit"] = r.k_fit;
  j["k_fit_error"] = (r.k_fit - params.actuator.k) / params.actuator.k;
  j["r_squared"] = r.r_squared;
  j["max_error_uncompensated"] = r.max_error_uncompensated;
  j["max_error_compensated"] = r.max_error_compensated;
  j["residual_compensated_min"] = r.min_residual_compensated;
  j["residual_compensated_max"] = r.max_residual_compensated;
  const std::string summary = j.dump(2) + "\n";

  const RunDirectory dir(run.out);
  dir.write_config(config);
  dir.write("bench.csv", csv.str());
  dir.write("summary.json", summary);
  if (run.plot) run_plot_script("plot_bench.py", {dir.path().string()});
  if (run.json) {
    fmt::print("{}", summary);
  } else {
    fmt::print("stiffness bench: k_fit = {:.2f} Nm/rad (true {:.2f}), R² = {:.5f}\n", r.k_fit, params.actuator.k,
               r.r_squared);
    fmt::print("max |link − command|: {:.5f} rad uncompensated, {:.5f} rad compensated\n", r.max_error_uncompensated,
               r.max_error_compensated);
    fmt::print("results in {}\n", dir.path().string());
  }
  return 0;
}

}  // namespace

void add_humanoid_commands(CLI::App& app, std::function<int()>& action) {
  CLI::App* humanoid = app.add_subcommand("humanoid", "THORMANG-class humanoid twin with elastic gears (MuJoCo)");
  humanoid->require_subcommand(1);
  auto run = std::make_shared<RunOptions>();
  CLI::App* b = humanoid->add_subcommand(
      "bench", "Stiffness bench (thesis Fig. 12): one actuator with a load arm swept through poses; fit k_joint from "
               "angle error against gravity torque, then repeat with the input compensator");
  add_run_options(*b, *run, "runs/humanoid-bench");
  b->callback([run, &action] { action = [run] { return bench(*run); }; });
}

}  // namespace flexgait::cli
