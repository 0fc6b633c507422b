// flexgait: the command-line program. Exit codes: 0 success, 1 runtime failure, 2 bad usage
// or bad configuration (one line on stderr naming the key, the value and what is allowed). Every
// message is one line: control characters escaped, long text cut (core one_line). Under mpirun
// a bad argument is said once, by rank 0, which exits 2 (so does mpirun); the other ranks exit 0.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <functional>
#include <system_error>

#include "command_module.hpp"
#include "configs_command.hpp"
#include "flexgait/campaign/program_build.hpp"
#include "flexgait/core/config.hpp"
#include "flexgait/core/text.hpp"
#include "mpi_distributor.hpp"
#include "rimless_commands.hpp"

namespace {

// A word where a subcommand belongs that names none of them ("" if there is none): CLI11 says only
// "A subcommand is required".
std::string unknown_command(const CLI::App& app, int argc, char** argv) {
  const CLI::App* cur = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    const auto subs = cur->get_subcommands([](const CLI::App*) { return true; });
    if (word.empty() || word[0] == '-' || subs.empty()) return "";
    const CLI::App* next = nullptr;
    std::string names;
    for (const CLI::App* s : subs) {
      if (s->check_name(word)) next = s;
      names += (names.empty() ? "" : ", ") + s->get_name();
    }
    if (next == nullptr)
      return fmt::format("unknown command '{}'; the commands are {}", flexgait::one_line(word), names);
    cur = next;
  }
  return "";
}

// Whether the first argument names one of the commands registered on `app` so far.
bool names_registered_command(const CLI::App& app, int argc, char** argv) {
  if (argc < 2) return false;
  for (const CLI::App* s : app.get_subcommands([](const CLI::App*) { return true; }))
    if (s->check_name(argv[1])) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"flexgait: legged locomotion with compliance (flexible-leg rimless wheel, humanoid with elastic gears)"};
  app.set_version_flag("--version", "flexgait " + flexgait::campaign::program_build());
  app.require_subcommand(1);
  std::function<int()> action;
  flexgait::cli::add_rimless_commands(app, action);
  flexgait::cli::add_configs_command(app, action);
  // The commands that need MuJoCo come from a module, loaded unless the first word names one of
  // the commands above (command_module.hpp).
  if (!names_registered_command(app, argc, argv)) {
    try {
      flexgait::cli::add_module_commands(app, action);
    } catch (const std::exception& e) {
      fmt::print(stderr, "error: {}\n", flexgait::one_line(e.what(), 1000));
      return 1;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Name the deepest subcommand reached, so the hint points at the right --help.
    std::string path = "flexgait";
    for (const CLI::App* cur = &app; !cur->get_subcommands().empty();) {
      cur = cur->get_subcommands().front();
      path += " " + cur->get_name();
    }
    const std::string unknown = unknown_command(app, argc, argv);
    // Every rank has the same arguments: rank 0 says it and exits 2. Another rank leaves both to
    // rank 0: had it exited 2 first, mpirun would abort the job, rank 0 unheard (seen under load).
    if (flexgait::cli::secondary_mpi_rank()) return 0;
    fmt::print(stderr, "error: {}; see '{} --help'\n", unknown.empty() ? flexgait::one_line(e.what(), 1000) : unknown,
               path);
    return 2;
  }
  try {
    return action ? action() : 2;
  } catch (const flexgait::UsageError& e) {  // bad configuration or bad usage, ConfigError included
    // Under mpirun every rank meets it (a campaign's ranks agree on it first): rank 0 says it once
    // and exits 2; the others exit 0, for the reason above.
    if (flexgait::cli::secondary_mpi_rank()) return 0;
    fmt::print(stderr, "error: {}\n", flexgait::one_line(e.what(), 1000));
    return 2;
  } catch (const std::logic_error& e) {  // a broken contract inside flexgait
    fmt::print(stderr, "error: internal error (a bug in flexgait, please report it): {}\n",
               flexgait::one_line(e.what(), 1000));
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", flexgait::one_line(e.what(), 1000));
    return 1;
  }
}
