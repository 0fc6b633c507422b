// The commands' module's one entry (command_module.hpp).
#include "campaign_command.hpp"
#include "command_module.hpp"
#include "flexgait/twin/mujoco_messages.hpp"
#include "humanoid_commands.hpp"
#include "render_command.hpp"
#include "reproduce_command.hpp"
#include "schema_command.hpp"

extern "C" void flexgait_add_module_commands(CLI::App& app, std::function<int()>& action) {
  flexgait::twin::route_mujoco_messages_to_stderr();  // no MUJOCO_LOG.TXT, nothing on stdout
  // In the order `flexgait --help` lists them, after `rimless`.
  flexgait::cli::add_humanoid_commands(app, action);
  flexgait::cli::add_render_command(app, action);
  flexgait::cli::add_campaign_command(app, action);
  flexgait::cli::add_reproduce_command(app, action);
  flexgait::cli::add_schema_command(app, action);
}
