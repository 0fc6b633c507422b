// The builtin robot exported as URDF and loaded back through robot.description: the
// same kinematics and masses to the precision URDF stores (shortest round-trip decimals: exact
// here, the builtin's frames are all parallel).
#include "flexgait/robot/urdf_export.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/robot_loader.hpp"
#include "flexgait/walking/robot_model.hpp"

namespace flexgait::humanoid {
namespace {

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

TEST(UrdfExport, ExportedUrdfHasTheSameKinematicsAndMasses) {
  const LoadedRobot original = twin::load_robot_text(twin::humanoid_mjcf(RobotParams{}, twin::PlantParams{}), "xml",
                                                     "builtin", RobotDescriptionParams{});
  const LoadedRobot urdf =
      twin::load_robot_text(robot_urdf(original), "urdf", "exported.urdf", mapping_from(urdf_mapping(original)));
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
