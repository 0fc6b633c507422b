#pragma once
/// \file options.hpp  Options every run-writing subcommand shares, and their handling.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/enum_names.hpp"

namespace flexgait::cli {

struct RunOptions {
  std::string config_file;             ///< --config
  std::vector<std::string> overrides;  ///< --set key=value, in order
  std::string out;                     ///< --out
  bool json = false;                   ///< --json
  bool plot = true;                    ///< --no-plot clears it
};

/// Adds --config, --set, --out, --json and --no-plot to a subcommand.
void add_run_options(CLI::App& app, RunOptions& options, const std::string& default_out);

/// Resolves the configuration: defaults, then --config, then the values of options that set a key
/// (`options`: key, text as given, origin "--steps"; checked as --set is, errors naming the option),
/// then --set (so an explicit --set wins).
Config resolve(const Schema& schema, const RunOptions& options, const std::vector<ConfigEntry>& extra = {});

/// An option's value as a ConfigEntry for resolve(), or none when the option was not given.
void add_option_value(std::vector<ConfigEntry>& out, const CLI::App& cmd, const std::string& option,
                      const std::string& key, const std::string& text);

/// An option taking one of a named enum's names (core/enum_names.hpp), stored as the enum: the help and a
/// wrong value's error (exit 2) list the names; the default shown is the value's name.
template <NamedEnum E>
CLI::Option* add_enum_option(CLI::App& cmd, const std::string& name, E& value, const std::string& doc) {
  return cmd
      .add_option_function<std::string>(
          name, [&value](const std::string& text) { value = enum_from_name<E>(text).value(); }, doc)
      ->check(CLI::IsMember(enum_name_list<E>()))
      ->default_str(std::string(name_of(value)));
}

/// CLI11 check of a number option: rejects empty text, junk, NaN and infinities, naming the option.
CLI::Validator finite_number();
/// The same, and greater than 0.
CLI::Validator positive_number();

/// The fields of a comma-separated list as given, empty ones kept (CLI11's delimiter drops them,
/// so list options are read as one string and split here).
std::vector<std::string> split_list(const std::string& text);

/// CLI11 check of a comma-separated list of finite numbers in [lo, hi].
CLI::Validator number_list(double lo, double hi);

/// A Python script of the CLI (python/NAME): from $FLEXGAIT_PLOT_DIR, the source tree or the
/// installed share directory; nullopt if none has it.
std::optional<std::filesystem::path> find_python_script(const std::string& script);

/// Runs `/usr/bin/python3 <script> <args...>`, waits; returns its exit code as run_process does.
int run_python_script(const std::filesystem::path& script, const std::vector<std::string>& args);

/// One line on standard error saying what a command does next, when that is a terminal (a
/// stage that shows no progress bar and may take seconds: drawing figures, encoding a video).
void show_stage(const std::string& what);

/// Runs `/usr/bin/python3 <script> <args...>` from the plotting-script directory; returns
/// false (after printing a warning) if the script is missing or fails. Plots are optional.
/// On a terminal it says first that it draws the figures.
bool run_plot_script(const std::string& script, const std::vector<std::string>& args);

/// Runs args[0] (a path) with these arguments, waits; returns its exit code, -1 if it could not
/// start, 128 + signal if it was killed.
int run_process(const std::vector<std::string>& args);

/// The installed share directory, <prefix>/share/flexgait, found from this executable's own path
/// (so an install under any --prefix finds its files); empty when the program is not installed
/// (a build tree has no such directory beside it).
std::filesystem::path installed_data_dir();

/// The directories of the bundled configurations, in search order: the install's
/// share/flexgait/configs, then the source tree's configs/ (an uninstalled build). Only those that exist.
std::vector<std::filesystem::path> config_dirs();

/// A shipped configuration (FILE, e.g. "rimless.yaml") from config_dirs(); throws if none has it.
std::filesystem::path find_config(const std::string& file);

/// What --config names: a path that exists, as given; else a bundled configuration's NAME (no
/// directory, no extension: "walk-dynamic" is walk-dynamic.yaml of config_dirs()). nullopt if neither.
std::optional<std::filesystem::path> resolve_config_name(const std::string& text);

/// CLI11 check and transform of --config: the value becomes resolve_config_name's path, or the
/// option fails (exit 2) naming the value and the bundled names.
CLI::Validator config_file_option();

/// A bundled configuration's one-line description: the first line of its leading comment block.
std::string config_description(const std::filesystem::path& file);

/// The bundled configurations, by name (file name without .yaml), each from the first directory of
/// config_dirs() that holds it; sorted by name.
std::vector<std::pair<std::string, std::filesystem::path>> bundled_configs();

}  // namespace flexgait::cli
