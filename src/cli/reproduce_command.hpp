#pragma once
/// \file reproduce_command.hpp  `flexgait reproduce`: every reproduction of both studies, one report.
#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace flexgait::cli {
/// One run of the full reproduction: its directory under --out and the command that makes it
/// ("humanoid compensation", "rimless analysis basin", "campaign humanoid-walk": the arguments
/// before the first option).
struct ReproduceRun {
  std::string dir, command;
};
std::vector<ReproduceRun> reproduce_runs();

/// Registers `flexgait reproduce`; its action is stored in `action`.
void add_reproduce_command(CLI::App& app, std::function<int()>& action);
}  // namespace flexgait::cli
