#pragma once
/// \file run_directory.hpp
/// The output folder of one run: `config.yaml` (the resolved configuration), CSV logs and
/// `summary.json`, each written atomically.
#include <filesystem>
#include <string_view>

#include "flexgait/core/config.hpp"

namespace flexgait {

class RunDirectory {
 public:
  /// Creates `path` (and its parents). Throws UsageError naming --out if that fails or if `path`
  /// exists and is not a directory. Commands make it after every check and before computing.
  explicit RunDirectory(std::filesystem::path path);
  const std::filesystem::path& path() const { return path_; }
  /// Writes `name` inside the run directory atomically.
  void write(const std::string& name, std::string_view content) const;
  /// Writes `config.yaml` with the resolved configuration.
  void write_config(const Config& config) const;

 private:
  std::filesystem::path path_;
};

}  // namespace flexgait
