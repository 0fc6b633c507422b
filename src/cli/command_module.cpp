#include "command_module.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "flexgait/core/text.hpp"

namespace flexgait::cli {

namespace {

/// The module beside the executable (the build tree) or in the install's library directory, by
/// path; else its bare name, for the run path. A path, because under AddressSanitizer dlopen is
/// intercepted and the run path searched is libasan's (none), not the executable's.
std::string module_path() {
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error)
    for (const char* dir : {".", FLEXGAIT_MODULE_INSTALL_DIR}) {
      const std::filesystem::path candidate = exe.parent_path() / dir / FLEXGAIT_COMMAND_MODULE;
      if (std::filesystem::is_regular_file(candidate, error)) return candidate.lexically_normal().string();
    }
  return FLEXGAIT_COMMAND_MODULE;
}

}  // namespace

void add_module_commands(CLI::App& app, std::function<int()>& action) {
  // RTLD_GLOBAL: the module's libraries join the program's scope as they did when the program
  // linked them. Never closed: its commands' callbacks and actions run after this returns.
  void* module = ::dlopen(module_path().c_str(), RTLD_NOW | RTLD_GLOBAL);
  if (module == nullptr)
    throw std::runtime_error(fmt::format("cannot load the humanoid, campaign, reproduce and schema commands: {}",
                                         one_line(::dlerror(), 1000)));
  auto* add =
      reinterpret_cast<decltype(&flexgait_add_module_commands)>(::dlsym(module, "flexgait_add_module_commands"));
  if (add == nullptr)
    throw std::runtime_error(fmt::format("{} has no entry flexgait_add_module_commands", FLEXGAIT_COMMAND_MODULE));
  add(app, action);
}

}  // namespace flexgait::cli
