#include "reproduce_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "flexgait/core/run_directory.hpp"
#include "options.hpp"
#include "schema_command.hpp"

namespace flexgait::cli {
namespace {

struct ReproduceOptions {
  std::string out = "runs/reproduce";
  bool quick = false;
};

struct Step {
  std::string dir, title;
  std::vector<std::string> args;  ///< flexgait's arguments, without --out
  std::string caption = {};       ///< what its figures show, one sentence (may be empty)
};

/// One finished run, as reproduce.json lists it for the report.
struct RunRecord {
  std::string dir, title;
  std::string command;  ///< the command that made it, as the report shows it
  int exit_code = 0;
  std::string caption;
};

std::vector<Step> steps(bool quick) {
  const std::string rimless = find_config("rimless.yaml").string();
  auto walk = [](const std::string& name) { return find_config(name).string(); };
  std::vector<Step> s;
  s.push_back({"rimless-flexible",
               "Rimless wheel: flexible legs, stick-slip friction (mu = 0.6)",
               {"rimless", "simulate", "--config", rimless}});
  std::vector<std::string> gait{"rimless", "analysis", "gait-vs-friction", "--config", rimless};
  if (quick) gait.insert(gait.end(), {"--count", "30"});
  s.push_back({"rimless-gait-vs-friction", "Rimless wheel: gait against friction coefficient, thresholds", gait});
  s.push_back({"rimless-energy",
               "Rimless wheel: energy in single support, stick against slip",
               {"rimless", "analysis", "energy", "--config", rimless}});
  s.push_back({"rimless-fixed-points",
               "Rimless wheel: fixed points of the four behaviours (Newton-Raphson)",
               {"rimless", "analysis", "fixed-points", "--config", rimless}});
  std::vector<std::string> robust{"rimless", "analysis", "robustness", "--config", rimless};
  if (quick) robust.insert(robust.end(), {"--mu", "0.105,0.6"});
  s.push_back({"rimless-robustness", "Rimless wheel: robustness of the gaits to perturbations", robust});
  // The stagnation interval lives where the first single support slides: mu just above tan(phi).
  const std::string stagnation = find_config("rimless-stagnation.yaml").string();
  s.push_back({"rimless-stagnation",
               "Rimless wheel: stagnation interval, sliding time near the vertical (paper Fig. 12)",
               {"rimless", "analysis", "stagnation", "--config", stagnation}});
  s.push_back({"rimless-stagnation-map",
               "Rimless wheel: stagnation interval against mu - tan(phi), I, C and K",
               {"rimless", "analysis", "stagnation-map", "--config", stagnation}});
  // Bifurcations: the gait continued in mu through the behaviour thresholds, across the changes of the
  // touchdown section's foot mode, to its end at mu = tan(phi); the orbit diagram over the slope
  // with the continued branch over it (it crosses the section's mode change at slope 0.2193); a basin of the gait.
  s.push_back(
      {"rimless-mu-continuation",
       "Rimless wheel: the gait continued in mu from 0.6 down (pseudo-arclength)",
       {"rimless", "continuation", "--config", rimless, "--param", "rimless.mu", "--from", "0.6", "--to", "0.05"},
       "The fixed point's angular velocity at the touchdown section and its largest |multiplier| against mu: "
       "stable solid, unstable dashed, each gait in its colour, located gait changes, changes of the "
       "section's foot mode and bifurcations marked; the branch ends at mu = tan(phi), where the sliding "
       "gait's friction balances gravity along the slope."});
  s.push_back({"rimless-slope-branch",
               "Rimless wheel: the gait continued in the slope from 0.2 up",
               {"rimless", "continuation", "--config", rimless, "--param", "rimless.slope", "--from", "0.2", "--to",
                "0.2355"}});
  s.push_back({"rimless-orbit-slope",
               "Rimless wheel: orbit diagram over the slope, with the continued branches",
               {"rimless", "analysis", "orbit-diagram", "--config", rimless, "--param", "rimless.slope", "--from",
                "0.2", "--to", "0.2355", "--count", quick ? "40" : "200", "--transient", quick ? "200" : "400",
                "--record", quick ? "32" : "64", "--branch", "@root/rimless-slope-branch/branch.csv"},
               "Each dot is the angular velocity at a touchdown after the transient, coloured by the step's gait; "
               "black: the continued fixed points (solid stable, dashed unstable). Past the Neimark-Sacker point the "
               "steps spread over an invariant curve and then chaos with periodic windows; past 0.2356 the wheel "
               "runs away."});
  s.push_back({"rimless-basin",
               "Rimless wheel: basin of attraction of the gait over the initial state",
               {"rimless", "analysis", "basin", "--config", rimless, "--x", "initial.omega", "--y", "initial.beta",
                "--x-range", quick ? "-1:3:24" : "-1:3:80", "--y-range", quick ? "-0.3:0.3:16" : "-0.3:0.3:50"},
               "Each cell is one start (initial angular velocity, stance-leg angle): green when it converges to the "
               "gait Newton finds from the configured start, red when the wheel rolls back onto its previous leg, "
               "grey when the start puts a foot below the ground."});
  s.push_back({"humanoid-bench", "Humanoid: stiffness bench (thesis Fig. 12)", {"humanoid", "bench"}});
  std::vector<std::string> quasi{"humanoid", "compensation", "--config", walk("walk-quasi-static.yaml")};
  if (quick) quasi.insert(quasi.end(), {"--set", "walk.steps=3"});
  s.push_back(
      {"humanoid-quasi-static", "Humanoid: quasi-static walking, 24 s/step (thesis Figs. 13a, 14a, 15)", quasi});
  s.push_back({"humanoid-dynamic",
               "Humanoid: dynamic walking, 3 s/step (thesis Figs. 13b, 14b, 15)",
               {"humanoid", "compensation", "--config", walk("walk-dynamic.yaml")}});
  s.push_back({"humanoid-mismatch",
               "Humanoid: stiffness model wrong by ±30 % (3 s/step, balance on)",
               {"humanoid", "mismatch", "--config", walk("walk-dynamic.yaml")}});
  std::vector<std::string> fast{"humanoid", "compensation", "--config", walk("walk-robotis.yaml")};
  if (quick) fast.insert(fast.end(), {"--set", "walk.steps=3"});
  s.push_back({"humanoid-compensation-1s",
               "Humanoid: 1.0 s/step, compensation off against the field's baselines (ROBOTIS, TALOS) and ours", fast});
  s.push_back({"humanoid-walk-1s",
               "Humanoid: ROBOTIS's 1.0 s/step with compensation (beyond the thesis)",
               {"humanoid", "walk", "--config", walk("walk-robotis.yaml")}});
  // The walking envelope: a campaign (campaign/ on the sweep runner), 10-step walks of the default
  // configuration; quick: the corners of the full grid's step lengths 0.1 and 0.3 m.
  s.push_back(
      {"humanoid-envelope",
       "Humanoid: walking envelope, step length × step time, compensation off against both (a campaign)",
       {"campaign", "humanoid-walk", "--grid", quick ? "walk.step_length=0.1,0.3" : "walk.step_length=0.05:0.3:6",
        "--grid", quick ? "walk.step_time=0.6,0.8" : "walk.step_time=0.5:1.0:6", "--grid",
        "control.compensation=off,both", "--plot-metrics", "fell,pelvis_roll_error_max"},
       "Each cell is one walk of 10 steps at that step length and step time: on the left whether the twin "
       "fell, on the right its peak pelvis roll error (of a fall: up to the fall); the top row without the "
       "deformation compensators, the bottom row with both, on the same colour scale."});
  // The largest recoverable push (docs/guide/campaigns.md): a campaign of bisections, standing and at mid single
  // support of the 3rd of 6 steps, pd against dcm balance; quick: forward only, with both
  // compensators only (4 bisections).
  s.push_back(
      {"humanoid-push-recovery",
       "Humanoid: largest recoverable push against the capture-point bound, pd against dcm balance (a campaign)",
       {"campaign", "humanoid-push-recovery", "--set", "walk.steps=6", "--grid",
        "push_recovery.situation=standing,walking", "--grid",
        quick ? "push_recovery.direction=forward" : "push_recovery.direction=forward,backward,left,right", "--grid",
        quick ? "control.compensation=both" : "control.compensation=off,both", "--grid", "balance.mode=pd,dcm",
        "--plot-metrics", "fraction,recovered"},
       "Each cell is a bisection (to 1 N s) on the impulse of a 0.1 s chest push: the largest impulse the twin "
       "recovers without a fall, and that impulse as a fraction of the capture-point bound (the impulse an "
       "ankle strategy can absorb at best: m sqrt(g/z_c) times the distance from the COM to the support "
       "polygon's edge in the push's direction). Standing: pushed at 4 s; walking: at mid single support of "
       "the 3rd step (left foot in stance; a push to the right, toward the swinging foot, is caught by the "
       "step that lands 0.4 s later, so it can exceed the bound, which assumes no step)."});
  // One push, seen (docs/guide/campaigns.md): the full variant renders the 1 s/step walk pushed outward at mid single
  // support of its 3rd step (the example push of docs/guide/campaigns.md), frames and video.mp4 (ffmpeg).
  if (!quick)
    s.push_back({"humanoid-push-video",
                 "Humanoid: a 7 N s chest push at mid single support, 1.0 s/step (video)",
                 {"humanoid", "walk", "--config", walk("walk-robotis.yaml"), "--set", "walk.steps=6", "--set",
                  "disturbance.push.time=4.1", "--set", "disturbance.push.force_y=70", "--render"},
                 "The twin with its default compensation and pd balance, pushed at the chest with 70 N for 0.1 s (the "
                 "orange arrow) toward the left, away from its only support, the left foot, in the middle of the 3rd "
                 "step's single support; it recovers and walks on. The largest push it recovers in that situation is "
                 "the walking, left cell of humanoid-push-recovery."});
  return s;
}

}  // namespace

std::vector<ReproduceRun> reproduce_runs() {
  std::vector<ReproduceRun> out;
  for (const Step& step : steps(false)) {
    std::string command;
    for (const auto& a : step.args) {
      if (a.starts_with("-")) break;
      command += (command.empty() ? "" : " ") + a;
    }
    out.push_back({step.dir, command});
  }
  return out;
}

namespace {

/// The command line of a step as the report shows it: configuration files by their names only.
std::string shown_command(const Step& step) {
  std::string command = "flexgait";
  for (const auto& a : step.args)
    command += " " + (a.find('/') != std::string::npos ? std::filesystem::path(a).filename().string() : a);
  return command;
}

/// reproduce.json: the variant and every run (directory, title, command, exit code).
std::string manifest(const std::vector<RunRecord>& runs, bool quick) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& r : runs)
    list.push_back({{"dir", r.dir},
                    {"title", r.title},
                    {"command", r.command},
                    {"exit_code", r.exit_code},
                    {"caption", r.caption}});
  return nlohmann::json{{"quick", quick}, {"runs", list}}.dump(2) + "\n";
}

/// Writes index.html with python/report.py from reproduce.json and the runs' own files; false
/// (after saying why) if the script is missing or fails, e.g. on a value a run did not write.
bool write_report(const RunDirectory& root) {
  const auto script = find_python_script("report.py");
  if (!script) {
    fmt::print(stderr, "[reproduce] report.py not found; index.html not written\n");
    return false;
  }
  const int status = run_python_script(*script, {root.path().string()});
  if (status != 0) {
    fmt::print(stderr, "[reproduce] report.py exited with {}; index.html not written\n", status);
    return false;
  }
  return true;
}

int reproduce(const ReproduceOptions& o) {
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
  const std::vector<Step> plan = steps(o.quick);  // finds the configurations before writing anything
  const RunDirectory root(o.out);
  std::filesystem::remove(root.path() / "index.html");  // a report of earlier runs would mislead
  std::vector<RunRecord> runs;
  int failures = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const Step& st = plan[i];
    fmt::print("[reproduce {}/{}] {}\n", i + 1, plan.size(), st.title);
    std::fflush(stdout);
    std::vector<std::string> argv{self.string()};
    for (const auto& arg : st.args)  // "@root/DIR/FILE": a file an earlier run of this reproduction wrote
      argv.push_back(arg.starts_with("@root/") ? (root.path() / arg.substr(6)).string() : arg);
    argv.insert(argv.end(), {"--out", (root.path() / st.dir).string()});
    const int code = run_process(argv);
    if (code != 0) {
      ++failures;
      fmt::print(stderr, "[reproduce] {} exited with {}\n", st.dir, code);
    }
    runs.push_back({st.dir, st.title, shown_command(st), code, st.caption});
  }
  root.write("reproduce.json", manifest(runs, o.quick));
  root.write("schema.json", schema_document());  // what every summary field means, from the records
  const bool report_written = write_report(root);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print("[reproduce] {} runs in {:.0f} s, {} failed; report: {}\n", plan.size(), seconds, failures,
             report_written ? (root.path() / "index.html").string() : "not written");
  return failures == 0 && report_written ? 0 : 1;
}

}  // namespace

void add_reproduce_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<ReproduceOptions>();
  CLI::App* r = app.add_subcommand(
      "reproduce",
      "Run every reproduction of both studies (rimless wheel analyses, stiffness bench, compensation "
      "studies, stiffness mismatch, 1 s/step walk, walking envelope) and write OUT/index.html with the figures and our "
      "numbers beside the thesis's and the paper's (python/report.py over data/report/references.yaml); "
      "exit 1 if a run failed or the report could not be written");
  r->add_option("--out", o->out, "output directory")->capture_default_str();
  r->add_flag(
      "--quick", o->quick,
      "shorter variant: 3 steps of the 24 s/step walk, coarser rimless sweeps, a coarser orbit diagram and basin, "
      "an 8-point walking envelope");
  r->callback([o, &action] { action = [o] { return reproduce(*o); }; });
}

}  // namespace flexgait::cli
