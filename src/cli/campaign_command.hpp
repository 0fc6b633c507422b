#pragma once
#include <CLI/CLI.hpp>

#include <functional>

namespace flexgait::cli {
/// Registers `flexgait campaign EXPERIMENT --grid ...`; its action is stored in `action`.
void add_campaign_command(CLI::App& app, std::function<int()>& action);
}  // namespace flexgait::cli
