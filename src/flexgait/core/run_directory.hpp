#pragma once
/// \file run_directory.hpp
/// The output folder of one run: `config.yaml` (the resolved configuration), CSV logs and
/// `summary.json`, each written atomically, and the `complete` marker.
///
/// A run directory is complete when its command returned, whatever the run's outcome (a fall or
/// a failed solver is a result, written in full): the RunDirectory object then writes the empty
/// file `complete` as it goes out of scope. A run that was killed, crashed or stopped on an error
/// leaves no `complete`, so a reader (a script, `--resume`) can tell it from a finished one.
#include <filesystem>
#include <string>
#include <string_view>

#include "flexgait/core/config.hpp"

namespace flexgait {

class RunDirectory {
 public:
  /// The marker's file name.
  static constexpr const char* kCompleteMarker = "complete";

  /// Creates `path` (and its parents). Throws UsageError naming --out if that fails, if `path`
  /// exists and is not a directory, or if it holds an entry that is neither a regular file nor a
  /// directory (check_output_directory: a FIFO or a device where a run file would be renamed).
  /// Commands make it after every check and before computing.
  /// An existing directory loses its `complete` marker (it is being written again) and the
  /// temporary files that killed writers left in it (remove_orphaned_temporaries).
  explicit RunDirectory(std::filesystem::path path);
  /// Writes `complete` unless an exception is unwinding through the scope that made this object.
  ~RunDirectory();
  RunDirectory(RunDirectory&& other) noexcept;
  RunDirectory(const RunDirectory&) = delete;
  RunDirectory& operator=(const RunDirectory&) = delete;
  RunDirectory& operator=(RunDirectory&&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// Writes `name` inside the run directory atomically.
  void write(const std::string& name, std::string_view content) const;
  /// Writes `config.yaml` with the resolved configuration.
  void write_config(const Config& config) const;

 private:
  std::filesystem::path path_;
  int uncaught_at_start_ = 0;  ///< std::uncaught_exceptions() when made
  bool owner_ = true;          ///< false once moved from
};

/// Makes `path` and its parents for a command's output. Throws UsageError naming `option` if
/// check_output_directory refuses it or if it cannot be made (a regular file in the way, no
/// permission): a directory the user named that cannot hold the output is bad usage (exit 2).
void make_output_directory(const std::filesystem::path& path, const std::string& option = "--out");

/// True if `path` holds the `complete` marker of a finished run.
bool run_directory_complete(const std::filesystem::path& path);

}  // namespace flexgait
