#pragma once
/// \file configs_command.hpp  `flexgait configs`: the bundled configurations, by the names that
/// `--config NAME` takes.
#include <CLI/CLI.hpp>

#include <functional>

namespace flexgait::cli {
/// Registers `flexgait configs`; its action is stored in `action`.
void add_configs_command(CLI::App& app, std::function<int()>& action);
}  // namespace flexgait::cli
