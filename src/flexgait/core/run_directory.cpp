#include "flexgait/core/run_directory.hpp"

#include <system_error>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/version.hpp"

namespace flexgait {

RunDirectory::RunDirectory(std::filesystem::path path) : path_(std::move(path)) {
  std::filesystem::create_directories(path_);
  if (!std::filesystem::is_directory(path_))
    throw std::system_error(std::make_error_code(std::errc::not_a_directory), path_.string());
}

void RunDirectory::write(const std::string& name, std::string_view content) const {
  write_file_atomic(path_ / name, content);
}

void RunDirectory::write_config(const Config& config) const {
  write("config.yaml", std::string("# resolved configuration, flexgait ") + kVersion + "\n" + config.to_yaml());
}

}  // namespace flexgait
