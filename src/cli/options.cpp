#include "options.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <system_error>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/text.hpp"

#include "paths.hpp"

extern char** environ;

namespace flexgait::cli {

void add_run_options(CLI::App& app, RunOptions& o, const std::string& default_out) {
  o.out = default_out;
  app.add_option("--config", o.config_file,
                 "YAML configuration file (keys as in config.yaml of a run), or the NAME of a bundled one "
                 "(flexgait configs lists them)")
      ->transform(config_file_option());
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

std::vector<std::string> split_list(const std::string& text) {
  return split_text(text, ',');
}

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

CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& text) {
        const double inf = std::numeric_limits<double>::infinity();
        if (std::string problem = number_problem(text, -inf, inf); !problem.empty()) return problem;
        if (!(*parse_finite_number(text) > 0)) return fmt::format("'{}' is not greater than 0", one_line(text));
        return std::string();
      },
      "NUMBER > 0");
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
  if (const auto share = installed_data_dir(); !share.empty()) dirs.push_back(share / "python");
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

void show_stage(const std::string& what) {
  if (isatty(STDERR_FILENO) != 0) fmt::print(stderr, "{}\n", what);
}

bool run_plot_script(const std::string& script, const std::vector<std::string>& args) {
  const auto path = find_python_script(script);
  if (!path) {
    fmt::print(stderr, "warning: plotting script {} not found; no figures drawn\n", script);
    return false;
  }
  show_stage(fmt::format("drawing the figures ({})", script));
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

std::filesystem::path installed_data_dir() {
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return {};
  const std::filesystem::path share = exe.parent_path() / FLEXGAIT_DATA_INSTALL_DIR;
  return std::filesystem::is_directory(share, error) ? share.lexically_normal() : std::filesystem::path();
}

std::vector<std::filesystem::path> config_dirs() {
  std::vector<std::filesystem::path> dirs;
  std::error_code error;
  if (const auto share = installed_data_dir();
      !share.empty() && std::filesystem::is_directory(share / "configs", error))
    dirs.push_back(share / "configs");
  for (const char* d : kConfigDirs)
    if (std::filesystem::is_directory(d, error) &&
        std::find(dirs.begin(), dirs.end(), std::filesystem::path(d)) == dirs.end())
      dirs.emplace_back(d);
  return dirs;
}

std::filesystem::path find_config(const std::string& file) {
  std::error_code error;
  for (const auto& d : config_dirs())
    if (std::filesystem::is_regular_file(d / file, error)) return d / file;
  throw std::runtime_error("configuration " + file + " not found in the installed share directory or the source tree");
}

std::optional<std::filesystem::path> resolve_config_name(const std::string& text) {
  std::error_code error;
  if (text.empty()) return std::nullopt;
  if (std::filesystem::exists(text, error) && !std::filesystem::is_directory(text, error))
    return std::filesystem::path(text);
  const std::filesystem::path name(text);
  if (name.has_parent_path() || name.has_extension() || text.front() == '.') return std::nullopt;
  for (const auto& d : config_dirs())
    if (std::filesystem::is_regular_file(d / (text + ".yaml"), error)) return d / (text + ".yaml");
  return std::nullopt;
}

CLI::Validator config_file_option() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (const auto path = resolve_config_name(text)) {
          text = path->string();
          return "";
        }
        std::string names;
        for (const auto& [name, path] : bundled_configs()) names += (names.empty() ? "" : ", ") + name;
        return fmt::format("'{}' is neither a file nor the name of a bundled configuration ({})", one_line(text),
                           names.empty() ? "none found" : names);
      },
      "FILE|NAME");
}

std::string config_description(const std::filesystem::path& file) {
  const std::string text = read_text_file(file);
  for (const std::string& line : split_text(text, '\n')) {
    if (line.empty() || line.front() != '#') break;
    const std::size_t start = line.find_first_not_of("# \t");
    if (start != std::string::npos) return line.substr(start);
  }
  return "";
}

std::vector<std::pair<std::string, std::filesystem::path>> bundled_configs() {
  std::map<std::string, std::filesystem::path> found;
  std::error_code error;
  for (const auto& d : config_dirs())
    for (const auto& entry : std::filesystem::directory_iterator(d, error))
      if (entry.is_regular_file(error) && entry.path().extension() == ".yaml")
        found.emplace(entry.path().stem().string(), entry.path());  // the first directory's wins
  return {found.begin(), found.end()};
}

}  // namespace flexgait::cli
