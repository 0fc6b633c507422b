#include "flexgait/core/run_directory.hpp"

#include <fmt/format.h>

#include <exception>
#include <system_error>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/version.hpp"

namespace flexgait {

void make_output_directory(const std::filesystem::path& path, const std::string& option) {
  check_output_directory(path, option);
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (!ec && !std::filesystem::is_directory(path)) ec = std::make_error_code(std::errc::not_a_directory);
  if (ec)
    throw UsageError(
        fmt::format("{}: cannot make the run directory {}: {}", option, one_line(path.string(), 1000), ec.message()));
}

RunDirectory::RunDirectory(std::filesystem::path path)
    : path_(std::move(path)), uncaught_at_start_(std::uncaught_exceptions()) {
  make_output_directory(path_);
  std::error_code ec;
  std::filesystem::remove(path_ / kCompleteMarker, ec);
  remove_orphaned_temporaries(path_);
}

RunDirectory::RunDirectory(RunDirectory&& other) noexcept
    : path_(other.path_), uncaught_at_start_(other.uncaught_at_start_), owner_(other.owner_) {
  other.owner_ = false;
}

RunDirectory::~RunDirectory() {
  if (!owner_ || std::uncaught_exceptions() > uncaught_at_start_) return;
  try {
    write_file_atomic(path_ / kCompleteMarker, "");
  } catch (const std::exception& e) {  // a destructor must not throw; the run's files are written
    fmt::print(stderr, "warning: cannot mark {} complete: {}\n", one_line(path_.string(), 1000),
               one_line(e.what(), 1000));
  }
}

void RunDirectory::write(const std::string& name, std::string_view content) const {
  write_file_atomic(path_ / name, content);
}

void RunDirectory::write_config(const Config& config) const {
  write("config.yaml", std::string("# resolved configuration, flexgait ") + kVersion + "\n" + config.to_yaml());
}

bool run_directory_complete(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path / RunDirectory::kCompleteMarker, ec);
}

}  // namespace flexgait
