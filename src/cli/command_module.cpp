#include "command_module.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <stdexcept>

#include "flexgait/core/text.hpp"

namespace flexgait::cli {

void add_module_commands(CLI::App& app, std::function<int()>& action) {
  // RTLD_GLOBAL: the module's libraries join the program's scope as they did when the program
  // linked them. Never closed: its commands' callbacks and actions run after this returns.
  void* module = ::dlopen(FLEXGAIT_COMMAND_MODULE, RTLD_NOW | RTLD_GLOBAL);
  if (module == nullptr)
    throw std::runtime_error(fmt::format("cannot load the humanoid, campaign, reproduce and schema commands: {}",
                                         one_line(::dlerror(), 1000)));
  auto* add = reinterpret_cast<decltype(&flexgait_add_module_commands)>(::dlsym(module, "flexgait_add_module_commands"));
  if (add == nullptr)
    throw std::runtime_error(fmt::format("{} has no entry flexgait_add_module_commands", FLEXGAIT_COMMAND_MODULE));
  add(app, action);
}

}  // namespace flexgait::cli
