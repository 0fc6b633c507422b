#pragma once
/// \file config_file.hpp
/// A YAML configuration file read with limits (docs/guide/commands.md, "Reproduce, schema and bad input"): a regular
/// file of at most
/// kMaxConfigBytes, one document, a mapping nested at most kMaxConfigDepth deep whose keys are
/// plain names, each key once, aliases expanded to at most kMaxConfigNodes nodes and never into
/// themselves. Anything else is a ConfigError naming the file, the line and the problem.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "flexgait/core/config.hpp"

namespace flexgait {

inline constexpr std::size_t kMaxConfigBytes = 1 << 20;  ///< a configuration file's size limit [bytes]
inline constexpr int kMaxConfigDepth = 32;               ///< mappings nested deeper are refused
inline constexpr std::size_t kMaxConfigNodes = 10000;    ///< nodes visited, aliases expanded

/// One field of one item of a list value, as text: one scalar, or a list of scalars.
struct ItemFieldText {
  std::string name;
  std::vector<std::string> values;
  bool list = false;
};

/// Reads `text` (YAML, flow or block) as a list of mappings whose values are scalars or lists of
/// scalars, with the limits of a file (depth, aliases expanded to at most kMaxConfigNodes nodes).
/// Throws ConfigError("", problem): the problem only, for the caller to name key and origin.
std::vector<std::vector<ItemFieldText>> parse_list_text(std::string_view text);

/// The entries of YAML text `text` (named `name` in messages), in file order. An empty document
/// gives none. Throws ConfigError on a syntax error, more than one document, a top level that is
/// not a mapping, a key without a value, a key that is not a plain name (a mapping, a list,
/// null), a key given twice
/// (also as `a.b` and `a: {b: }`), a recursive alias, or a limit exceeded. A list value is one entry
/// whose text is the list as flow YAML, with `list` set (its key's type decides whether it is allowed).
std::vector<ConfigEntry> parse_config_yaml(std::string_view text, const std::string& name);

/// Reads and parses the configuration file `file`: refuses what is not a regular file (a directory,
/// a FIFO, a device) before opening it, and a file larger than kMaxConfigBytes.
std::vector<ConfigEntry> read_config_file(const std::filesystem::path& file);

}  // namespace flexgait
