#include "flexgait/core/run_directory.hpp"

#include <fmt/format.h>

#include <system_error>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/version.hpp"

namespace flexgait {

RunDirectory::RunDirectory(std::filesystem::path path) : path_(std::move(path)) {
  std::error_code ec;
  std::filesystem::create_directories(path_, ec);
  if (!ec && !std::filesystem::is_directory(path_)) ec = std::make_error_code(std::errc::not_a_directory);
  if (ec)
    throw UsageError(fmt::format("--out: cannot make the run directory {}: {}", one_line(path_.string(), 1000), ec.message()));
}

void RunDirectory::write(const std::string& name, std::string_view content) const {
  write_file_atomic(path_ / name, content);
}

void RunDirectory::write_config(const Config& config) const {
  write("config.yaml", std::string("# resolved configuration, flexgait ") + kVersion + "\n" + config.to_yaml());
}

}  // namespace flexgait
