#include "configs_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>

#include "options.hpp"

namespace flexgait::cli {

void add_configs_command(CLI::App& app, std::function<int()>& action) {
  auto paths = std::make_shared<bool>(false);
  CLI::App* cmd =
      app.add_subcommand("configs",
                         "List the bundled configurations: each NAME, which --config NAME loads from any directory, "
                         "with its one-line description");
  cmd->add_flag("--paths", *paths, "also print the file each name loads");
  cmd->callback([paths, &action] {
    action = [paths] {
      const auto configs = bundled_configs();
      if (configs.empty()) {
        fmt::print(stderr, "error: no bundled configurations found (neither installed nor in the source tree)\n");
        return 1;
      }
      std::size_t width = 0;
      for (const auto& c : configs) width = std::max(width, c.first.size());
      for (const auto& [name, path] : configs) {
        fmt::print("{:<{}}  {}\n", name, width, config_description(path));
        if (*paths) fmt::print("{:<{}}  {}\n", "", width, path.string());
      }
      return 0;
    };
  });
}

}  // namespace flexgait::cli
