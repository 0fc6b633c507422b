#pragma once
#include <CLI/CLI.hpp>

#include <functional>

namespace flexgait::cli {
/// Registers `flexgait rimless ...`; the chosen subcommand's action is stored in `action`.
void add_rimless_commands(CLI::App& app, std::function<int()>& action);
}  // namespace flexgait::cli
