#pragma once
// Fresh, empty directories under the system's temporary directory for the core tests' files,
// one per test and process (flexgait_atomic_<pid>_<name>).
#include <unistd.h>

#include <filesystem>
#include <string>

namespace flexgait::testing {

inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("flexgait_atomic_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace flexgait::testing
