#include "rimless_commands.hpp"

#include <fmt/format.h>

#include <memory>

#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/sweep_runner.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/rimless/analyses.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/output.hpp"
#include "flexgait/rimless/sweep.hpp"
#include "flexgait/rimless/wheel_setup.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "options.hpp"

namespace flexgait::cli {
namespace {

struct SimulateArgs {
  RunOptions run;
  std::string model, steps, omega0;  ///< as given: checked as --set checks sim.model, sim.steps, initial.omega
};

int simulate(const SimulateArgs& a, const CLI::App& cmd) {
  std::vector<ConfigEntry> extra;
  add_option_value(extra, cmd, "--model", "sim.model", a.model);
  add_option_value(extra, cmd, "--steps", "sim.steps", a.steps);
  add_option_value(extra, cmd, "--omega0", "initial.omega", a.omega0);
  const rimless::WheelSetup s = rimless::wheel_setup(resolve(rimless::rimless_schema(), a.run, extra));
  const Config& config = s.config;
  const std::string model = config.choice("sim.model");
  const RunDirectory dir(a.run.out);  // --out before the computation
  dir.write_config(config);

  const rimless::SimulationResult result = s.sim.model == rimless::Model::Rigid
                                               ? rimless::simulate_rigid(s.wheel, s.initial, s.sim)
                                               : rimless::simulate_flexible(s.wheel, s.initial, s.sim);
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

struct FixedPointArgs {
  RunOptions run;
  std::string model;
  std::string section = "touchdown";
};

using rimless::WheelSetup;

/// The analysis configuration with --model (if given) as sim.model.
WheelSetup wheel_setup(const RunOptions& run, const CLI::App& cmd, const std::string& model) {
  std::vector<ConfigEntry> extra;
  add_option_value(extra, cmd, "--model", "sim.model", model);
  return rimless::wheel_setup(resolve(rimless::rimless_analysis_schema(), run, extra));
}

int fixed_point(const FixedPointArgs& a, const CLI::App& cmd) {
  const WheelSetup s = wheel_setup(a.run, cmd, a.model);
  const rimless::AnalysisOptions opt = rimless::analysis_from_config(s.config);
  const rimless::Section section = a.section == "upright" ? rimless::Section::Upright : rimless::Section::Touchdown;
  const RunDirectory dir(a.run.out);  // --out before the computation
  dir.write_config(s.config);
  const rimless::FixedPointReport rep = rimless::find_fixed_point(s.wheel, s.sim, opt, s.sim.model, section, s.initial);
  const std::string json = rimless::fixed_point_json(rep);
  dir.write("fixed_point.json", json);
  if (a.run.json) fmt::print("{}", json);
  if (!rep.converged) {  // a named failure: exit 1, the report (state and multipliers null) kept
    fmt::print(stderr, "error: no fixed point ({} wheel, {} section): {}; report in {}\n", s.config.choice("sim.model"),
               a.section, one_line(rep.failure, 1000), (dir.path() / "fixed_point.json").string());
    return 1;
  }
  if (a.run.json) return 0;
  fmt::print("{} wheel, {} section: fixed point after {} Newton iterations, residual {:.2e}\n",
             s.config.choice("sim.model"), a.section, rep.iterations, rep.residual);
  const auto names = rep.point.names();
  for (Eigen::Index i = 0; i < rep.point.z.size(); ++i)
    fmt::print("  {:8s} = {:.12g}\n", names.at(static_cast<std::size_t>(i)), rep.point.z(i));
  for (const auto& m : rep.multipliers) fmt::print("  multiplier {:.6g}{:+.6g}i  |{:.6g}|\n", m.real(), m.imag(), std::abs(m));
  fmt::print("  {} gait '{}', period {:.6f} s, speed {:.6f} m/s, dissipated {:.6f} J per cycle\n",
             rep.stable ? "stable" : "unstable", rep.gait, rep.period, rep.speed, rep.dissipated);
  fmt::print("results in {}\n", dir.path().string());
  return 0;
}

struct SweepArgs {
  RunOptions run;
  std::string model;
  std::string section = "touchdown";
  std::string param;
  double from = 0, to = 0;
  int count = 0;
  int jobs = 0;
  bool resume = false;
};

int sweep(const SweepArgs& a, const CLI::App& cmd) {
  const WheelSetup s = wheel_setup(a.run, cmd, a.model);
  rimless::check_sweep_param(s.config.schema(), a.param);
  rimless::SweepSpec spec{a.param, a.from, a.to, a.count,
                          a.section == "upright" ? rimless::Section::Upright : rimless::Section::Touchdown};
  rimless::check_sweep(s.config, spec);  // its ends and every point valid first
  SweepJob job;
  job.dir = a.run.out;
  job.header = rimless::sweep_header();
  job.count = spec.count;
  job.jobs = a.jobs;
  job.resume = a.resume;
  job.signature = fmt::format("param {} from {} to {} count {} section {}\n{}", spec.param, spec.from, spec.to, spec.count,
                              a.section, s.config.to_yaml());
  const Config base = s.config;
  job.row = [base, spec](int i) { return rimless::sweep_row(base, spec, i); };
  check_resumable(job);
  const RunDirectory dir(a.run.out);
  dir.write_config(s.config);
  const SweepOutcome out = run_sweep(job);
  if (a.run.plot) run_plot_script("plot_sweep.py", {dir.path().string(), spec.param});
  fmt::print("sweep of {} over [{}, {}], {} points: {} computed, {} resumed, {:.2f} s\n", spec.param, spec.from, spec.to,
             spec.count, out.computed, out.resumed, out.seconds);
  fmt::print("results in {}\n", (dir.path() / "sweep.csv").string());
  return 0;
}

struct AnalysisArgs {
  RunOptions run;
  std::string name;
  std::string mus;  ///< as given: each checked as --set checks rimless.mu_s and mu_k
  double from = 0, to = 0;
  int count = 0;
  int jobs = 0;
  bool resume = false;
  std::string section = "touchdown";
};

int analysis(const AnalysisArgs& a, const CLI::App& cmd) {
  // Every option checked before anything is written; an option this analysis ignores is refused.
  const bool ranged = a.name == "gait-vs-friction" || a.name == "stagnation";
  const std::string which = "analysis " + a.name;
  if (ranged) reject_unused(cmd, {"--mu"}, which + " (only energy, fixed-points and robustness take --mu)");
  else reject_unused(cmd, {"--from", "--to", "--count", "--jobs", "--resume"}, which + " (only gait-vs-friction and "
                                                                                      "stagnation sweep a range)");
  if (a.name != "gait-vs-friction" && a.name != "fixed-points")
    reject_unused(cmd, {"--section"}, which + " (only gait-vs-friction and fixed-points seek fixed points on a section)");
  const WheelSetup s = wheel_setup(a.run, cmd, "");
  const rimless::Section section = a.section == "upright" ? rimless::Section::Upright : rimless::Section::Touchdown;
  std::vector<double> given_mus;
  if (cmd.count("--mu") > 0)
    for (const auto& text : split_list(a.mus))
      given_mus.push_back(rimless::config_at(s.config, "rimless.mu", text, "--mu").real("rimless.mu_s"));
  auto mus = [&](std::vector<double> fallback) { return given_mus.empty() ? fallback : given_mus; };
  rimless::SweepSpec range;  // gait-vs-friction: mu; stagnation: omega0
  if (ranged) {
    const bool friction = a.name == "gait-vs-friction";
    range = {friction ? "rimless.mu" : "initial.omega", cmd.count("--from") ? a.from : (friction ? 0.1 : 0.05),
             cmd.count("--to") ? a.to : (friction ? 1.5 : 2.0), cmd.count("--count") ? a.count : (friction ? 100 : 80),
             section};
    rimless::check_sweep(s.config, range);
  }
  // A resumed sweep must match the one in --out: check before anything is written.
  if (a.resume && (a.name == "gait-vs-friction" || a.name == "stagnation")) {
    SweepJob probe;
    probe.dir = a.run.out;
    probe.name = a.name == "stagnation" ? "stagnation" : "sweep";
    probe.resume = true;
    probe.signature = "?";
    if (!std::filesystem::exists(probe.dir / (probe.name + ".signature"))) check_resumable(probe);
  }
  const RunDirectory dir(a.run.out);
  dir.write_config(s.config);
  std::vector<std::string> files;
  if (a.name == "gait-vs-friction") {
    const double lo = range.from, hi = range.to;
    const int n = range.count;
    const rimless::SweepSpec spec = range;
    SweepJob job;
    job.dir = dir.path();
    job.header = rimless::sweep_header();
    job.count = n;
    job.jobs = a.jobs;
    job.resume = a.resume;
    job.signature = fmt::format("gait-vs-friction {} {} {} {}\n{}", lo, hi, n, a.section, s.config.to_yaml());
    const Config base = s.config;
    job.row = [base, spec](int i) { return rimless::sweep_row(base, spec, i); };
    run_sweep(job);
    // Thresholds from the sweep's gaits, refined by bisection.
    std::vector<std::pair<double, std::string>> points;
    for (int i = 0; i < n; ++i) points.emplace_back(spec.value(i), rimless::gait_at_friction(base, spec.value(i), section));
    dir.write("thresholds.csv", rimless::friction_thresholds_csv(base, points, section, 1e-4));
    files = {"sweep.csv", "thresholds.csv"};
  } else if (a.name == "energy") {
    dir.write("energy.csv", rimless::single_support_energy_csv(s.config, mus({0.6, 0.105})));
    files = {"energy.csv"};
  } else if (a.name == "fixed-points") {
    dir.write("fixed_points.csv", rimless::behaviour_fixed_points_csv(s.config, mus({0.105, 0.13, 0.2, 0.6}), section));
    files = {"fixed_points.csv"};
  } else if (a.name == "robustness") {
    std::vector<double> eps;
    for (int k = 0; k <= 12; ++k) eps.push_back(1e-3 * std::pow(10.0, k / 4.0));
    std::string text;
    for (double mu : mus({0.105, 0.6})) {
      const std::string part = rimless::robustness_csv(s.config, mu, eps, 300);
      text += text.empty() ? part : part.substr(part.find('\n') + 1);
    }
    dir.write("robustness.csv", text);
    files = {"robustness.csv"};
  } else {  // stagnation
    const double lo = range.from, hi = range.to;
    const int n = range.count;
    SweepJob job;
    job.dir = dir.path();
    job.name = "stagnation";
    job.header = rimless::stagnation_header();
    job.count = n;
    job.jobs = a.jobs;
    job.resume = a.resume;
    job.signature = fmt::format("stagnation {} {} {}\n{}", lo, hi, n, s.config.to_yaml());
    const Config base = s.config;
    const double window = 0.05;
    const double l = lo, h = hi;
    const int cnt = n;
    job.row = [base, l, h, cnt, window](int i) {
      return rimless::stagnation_row(base, cnt == 1 ? l : l + (h - l) * i / (cnt - 1), window);
    };
    run_sweep(job);
    files = {"stagnation.csv"};
  }
  if (a.run.plot) run_plot_script("plot_analysis.py", {a.name, dir.path().string()});
  for (const auto& f : files) fmt::print("wrote {}\n", (dir.path() / f).string());
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
  sim->add_option("--steps", args->steps, "number of steps (touchdowns of new legs); sets sim.steps")->type_name("INT");
  sim->add_option("--omega0", args->omega0, "initial angular velocity (rad/s); sets initial.omega")->type_name("FLOAT");
  sim->callback([args, sim, &action] { action = [args, sim] { return simulate(*args, *sim); }; });

  auto fp_args = std::make_shared<FixedPointArgs>();
  CLI::App* fp = rimless->add_subcommand("fixed-point", "Find a periodic gait: Newton-Raphson on the Poincare map, "
                                                        "Floquet multipliers, stability");
  add_run_options(*fp, fp_args->run, "runs/rimless-fixed-point");
  fp->add_option("--model", fp_args->model, "flexible or rigid; sets sim.model")
      ->check(CLI::IsMember({"flexible", "rigid"}));
  fp->add_option("--section", fp_args->section, "Poincare section: touchdown of a new leg, or stance leg upright")
      ->check(CLI::IsMember({"touchdown", "upright"}))
      ->capture_default_str();
  fp->callback([fp_args, fp, &action] { action = [fp_args, fp] { return fixed_point(*fp_args, *fp); }; });

  auto sw = std::make_shared<SweepArgs>();
  CLI::App* swc = rimless->add_subcommand("sweep", "Sweep one parameter: gait, fixed point, multipliers, stability, "
                                                   "speed and energy per point, on all cores, resumable");
  add_run_options(*swc, sw->run, "runs/rimless-sweep");
  swc->add_option("--param", sw->param, "configuration key to vary (e.g. rimless.slope, initial.omega), or "
                                        "rimless.mu for mu_s = mu_k")->required();
  swc->add_option("--from", sw->from, "first value (in the key's unit)")->required()->check(finite_number());
  swc->add_option("--to", sw->to, "last value (in the key's unit)")->required()->check(finite_number());
  swc->add_option("--count", sw->count, "number of values, evenly spaced, ends included")
      ->required()->check(CLI::Range(1, 1000000));
  swc->add_option("--jobs", sw->jobs, "worker threads (0: all cores)")->check(CLI::Range(0, 1024))->capture_default_str();
  swc->add_flag("--resume", sw->resume, "keep the finished points of an interrupted sweep in --out");
  swc->add_option("--model", sw->model, "flexible or rigid; sets sim.model")->check(CLI::IsMember({"flexible", "rigid"}));
  swc->add_option("--section", sw->section, "Poincare section of the fixed points")
      ->check(CLI::IsMember({"touchdown", "upright"}))->capture_default_str();
  swc->callback([sw, swc, &action] { action = [sw, swc] { return sweep(*sw, *swc); }; });

  auto an = std::make_shared<AnalysisArgs>();
  CLI::App* anc = rimless->add_subcommand(
      "analysis", "The paper's analyses, each a CSV and a PNG: gait-vs-friction (behaviours and thresholds), energy "
                  "(single support, stick against slip), fixed-points (the four behaviours), robustness (of the "
                  "sliding gait), stagnation (paper Fig. 12)");
  add_run_options(*anc, an->run, "runs/rimless-analysis");
  anc->add_option("name", an->name, "which analysis")
      ->required()
      ->check(CLI::IsMember({"gait-vs-friction", "energy", "fixed-points", "robustness", "stagnation"}));
  anc->add_option("--mu", an->mus, "friction coefficients (mu_s = mu_k), comma separated, for energy, fixed-points, "
                                   "robustness")
      ->type_name("MU,...");
  anc->add_option("--from", an->from, "first value: mu (gait-vs-friction, default 0.1) or omega0 in rad/s (stagnation, default 0.05)")
      ->check(finite_number());
  anc->add_option("--to", an->to, "last value: mu (default 1.5) or omega0 in rad/s (default 2.0)")->check(finite_number());
  anc->add_option("--count", an->count, "number of values (default 100 for gait-vs-friction, 80 for stagnation)")
      ->check(CLI::Range(1, 1000000));
  anc->add_option("--jobs", an->jobs, "worker threads (0: all cores)")->check(CLI::Range(0, 1024));
  anc->add_flag("--resume", an->resume, "keep the finished points of an interrupted run in --out");
  anc->add_option("--section", an->section, "Poincare section of the fixed points")
      ->check(CLI::IsMember({"touchdown", "upright"}))->capture_default_str();
  anc->callback([an, anc, &action] { action = [an, anc] { return analysis(*an, *anc); }; });
}

}  // namespace flexgait::cli
