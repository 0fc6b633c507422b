// The robot of a walk configuration as MJCF or URDF, and the configuration that loads it back
// (experiments/robot_export.hpp): the MJCF is the twin the walk simulates, the reload
// configuration names the file and keeps every other key, a bad format is refused by name.
#include "flexgait/experiments/robot_export.hpp"

#include <gtest/gtest.h>

#include <string>

#include "flexgait/experiments/walk_experiment.hpp"

namespace flexgait::experiments {
namespace {

Config walk_config() {
  return resolve_config(walk_run_schema(), std::nullopt, {}, {{"walk.steps", "3", "test"}});
}

TEST(RobotExport, TheMjcfIsTheTwinTheWalkSimulates) {
  const Config c = walk_config();
  const RobotExport e = export_robot(c, "mjcf", "twin.xml");
  EXPECT_EQ(e.text, walk_twin(walk_run_from_config(c)).mjcf);
  EXPECT_EQ(e.reload.text("robot.description"), "twin.xml");
  EXPECT_EQ(e.reload.integer("walk.steps"), 3);  // the run's other keys kept
}

TEST(RobotExport, TheUrdfIsARobotDocumentNamedInItsReloadConfiguration) {
  const RobotExport e = export_robot(walk_config(), "urdf", "robot.urdf");
  EXPECT_NE(e.text.find("<robot"), std::string::npos);
  EXPECT_EQ(e.reload.text("robot.description"), "robot.urdf");
}

TEST(RobotExport, AnUnknownFormatIsRefusedByName) {
  try {
    export_robot(walk_config(), "sdf", "robot.sdf");
    FAIL() << "sdf accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("'sdf' is not one of mjcf, urdf"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace flexgait::experiments
