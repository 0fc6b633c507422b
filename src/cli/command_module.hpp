#pragma once
/// \file command_module.hpp
/// The commands that need MuJoCo (`humanoid`, `campaign`, `reproduce`, `schema`) live in a module
/// that the executable loads only when the command line may name one of them. MuJoCo brings
/// OSMesa and with it LLVM: loading and relocating those costs ~20 ms at every start, which a
/// `rimless` run (0.25 s for 2000 steps) need not pay. The executable holds `rimless` and what
/// every command shares (options.hpp, mpi_distributor.hpp, which the module calls back: the
/// executable exports its symbols); main() loads the module unless the first word names one of
/// the executable's own commands, so `--help`, an unknown word or a module command see all of them.
#include <CLI/CLI.hpp>

#include <functional>

/// The module's one entry (command_module_entry.cpp), looked up by this name: registers its
/// commands on `app` as the executable's add_*_command functions do, and routes MuJoCo's messages.
extern "C" void flexgait_add_module_commands(CLI::App& app, std::function<int()>& action);

namespace flexgait::cli {

/// Loads the module (file FLEXGAIT_COMMAND_MODULE, found on the executable's run path: beside it
/// in the build tree, in lib/ when installed) and calls its entry. Throws std::runtime_error
/// naming the file and the loader's reason if it cannot be loaded.
void add_module_commands(CLI::App& app, std::function<int()>& action);

}  // namespace flexgait::cli
