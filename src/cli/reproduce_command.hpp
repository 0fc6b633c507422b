#pragma once
/// \file reproduce_command.hpp  `flexgait reproduce`: every reproduction of both studies, one report.
#include <CLI/CLI.hpp>

#include <functional>

namespace flexgait::cli {
/// Registers `flexgait reproduce`; its action is stored in `action`.
void add_reproduce_command(CLI::App& app, std::function<int()>& action);
}  // namespace flexgait::cli
