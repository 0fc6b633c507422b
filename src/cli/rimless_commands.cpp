#include "rimless_commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <utility>

#include "flexgait/core/progress.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/sweep_runner.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/rimless/analyses.hpp"
#include "flexgait/rimless/fixed_point.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/gait_branch.hpp"
#include "flexgait/rimless/output.hpp"
#include "flexgait/rimless/replay.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "flexgait/rimless/stagnation.hpp"
#include "flexgait/rimless/sweep.hpp"
#include "flexgait/rimless/wheel_setup.hpp"
#include "options.hpp"
#include "rimless_map_commands.hpp"

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
  check_with_origin(config, [&] { rimless::check_log_size(s.sim); });  // before anything is written
  const RunDirectory dir(a.run.out);                                   // --out before the computation
  dir.write_config(config);

  // log.csv, events.csv and steps.csv are written while the run goes: memory does not grow
  // with the number of steps.
  rimless::RunFiles files(dir);
  // replay.html: a frame every 1/60 s of simulated time, recorded from the same samples.
  rimless::WheelReplay replay(s.wheel, files);
  const rimless::SimulationResult result = s.sim.model == rimless::Model::Rigid
                                               ? rimless::simulate_rigid(s.wheel, s.initial, s.sim, replay)
                                               : rimless::simulate_flexible(s.wheel, s.initial, s.sim, replay);
  files.finish();
  if (replay::replay_page_available()) dir.write("replay.html", replay::replay_html(replay.finish()));
  dir.write("summary.json", rimless::summary_json(result, model));
  if (a.run.plot) run_plot_script("plot_rimless.py", {dir.path().string()});
  if (a.run.json) {
    fmt::print("{}", rimless::summary_json(result, model));
  } else {
    std::string gaits;
    for (const std::string& g : result.gaits) gaits += (gaits.empty() ? "" : " ") + g;
    fmt::print("rimless {} wheel: {} steps in {:.3f} s, mean speed {:.4f} m/s\n", model, result.steps_completed,
               result.t_final, result.mean_speed);
    fmt::print("gaits: {}\n", gaits.empty() ? "-" : gaits);
    fmt::print("energy: initial {:.6f} J, final {:.6f} J, damping {:.6f} J, friction {:.6f} J, balance error {:.2e}\n",
               result.energy_initial, result.energy_final, result.work_damping, result.work_friction,
               result.energy_balance_error);
    fmt::print("results in {}\n", dir.path().string());
  }
  // The run did not do what was asked (its steps): the wheel stopped, rolled back or slid away,
  // or the solver failed. The files are written; the reason is in summary.json's failure too.
  if (!result.failure) return 0;
  fmt::print(stderr, "error: stopped after {} of {} steps: {}\n", result.steps_completed, s.sim.steps,
             one_line(result.failure->text(), 1000));
  return 1;
}

struct FixedPointArgs {
  RunOptions run;
  std::string model;
  rimless::Section section = rimless::Section::Touchdown;
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
  const RunDirectory dir(a.run.out);  // --out before the computation
  dir.write_config(s.config);
  const rimless::FixedPointReport rep =
      rimless::find_fixed_point(s.wheel, s.sim, opt, s.sim.model, a.section, s.initial);
  const std::string json = rimless::fixed_point_json(rep);
  dir.write("fixed_point.json", json);
  if (a.run.json) fmt::print("{}", json);
  if (!rep.converged) {  // a named failure: exit 1, the report (state and multipliers null) kept
    fmt::print(stderr, "error: no fixed point ({} wheel, {} section): {}; report in {}\n", s.config.choice("sim.model"),
               name_of(a.section), one_line(rep.failure(), 1000), (dir.path() / "fixed_point.json").string());
    return 1;
  }
  if (a.run.json) return 0;
  fmt::print("{} wheel, {} section: fixed point after {} Newton iterations, residual {:.2e}\n",
             s.config.choice("sim.model"), name_of(a.section), rep.iterations, rep.residual);
  const auto names = rep.point.names();
  for (Eigen::Index i = 0; i < rep.point.z.size(); ++i)
    fmt::print("  {:8s} = {:.12g}\n", names.at(static_cast<std::size_t>(i)), rep.point.z(i));
  for (const auto& m : rep.multipliers)
    fmt::print("  multiplier {:.6g}{:+.6g}i  |{:.6g}|\n", m.real(), m.imag(), std::abs(m));
  fmt::print("  {} gait '{}', period {:.6f} s, speed {:.6f} m/s, dissipated {:.6f} J per cycle\n",
             rep.stable ? "stable" : "unstable", rep.gait, rep.period, rep.speed, rep.dissipated);
  fmt::print("results in {}\n", dir.path().string());
  return 0;
}

struct SweepArgs {
  RunOptions run;
  std::string model;
  rimless::Section section = rimless::Section::Touchdown;
  std::string param;
  double from = 0, to = 0;
  int count = 0;
  int jobs = 0;
  bool resume = false;
};

int sweep(const SweepArgs& a, const CLI::App& cmd) {
  const WheelSetup s = wheel_setup(a.run, cmd, a.model);
  rimless::check_sweep_param(s.config.schema(), a.param);
  rimless::SweepSpec spec{a.param, a.from, a.to, a.count, a.section};
  rimless::check_sweep(s.config, spec);  // its ends and every point valid first
  SweepJob job;
  job.dir = a.run.out;
  job.header = rimless::sweep_header();
  job.count = spec.count;
  job.jobs = a.jobs;
  job.resume = a.resume;
  job.signature = fmt::format("param {} from {} to {} count {} section {}\n{}", spec.param, spec.from, spec.to,
                              spec.count, name_of(a.section), s.config.to_yaml());
  const Config base = s.config;
  job.row = [base, spec](int i) { return rimless::sweep_row(base, spec, i); };
  job.valid_row = [spec](int i, const std::vector<std::string>& cells) {
    return rimless::sweep_row_valid(spec, i, cells);
  };
  check_resumable(job);
  const RunDirectory dir(a.run.out);
  dir.write_config(s.config);
  const SweepOutcome out = run_sweep(job);
  if (a.run.plot) run_plot_script("plot_sweep.py", {dir.path().string(), spec.param});
  fmt::print("sweep of {} over [{}, {}], {} points: {} computed, {} resumed, {:.2f} s\n", spec.param, spec.from,
             spec.to, spec.count, out.computed, out.resumed, out.seconds);
  fmt::print("results in {}\n", (dir.path() / "sweep.csv").string());
  return 0;
}

struct AnalysisArgs {
  RunOptions run;
  std::string name;
  std::string mus;  ///< as given: a comma-separated list, set as the running analysis's analysis.*.mu
  double from = 0, to = 0;
  int count = 0;
  int jobs = 0;
  bool resume = false;
  rimless::Section section = rimless::Section::Touchdown;
  std::vector<std::string> vary;
  MapOptions map;  ///< orbit-diagram and basin (rimless_map_commands.hpp)
};

/// The stagnation map's default variations of the base configuration (configs/rimless-stagnation.yaml):
/// the friction margin mu - tan(phi), the inertia, the damping and the stiffness, one at a time,
/// and small inertia at mu = 0.25, where the foot sticks near the vertical.
std::vector<std::string> default_stagnation_map() {
  return {"",
          "rimless.mu=0.1",
          "rimless.mu=0.11",
          "rimless.mu=0.12",
          "rimless.mu=0.15",
          "rimless.I=0.1",
          "rimless.I=1",
          "rimless.C=10",
          "rimless.C=100",
          "rimless.K=300",
          "rimless.K=10000",
          "rimless.I=0.02,rimless.mu=0.25"};
}

/// What an analysis's handler works from: the options, the checked configuration and its
/// `analysis.*` keys (analyses.hpp) and stagnation.* keys.
struct AnalysisContext {
  const AnalysisArgs& args;
  const WheelSetup& setup;
  const rimless::PaperAnalysisOptions& paper;
  const rimless::StagnationOptions& stagnation;
  rimless::Section section;
  std::vector<std::string> variations;  ///< stagnation-map: --vary, or default_stagnation_map()
};

/// One analysis of `rimless analysis NAME`.
struct Analysis {
  std::string name{};
  std::string help{};                  ///< what it computes, for --help
  std::vector<std::string> options{};  ///< the options it takes beyond --config/--set/--out/--json/--no-plot
  /// Options that set a configuration key for this analysis (checked as --set checks the key).
  std::vector<std::pair<std::string, std::string>> keys{};
  std::string sweep_name{};       ///< the resumable sweep's file stem in --out ("" when not resumable)
  bool reads_stagnation = false;  ///< reads the stagnation.* keys (checked together: stagnation_from_config)
  /// Checks beyond the keys' own, before anything is written (may be null); given this entry, so
  /// that a check reads its keys from `keys`.
  void (*check)(const AnalysisContext&, const Analysis&) = nullptr;
  /// Computes and writes into the run directory; returns the files written.
  std::vector<std::string> (*run)(const AnalysisContext&, const RunDirectory&) = nullptr;
  /// orbit-diagram and basin resolve and write on their own (rimless_map_commands.hpp).
  bool map = false;
};

// Every μ of the entry's --mu key is a valid friction coefficient of the wheel (mu_s = mu_k).
void check_mus(const AnalysisContext& c, const Analysis& entry) {
  const auto mu = std::find_if(entry.keys.begin(), entry.keys.end(), [](const auto& k) { return k.first == "--mu"; });
  if (mu == entry.keys.end()) throw std::logic_error("analysis " + entry.name + " checks --mu but has no key for it");
  const std::string& key = mu->second;
  for (const double value : c.setup.config.reals(key))
    rimless::config_at(c.setup.config, "rimless.mu", format_number(value), c.setup.config.origin(key));
}

rimless::SweepSpec friction_range(const AnalysisContext& c) {
  return {"rimless.mu", c.paper.friction_mu_from, c.paper.friction_mu_to, c.paper.friction_count, c.section};
}

std::vector<std::string> gait_vs_friction(const AnalysisContext& c, const RunDirectory& dir) {
  const rimless::SweepSpec spec = friction_range(c);
  SweepJob job;
  job.dir = dir.path();
  job.header = rimless::sweep_header();
  job.count = spec.count;
  job.jobs = c.args.jobs;
  job.resume = c.args.resume;
  job.signature = fmt::format("gait-vs-friction {} {} {} {}\n{}", spec.from, spec.to, spec.count,
                              name_of(c.args.section), c.setup.config.to_yaml());
  const Config base = c.setup.config;
  job.row = [base, spec](int i) { return rimless::sweep_row(base, spec, i); };
  job.valid_row = [spec](int i, const std::vector<std::string>& cells) {
    return rimless::sweep_row_valid(spec, i, cells);
  };
  run_sweep(job);
  // The periodic gait at each value (longer transients, then continuation from the neighbours'
  // fixed points where the start finds none), and the thresholds between them by bisection.
  std::vector<double> values;
  for (int i = 0; i < spec.count; ++i) values.push_back(spec.value(i));
  const std::vector<rimless::FrictionGait> gaits = rimless::friction_gaits(base, values, c.section, c.paper);
  dir.write("gaits.csv", rimless::friction_gaits_csv(gaits));
  dir.write("thresholds.csv", rimless::friction_thresholds_csv(base, gaits, c.section, c.paper));
  return {"sweep.csv", "gaits.csv", "thresholds.csv"};
}

std::vector<std::string> energy(const AnalysisContext& c, const RunDirectory& dir) {
  dir.write("energy.csv", rimless::single_support_energy_csv(c.setup.config, c.paper.energy_mu));
  return {"energy.csv"};
}

std::vector<std::string> fixed_points(const AnalysisContext& c, const RunDirectory& dir) {
  dir.write("fixed_points.csv",
            rimless::behaviour_fixed_points_csv(c.setup.config, c.paper.fixed_points_mu, c.section));
  return {"fixed_points.csv"};
}

std::vector<std::string> robustness(const AnalysisContext& c, const RunDirectory& dir) {
  const std::vector<double> eps = rimless::robustness_epsilons(c.paper);
  std::string text;
  const auto fixed_points = static_cast<double>(c.paper.robustness_mu.size());
  ProgressBar bar(100, "% of the perturbations");
  bar.show(0);
  for (std::size_t k = 0; k < c.paper.robustness_mu.size(); ++k) {
    const std::string part = rimless::robustness_csv(
        c.setup.config, c.paper.robustness_mu[k], eps, c.paper.max_steps, c.paper.return_tol,
        [&](double fraction) { bar.show(100 * (static_cast<double>(k) + fraction) / fixed_points); });
    text += text.empty() ? part : part.substr(part.find('\n') + 1);
  }
  dir.write("robustness.csv", text);
  return {"robustness.csv"};
}

std::vector<std::string> stagnation(const AnalysisContext& c, const RunDirectory& dir) {
  const WheelSetup& s = c.setup;
  const rimless::StagnationScan scan = rimless::scan_stagnation(s.wheel, s.initial, s.sim, c.stagnation);
  dir.write("stagnation.csv", rimless::stagnation_csv(scan));
  dir.write("stagnation.json", json_file_text(record_json(scan.summary)));
  const rimless::StagnationSummary& r = scan.summary;
  if (r.critical_found) {
    fmt::print("critical omega0 = {:.12f} rad/s (bracket {:.3e} wide after {} bisection stages){}\n", r.omega_c,
               r.omega_c_high - r.omega_c_low, r.bisection_steps,
               r.bisection_note.empty() ? "" : "; " + r.bisection_note);
    fmt::print(
        "{} stagnation: {:.3f} s near the vertical per decade of |omega0 - omega_c| above, {:.3f} s below "
        "(pendulum estimates: {:.3f} s sliding, {:.3f} s sticking)\n",
        r.kind, r.growth_above, r.growth_below, r.estimate_sliding, r.estimate_sticking);
    fmt::print("stagnation interval (near-vertical time > {:.3f} s): omega0 in [{:.10f}, {:.10f}] rad/s\n", r.threshold,
               r.interval_low, r.interval_high);
  } else {
    fmt::print("no critical omega0 in [{}, {}]: the stage's end does not flip from rolled_back to next_leg_landed\n",
               c.stagnation.omega_from, c.stagnation.omega_to);
  }
  return {"stagnation.csv", "stagnation.json"};
}

std::vector<std::string> stagnation_map(const AnalysisContext& c, const RunDirectory& dir) {
  SweepJob job;
  job.dir = dir.path();
  job.name = "stagnation_map";
  job.header = rimless::stagnation_map_header();
  job.count = static_cast<int>(c.variations.size());
  job.jobs = c.args.jobs;
  job.resume = c.args.resume;
  std::string list;
  for (const auto& v : c.variations) list += v + ";";
  job.signature = fmt::format("stagnation-map {}\n{}", list, c.setup.config.to_yaml());
  const Config base = c.setup.config;
  job.row = [base, variations = c.variations](int i) {
    return rimless::stagnation_map_row(base, variations[static_cast<std::size_t>(i)]);
  };
  job.valid_row = [variations = c.variations](int i, const std::vector<std::string>& cells) {
    return rimless::stagnation_map_row_valid(variations[static_cast<std::size_t>(i)], cells);
  };
  run_sweep(job);
  return {"stagnation_map.csv"};
}

/// The analyses: the one list of names; --help, the name check and which options each takes come from it.
const std::vector<Analysis>& analyses() {
  static const std::vector<Analysis> table = [] {
    using Keys = std::vector<std::pair<std::string, std::string>>;
    const Keys omega_grid{
        {"--from", "stagnation.omega_from"}, {"--to", "stagnation.omega_to"}, {"--count", "stagnation.count"}};
    return std::vector<Analysis>{
        {.name = "gait-vs-friction",
         .help = "behaviours and thresholds",
         .options = {"--from", "--to", "--count", "--jobs", "--resume", "--section"},
         .keys = {{"--from", "analysis.friction.mu_from"},
                  {"--to", "analysis.friction.mu_to"},
                  {"--count", "analysis.friction.count"}},
         .sweep_name = "sweep",
         .check = [](const AnalysisContext& c,
                     const Analysis&) { rimless::check_sweep(c.setup.config, friction_range(c)); },
         .run = gait_vs_friction},
        {.name = "energy",
         .help = "single support, stick against slip",
         .options = {"--mu"},
         .keys = {{"--mu", "analysis.energy.mu"}},
         .check = check_mus,
         .run = energy},
        {.name = "fixed-points",
         .help = "the four behaviours",
         .options = {"--mu", "--section"},
         .keys = {{"--mu", "analysis.fixed_points.mu"}},
         .check = check_mus,
         .run = fixed_points},
        {.name = "robustness",
         .help = "of the sliding gait",
         .options = {"--mu"},
         .keys = {{"--mu", "analysis.robustness.mu"}},
         .check = check_mus,
         .run = robustness},
        {.name = "stagnation",
         .help = "paper Fig. 12: the critical omega0, the time sliding near the true vertical against "
                 "|omega0 - omega_c|, the stagnation interval",
         .options = {"--from", "--to", "--count"},
         .keys = omega_grid,
         .reads_stagnation = true,
         .run = stagnation},
        {.name = "stagnation-map",
         .help = "how the interval moves with mu - tan(phi), I, C, K",
         .options = {"--from", "--to", "--count", "--jobs", "--resume", "--vary"},
         .keys = omega_grid,
         .sweep_name = "stagnation_map",
         .reads_stagnation = true,
         .check =
             [](const AnalysisContext& c, const Analysis&) {
               for (const auto& v : c.variations) rimless::stagnation_map_config(c.setup.config, v);  // each valid
             },
         .run = stagnation_map},
        {.name = "orbit-diagram",
         .help = "section values of many steps after a transient, against a parameter",
         .options = {"--param", "--transient", "--record", "--branch", "--from", "--to", "--count", "--jobs",
                     "--resume", "--section"},
         .map = true},
        {.name = "basin",
         .help = "a grid of initial states: which converge to the gait, which fall and why",
         .options = {"--x", "--y", "--x-range", "--y-range", "--steps-limit", "--tolerance", "--jobs", "--resume",
                     "--section"},
         .map = true}};
  }();
  return table;
}

std::vector<std::string> analysis_names() {
  std::vector<std::string> names;
  for (const Analysis& a : analyses()) names.push_back(a.name);
  return names;
}

bool takes(const Analysis& a, const std::string& option) {
  return std::find(a.options.begin(), a.options.end(), option) != a.options.end();
}

/// An option given that `entry` does not take: "--count: not used by analysis energy (only A and B take it)".
void reject_options_not_taken(const CLI::App& cmd, const Analysis& entry) {
  std::vector<std::string> all{"--mu", "--from", "--to", "--count", "--jobs", "--resume", "--section", "--vary"};
  for (const auto& o : map_option_names()) all.push_back(o);
  for (const auto& option : all) {
    if (cmd.count(option) == 0 || takes(entry, option)) continue;
    std::vector<std::string> takers;
    for (const Analysis& a : analyses())
      if (takes(a, option)) takers.push_back(a.name);
    std::string list;
    for (std::size_t i = 0; i < takers.size(); ++i)
      list += (i == 0 ? "" : i + 1 == takers.size() ? " and " : ", ") + takers[i];
    throw UsageError(fmt::format("{}: not used by analysis {} (only {} take{} it)", option, entry.name, list,
                                 takers.size() == 1 ? "s" : ""));
  }
}

int analysis(const AnalysisArgs& a, const CLI::App& cmd) {
  // Every option checked before anything is written; an option this analysis ignores is refused.
  const auto& table = analyses();
  const auto entry = std::find_if(table.begin(), table.end(), [&](const Analysis& x) { return x.name == a.name; });
  if (entry == table.end())
    throw std::logic_error("analysis " + a.name + " passed CLI11's check but is not in the table");
  reject_options_not_taken(cmd, *entry);
  if (entry->map)
    return run_map_analysis({a.name, a.run, a.map, a.from, a.to, a.count, a.jobs, a.resume, a.section}, cmd);
  std::vector<ConfigEntry> extra;
  for (const auto& [option, key] : entry->keys) {
    const std::string text = option == "--mu"     ? "[" + a.mus + "]"
                             : option == "--from" ? format_number(a.from)
                             : option == "--to"   ? format_number(a.to)
                                                  : std::to_string(a.count);
    add_option_value(extra, cmd, option, key, text);
  }
  const WheelSetup s = rimless::wheel_setup(resolve(rimless::rimless_analysis_schema(), a.run, extra));
  const rimless::PaperAnalysisOptions paper = rimless::paper_analysis_from_config(s.config);
  const rimless::StagnationOptions stagnation =
      entry->reads_stagnation ? rimless::stagnation_from_config(s.config) : rimless::StagnationOptions{};
  const AnalysisContext context{a, s, paper, stagnation, a.section, a.vary.empty() ? default_stagnation_map() : a.vary};
  if (entry->check != nullptr) entry->check(context, *entry);
  // A resumed sweep must match the one in --out: check before anything is written.
  if (a.resume && !entry->sweep_name.empty()) {
    SweepJob probe;
    probe.dir = a.run.out;
    probe.name = entry->sweep_name;
    probe.resume = true;
    probe.signature = "?";
    if (!std::filesystem::exists(probe.dir / (probe.name + ".signature"))) check_resumable(probe);
  }
  const RunDirectory dir(a.run.out);
  dir.write_config(s.config);
  const std::vector<std::string> files = entry->run(context, dir);
  if (a.run.plot) run_plot_script("plot_analysis.py", {a.name, dir.path().string()});
  for (const auto& f : files) fmt::print("wrote {}\n", (dir.path() / f).string());
  return 0;
}

// --- rimless continuation (docs/guide/rimless.md, "Orbit diagram and basin of attraction") ---
struct ContinuationArgs {
  RunOptions run;
  std::string model;
  rimless::Section section = rimless::Section::Touchdown;
  std::string param;
  double from = 0, to = 0, step = 0;
  int period = 1;
  bool switch_at_pd = false;
};

int continuation(const ContinuationArgs& a, const CLI::App& cmd) {
  const WheelSetup s = wheel_setup(a.run, cmd, a.model);
  rimless::GaitContinuationSpec spec{.param = a.param, .from = a.from, .to = a.to, .step = a.step};
  spec.section = a.section;
  spec.period = a.period;
  spec.switch_at_period_doubling = a.switch_at_pd;
  spec.tuning = rimless::gait_continuation_from_config(s.config);
  ProgressBar bar(100, "% of the interval");
  bar.show(0);
  double reached = 0;  // the branch may turn back at a fold: the farthest q reached
  spec.on_point = [&](double q) { bar.show(100 * (reached = std::max(reached, q))); };
  const auto t0 = std::chrono::steady_clock::now();
  const rimless::GaitBranch b = rimless::continue_gait(s.config, spec);  // throws ConfigError on bad input
  bar.show(100);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!b.failure.empty()) {
    fmt::print(stderr, "error: {}\n", b.failure);
    return 2;
  }
  const RunDirectory dir(a.run.out);
  dir.write_config(s.config);
  dir.write("branch.csv", rimless::gait_branch_csv(b));
  // The switched branch: branch_period<2k>.csv (and its figure), or why there is none.
  std::string switched;
  for (const auto& c : b.switched) {
    if (!c.failure.empty()) {
      switched = c.failure;
      continue;
    }
    const std::string name = fmt::format("branch_period{}", c.period);
    dir.write(name + ".csv", rimless::gait_branch_csv(c));
    switched = fmt::format("{} points, {} ({})", c.branch.points.size(), c.stop_reason, name + ".csv");
  }
  if (a.switch_at_pd && b.switched.empty()) switched = "no period doubling on the branch";
  if (a.run.plot) run_plot_script("plot_maps.py", {"bifurcation", dir.path().string(), b.param});
  if (a.run.json) {
    nlohmann::ordered_json j = rimless::gait_branch_summary(b);
    if (a.switch_at_pd) j["switched"] = switched;
    j["seconds"] = seconds;
    fmt::print("{}\n", j.dump(2));
    return 0;
  }
  fmt::print("continuation in {} from {} to {}: {} points in {:.2f} s ({} Jacobian), {}\n", b.param, a.from, a.to,
             b.branch.points.size(), seconds, b.exact_jacobian ? "exact" : "finite-difference", b.stop_reason);
  for (const auto& r : b.rows)
    if (!r.event.empty()) fmt::print("  {} = {:.10g}: {} (gait {})\n", b.param, r.p, r.event, r.gait);
  if (a.switch_at_pd) fmt::print("period-{} branch at the first period doubling: {}\n", 2 * b.period, switched);
  fmt::print("results in {}\n", (dir.path() / "branch.csv").string());
  return 0;
}
// --- end rimless continuation ---

/// --model: a wheel model's name (rimless::Model), kept as text and set as sim.model (checked as
/// --set checks it).
void add_model_option(CLI::App& cmd, std::string& model, const std::string& doc) {
  cmd.add_option("--model", model, doc)->check(CLI::IsMember(enum_name_list<rimless::Model>()));
}
}  // namespace

void add_rimless_commands(CLI::App& app, std::function<int()>& action) {
  CLI::App* rimless = app.add_subcommand("rimless", "Flexible-leg rimless wheel with stick-slip friction");
  rimless->require_subcommand(1);

  auto args = std::make_shared<SimulateArgs>();
  CLI::App* sim =
      rimless->add_subcommand("simulate", "Simulate the wheel for a number of steps and write a run directory");
  add_run_options(*sim, args->run, "runs/rimless-simulate");
  add_model_option(*sim, args->model,
                   "flexible (spring-damper legs, stick-slip) or rigid (McGeer's wheel); sets sim.model");
  sim->add_option("--steps", args->steps, "number of steps (touchdowns of new legs); sets sim.steps")->type_name("INT");
  sim->add_option("--omega0", args->omega0, "initial angular velocity (rad/s); sets initial.omega")->type_name("FLOAT");
  sim->callback([args, sim, &action] { action = [args, sim] { return simulate(*args, *sim); }; });

  auto fp_args = std::make_shared<FixedPointArgs>();
  CLI::App* fp = rimless->add_subcommand("fixed-point",
                                         "Find a periodic gait: Newton-Raphson on the Poincare map, "
                                         "Floquet multipliers, stability");
  add_run_options(*fp, fp_args->run, "runs/rimless-fixed-point");
  add_model_option(*fp, fp_args->model, "flexible or rigid; sets sim.model");
  add_enum_option(*fp, "--section", fp_args->section,
                  "Poincare section: touchdown of a new leg, or stance leg upright");
  fp->callback([fp_args, fp, &action] { action = [fp_args, fp] { return fixed_point(*fp_args, *fp); }; });

  auto sw = std::make_shared<SweepArgs>();
  CLI::App* swc = rimless->add_subcommand("sweep",
                                          "Sweep one parameter: gait, fixed point, multipliers, stability, "
                                          "speed and energy per point, on all cores, resumable");
  add_run_options(*swc, sw->run, "runs/rimless-sweep");
  swc->add_option("--param", sw->param,
                  "configuration key to vary (e.g. rimless.slope, initial.omega), or "
                  "rimless.mu for mu_s = mu_k")
      ->required();
  swc->add_option("--from", sw->from, "first value (in the key's unit)")->required()->check(finite_number());
  swc->add_option("--to", sw->to, "last value (in the key's unit)")->required()->check(finite_number());
  swc->add_option("--count", sw->count, "number of values, evenly spaced, ends included")
      ->required()
      ->check(CLI::Range(1, kMaxSweepPoints));
  swc->add_option("--jobs", sw->jobs, "worker threads (0: all cores)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  swc->add_flag("--resume", sw->resume, "keep the finished points of an interrupted sweep in --out");
  add_model_option(*swc, sw->model, "flexible or rigid; sets sim.model");
  add_enum_option(*swc, "--section", sw->section, "Poincare section of the fixed points");
  swc->callback([sw, swc, &action] { action = [sw, swc] { return sweep(*sw, *swc); }; });

  auto ct = std::make_shared<ContinuationArgs>();
  CLI::App* ctc = rimless->add_subcommand("continuation",
                                          "Pseudo-arclength continuation of the gait's fixed point in "
                                          "one real key: branch.csv with multipliers, stability and "
                                          "located folds, period doublings, Neimark-Sacker points and "
                                          "gait changes");
  add_run_options(*ctc, ct->run, "runs/rimless-continuation");
  ctc->add_option("--param", ct->param,
                  "real configuration key to continue in (e.g. rimless.slope), or rimless.mu "
                  "for mu_s = mu_k")
      ->required();
  ctc->add_option("--from", ct->from, "start value, where the first fixed point is found (in the key's unit)")
      ->required()
      ->check(finite_number());
  ctc->add_option("--to", ct->to, "end value (in the key's unit)")->required()->check(finite_number());
  ctc->add_option("--step", ct->step,
                  "first arclength step, in the key's unit (default |to - from| times "
                  "analysis.continuation.initial_step, 1/50; the step adapts up to "
                  "analysis.continuation.max_step_factor, 2, times this)")
      ->check(positive_number());
  ctc->add_option("--period", ct->period,
                  "continue period-K orbits: fixed points of the K-th iterate of the map, "
                  "Newton on it from the transient's state at --from")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  ctc->add_flag("--switch-at-pd", ct->switch_at_pd,
                "at the branch's first period doubling, switch to the period-2K "
                "branch born there and continue it too (branch_period2K.csv)");
  add_model_option(*ctc, ct->model, "flexible or rigid; sets sim.model");
  add_enum_option(*ctc, "--section", ct->section, "Poincare section of the fixed points");
  ctc->callback([ct, ctc, &action] { action = [ct, ctc] { return continuation(*ct, *ctc); }; });

  auto an = std::make_shared<AnalysisArgs>();
  std::string described;
  for (const Analysis& x : analyses()) described += (described.empty() ? "" : ", ") + x.name + " (" + x.help + ")";
  CLI::App* anc = rimless->add_subcommand("analysis", "The paper's analyses, each a CSV and a PNG: " + described);
  add_run_options(*anc, an->run, "runs/rimless-analysis");
  anc->add_option("name", an->name, "which analysis")->required()->check(CLI::IsMember(analysis_names()));
  anc->add_option("--mu", an->mus,
                  "friction coefficients (mu_s = mu_k), comma separated, for energy, fixed-points, "
                  "robustness (sets analysis.energy.mu, analysis.fixed_points.mu, "
                  "analysis.robustness.mu)")
      ->type_name("MU,...");
  anc->add_option("--from", an->from,
                  "first value: mu of gait-vs-friction (sets analysis.friction.mu_from) or "
                  "omega0 in rad/s of the stagnation grid (sets stagnation.omega_from)")
      ->check(finite_number());
  anc->add_option("--to", an->to,
                  "last value: mu (sets analysis.friction.mu_to) or omega0 in rad/s (sets "
                  "stagnation.omega_to)")
      ->check(finite_number());
  anc->add_option("--count", an->count, "number of values (sets analysis.friction.count or stagnation.count)")
      ->check(CLI::Range(1, 1000000));
  anc->add_option("--jobs", an->jobs, "worker threads (0: all cores)")->check(CLI::Range(0, 1024));
  anc->add_flag("--resume", an->resume, "keep the finished points of an interrupted run in --out");
  add_enum_option(*anc, "--section", an->section, "Poincare section of the fixed points");
  anc->add_option("--vary", an->vary,
                  "stagnation-map: one map point, KEY=VALUE[,KEY=VALUE...] set on the "
                  "configuration (rimless.mu sets mu_s and mu_k); repeat for more points; default: "
                  "the base and mu, I, C, K one at a time, and I = 0.02 with mu = 0.25");
  add_map_options(*anc, an->map);
  anc->callback([an, anc, &action] { action = [an, anc] { return analysis(*an, *anc); }; });
}

}  // namespace flexgait::cli
