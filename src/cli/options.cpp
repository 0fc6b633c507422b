#include "options.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <limits>
#include <system_error>

#include "flexgait/core/text.hpp"

#include "paths.hpp"

extern char** environ;

namespace flexgait::cli {

void add_run_options(CLI::App& app, RunOptions& o, const std::string& default_out) {
  o.out = default_out;
  app.add_option("--config", o.config_file, "YAML configuration file (keys as in config.yaml of a run)")
      ->check(CLI::ExistingFile);
  app.add_option("--set", o.overrides, "override one key, e.g. --set rimless.mu_s=0.4 (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  app.add_option("--out", o.out, "run directory for config.yaml, CSV logs, summary.json and plots")
      ->capture_default_str();
  app.add_flag("--json", o.json, "print summary.json on stdout");
  app.add_flag("!--no-plot", o.plot, "do not draw the PNG figures");
}

Config resolve(const Schema& schema, const RunOptions& o, const std::vector<ConfigEntry>& extra) {
  std::optional<std::filesystem::path> file;
  if (!o.config_file.empty()) file = o.config_file;
  return resolve_config(schema, file, o.overrides, extra);
}

void add_option_value(std::vector<ConfigEntry>& out, const CLI::App& cmd, const std::string& option,
                      const std::string& key, const std::string& text) {
  if (cmd.get_option_no_throw(option) != nullptr && cmd.count(option) > 0) out.push_back({key, text, option});
}

std::vector<std::string> split_list(const std::string& text) { return split_text(text, ','); }

namespace {

// Why `text` is not a finite number in [lo, hi], or "" if it is one.
std::string number_problem(const std::string& text, double lo, double hi) {
  const std::optional<double> number = parse_finite_number(text);
  if (!number) return fmt::format("'{}' is not a finite number", one_line(text));
  const double v = *number;
  if (v < lo || v > hi) return fmt::format("'{}' is not in [{}, {}]", one_line(text), lo, hi);
  return "";
}

}  // namespace

CLI::Validator finite_number() {
  const double inf = std::numeric_limits<double>::infinity();
  return CLI::Validator([inf](std::string& text) { return number_problem(text, -inf, inf); }, "NUMBER");
}

CLI::Validator number_list(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) {
        for (const auto& item : split_list(text))
          if (auto problem = number_problem(item, lo, hi); !problem.empty()) return problem;
        return std::string();
      },
      fmt::format("NUMBER,... in [{}, {}]", lo, hi));
}

std::optional<std::filesystem::path> find_python_script(const std::string& script) {
  std::vector<std::filesystem::path> dirs;
  if (const char* env = std::getenv("FLEXGAIT_PLOT_DIR")) dirs.emplace_back(env);
  for (const char* d : kPlotDirs) dirs.emplace_back(d);
  for (const auto& d : dirs)
    if (std::filesystem::exists(d / script)) return d / script;
  return std::nullopt;
}

int run_python_script(const std::filesystem::path& script, const std::vector<std::string>& args) {
  // The scripts check the names they read against `flexgait schema` (python/flexgait_plotting.py):
  // this program, unless the caller named another.
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) setenv("FLEXGAIT_EXE", self.c_str(), 0);
  std::vector<std::string> argv{"/usr/bin/python3", script.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  return run_process(argv);
}

bool run_plot_script(const std::string& script, const std::vector<std::string>& args) {
  const auto path = find_python_script(script);
  if (!path) {
    fmt::print(stderr, "warning: plotting script {} not found; no figures drawn\n", script);
    return false;
  }
  const int status = run_python_script(*path, args);
  if (status < 0) {
    fmt::print(stderr, "warning: cannot start /usr/bin/python3; no figures drawn\n");
    return false;
  }
  if (status != 0) {
    fmt::print(stderr, "warning: {} failed; figures may be missing\n", script);
    return false;
  }
  return true;
}

int run_process(const std::vector<std::string>& args) {
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

std::filesystem::path find_config(const std::string& name) {
  for (const char* d : kConfigDirs)
    if (std::filesystem::exists(std::filesystem::path(d) / name)) return std::filesystem::path(d) / name;
  throw std::runtime_error("configuration " + name + " not found in the source tree or the installed share directory");
}

}  // namespace flexgait::cli
