// The builtin robot exported and loaded back through robot.description (issue 16): as MJCF it
// walks with the same summary, to the last bit; as URDF it has the same kinematics and masses to
// the precision URDF stores (shortest round-trip decimals: exact here, the builtin's frames are
// all parallel).
#include <gtest/gtest.h>

#include <memory>

#include "flexgait/core/record_json.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/robot_loader.hpp"
#include "flexgait/robot/urdf_export.hpp"

namespace flexgait::humanoid {
namespace {

experiments::WalkRunParams one_second_steps() {
  experiments::WalkRunParams p;
  p.walk.step_time = 1.0;  // walk-robotis.yaml's gait, 6 steps
  p.walk.steps = 6;
  return p;
}

TEST(RobotRoundTrip, ExportedMjcfWalksWithTheSameSummary) {
  const experiments::WalkRunParams builtin = one_second_steps();
  experiments::WalkRunParams loaded = builtin;
  loaded.description.description = "exported.xml";
  loaded.loaded = std::make_shared<const LoadedRobot>(
      load_robot_text(humanoid_mjcf(builtin.robot, builtin.plant), "xml", "exported.xml", loaded.description));
  const auto a = experiments::run_walk(builtin);
  const auto b = experiments::run_walk(loaded);
  EXPECT_TRUE(a.metrics.completed());
  EXPECT_EQ(record_json(a.metrics).dump(), record_json(b.metrics).dump());
}

// Lines "KEY=VALUE" of urdf_mapping into the mapping record.
RobotDescriptionParams mapping_from(const std::string& lines) {
  RobotDescriptionParams p;
  const Schema schema = schema_of<RobotDescriptionParams>();
  std::vector<std::string> overrides;
  std::size_t start = 0;
  for (std::size_t end; (end = lines.find('\n', start)) != std::string::npos; start = end + 1)
    overrides.push_back(lines.substr(start, end - start));
  return record_from_config<RobotDescriptionParams>(resolve_config(schema, std::nullopt, overrides));
}

TEST(RobotRoundTrip, ExportedUrdfHasTheSameKinematicsAndMasses) {
  const LoadedRobot original =
      load_robot_text(humanoid_mjcf(RobotParams{}, PlantParams{}), "xml", "builtin", RobotDescriptionParams{});
  const LoadedRobot urdf = load_robot_text(robot_urdf(original), "urdf", "exported.urdf", mapping_from(urdf_mapping(original)));
  const walking::RobotModel a = walking::make_robot_model(original);
  const walking::RobotModel b = walking::make_robot_model(urdf);
  // Inertias pass through MuJoCo's eigen-decomposition of URDF's full tensor: 1e-12 kg m².
  EXPECT_NEAR(a.total_mass, b.total_mass, 1e-12);
  for (int k = 0; k < walking::kBodies; ++k) {
    const auto& x = a.bodies[static_cast<std::size_t>(k)];
    const auto& y = b.bodies[static_cast<std::size_t>(k)];
    EXPECT_LT((x.axis - y.axis).norm(), 1e-12) << k;
    EXPECT_LT((x.offset - y.offset).norm(), 1e-12) << k;
    EXPECT_NEAR(x.mass, y.mass, 1e-12) << k;
    EXPECT_LT((x.com - y.com).norm(), 1e-12) << k;
    EXPECT_LT((x.inertia - y.inertia).cwiseAbs().maxCoeff(), 1e-12) << k;
  }
  for (int side = 0; side < 2; ++side) {
    EXPECT_LT((a.leg[side].hip - b.leg[side].hip).norm(), 1e-12);
    EXPECT_NEAR(a.leg[side].ankle_to_sole, b.leg[side].ankle_to_sole, 1e-12);
    EXPECT_LT((a.sole_offset[side] - b.sole_offset[side]).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace flexgait::humanoid
