#pragma once
#include <CLI/CLI.hpp>

#include <functional>

namespace flexgait::cli {
/// Registers `flexgait humanoid ...`; the chosen subcommand's action is stored in `action`.
void add_humanoid_commands(CLI::App& app, std::function<int()>& action);
}  // namespace flexgait::cli
