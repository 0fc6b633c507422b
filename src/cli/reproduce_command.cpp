#include "reproduce_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>

#include "flexgait/core/run_directory.hpp"
#include "options.hpp"
#include "report_html.hpp"

namespace flexgait::cli {
namespace {

struct ReproduceOptions {
  std::string out = "runs/reproduce";
  bool quick = false;
};

struct Step {
  std::string dir, title;
  std::vector<std::string> args;  ///< flexgait's arguments, without --out
};

std::vector<Step> steps(bool quick) {
  const std::string rimless = find_config("rimless.yaml").string();
  auto walk = [](const std::string& name) { return find_config(name).string(); };
  std::vector<Step> s;
  s.push_back({"rimless-flexible", "Rimless wheel: flexible legs, stick-slip friction (mu = 0.6)",
               {"rimless", "simulate", "--config", rimless}});
  std::vector<std::string> gait{"rimless", "analysis", "gait-vs-friction", "--config", rimless};
  if (quick) gait.insert(gait.end(), {"--count", "30"});
  s.push_back({"rimless-gait-vs-friction", "Rimless wheel: gait against friction coefficient, thresholds", gait});
  s.push_back({"rimless-energy", "Rimless wheel: energy in single support, stick against slip",
               {"rimless", "analysis", "energy", "--config", rimless}});
  s.push_back({"rimless-fixed-points", "Rimless wheel: fixed points of the four behaviours (Newton-Raphson)",
               {"rimless", "analysis", "fixed-points", "--config", rimless}});
  std::vector<std::string> robust{"rimless", "analysis", "robustness", "--config", rimless};
  if (quick) robust.insert(robust.end(), {"--mu", "0.105,0.6"});
  s.push_back({"rimless-robustness", "Rimless wheel: robustness of the gaits to perturbations", robust});
  std::vector<std::string> stagnation{"rimless", "analysis", "stagnation", "--config", rimless};
  if (quick) stagnation.insert(stagnation.end(), {"--count", "30"});
  s.push_back({"rimless-stagnation", "Rimless wheel: stagnation against initial angular velocity (paper Fig. 12)",
               stagnation});
  s.push_back({"humanoid-bench", "Humanoid: stiffness bench (thesis Fig. 12)", {"humanoid", "bench"}});
  std::vector<std::string> quasi{"humanoid", "compensation", "--config", walk("walk-quasi-static.yaml")};
  if (quick) quasi.insert(quasi.end(), {"--set", "walk.steps=3"});
  s.push_back({"humanoid-quasi-static", "Humanoid: quasi-static walking, 24 s/step (thesis Figs. 13a, 14a, 15)", quasi});
  s.push_back({"humanoid-dynamic", "Humanoid: dynamic walking, 3 s/step (thesis Figs. 13b, 14b, 15)",
               {"humanoid", "compensation", "--config", walk("walk-dynamic.yaml")}});
  s.push_back({"humanoid-mismatch", "Humanoid: stiffness model wrong by ±30 % (3 s/step, balance on)",
               {"humanoid", "mismatch", "--config", walk("walk-dynamic.yaml")}});
  s.push_back({"humanoid-walk-1s", "Humanoid: ROBOTIS's 1.0 s/step with compensation (beyond the thesis)",
               {"humanoid", "walk", "--config", walk("walk-robotis.yaml")}});
  return s;
}

int reproduce(const ReproduceOptions& o) {
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
  const std::vector<Step> plan = steps(o.quick);  // finds the configurations before writing anything
  const RunDirectory root(o.out);
  std::vector<ReportSection> sections;
  int failures = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const Step& st = plan[i];
    fmt::print("[reproduce {}/{}] {}\n", i + 1, plan.size(), st.title);
    std::fflush(stdout);
    std::vector<std::string> argv{self.string()};
    argv.insert(argv.end(), st.args.begin(), st.args.end());
    argv.insert(argv.end(), {"--out", (root.path() / st.dir).string()});
    const int code = run_process(argv);
    if (code != 0) {
      ++failures;
      fmt::print(stderr, "[reproduce] {} exited with {}\n", st.dir, code);
    }
    std::string command = "flexgait";
    for (const auto& a : st.args) command += " " + (a.find('/') != std::string::npos ? std::filesystem::path(a).filename().string() : a);
    sections.push_back({st.dir, st.title, command, code});
  }
  root.write("index.html", reproduction_report(root.path(), sections, o.quick));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print("[reproduce] {} runs in {:.0f} s, {} failed; report: {}\n", plan.size(), seconds, failures,
             (root.path() / "index.html").string());
  return failures == 0 ? 0 : 1;
}

}  // namespace

void add_reproduce_command(CLI::App& app, std::function<int()>& action) {
  auto o = std::make_shared<ReproduceOptions>();
  CLI::App* r = app.add_subcommand(
      "reproduce", "Run every reproduction of both studies (rimless wheel analyses, stiffness bench, compensation "
                   "studies, stiffness mismatch, 1 s/step walk) and write OUT/index.html with the figures and our "
                   "numbers beside the thesis's and the paper's; exit 1 if a run failed");
  r->add_option("--out", o->out, "output directory")->capture_default_str();
  r->add_flag("--quick", o->quick, "shorter variant: 3 steps of the 24 s/step walk, coarser rimless sweeps");
  r->callback([o, &action] { action = [o] { return reproduce(*o); }; });
}

}  // namespace flexgait::cli
