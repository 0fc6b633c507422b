// flexgait: the command-line program. Exit codes: 0 success, 1 runtime failure, 2 bad usage
// or bad configuration (one line on stderr naming the key, the value and what is allowed).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <functional>
#include <system_error>

#include "flexgait/core/config.hpp"
#include "flexgait/version.hpp"
#include "humanoid_commands.hpp"
#include "reproduce_command.hpp"
#include "rimless_commands.hpp"
#include "schema_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"flexgait: legged locomotion with compliance (flexible-leg rimless wheel, humanoid with elastic gears)"};
  app.set_version_flag("--version", std::string("flexgait ") + flexgait::kVersion);
  app.require_subcommand(1);
  std::function<int()> action;
  flexgait::cli::add_rimless_commands(app, action);
  flexgait::cli::add_humanoid_commands(app, action);
  flexgait::cli::add_reproduce_command(app, action);
  flexgait::cli::add_schema_command(app, action);
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
    fmt::print(stderr, "error: {}; see '{} --help'\n", e.what(), path);
    return 2;
  }
  try {
    return action ? action() : 2;
  } catch (const flexgait::UsageError& e) {  // bad configuration or bad usage, ConfigError included
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  } catch (const std::logic_error& e) {  // a broken contract inside flexgait
    fmt::print(stderr, "error: internal error (a bug in flexgait, please report it): {}\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
}
