// The builtin robot exported as URDF and loaded back through robot.description: the
// same kinematics and masses to the precision URDF stores (shortest round-trip decimals: exact
// here, the builtin's frames are all parallel).
#include "flexgait/robot/urdf_export.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>
#include <random>
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

// URDF's rpy reproduces the rotation, R = Rz(yaw) Ry(pitch) Rx(roll), for random rotations and at
// gimbal lock (|pitch| = π/2, where the classic roll = atan2(R21, R22) reads the sign of rounding):
// the Berkeley Humanoid's foot frame (w x y z = ½(1, −1, −1, −1), a third of a turn about
// −(1, 1, 1)), a quarter turn about y after any yaw and roll, and a pitch 1e-9 rad short of it.
// Bound: a few products and three trigonometric functions of unit-size numbers, 1e-15.
TEST(UrdfExport, RpyReproducesTheRotationAlsoAtGimbalLock) {
  auto rebuilt = [](const std::array<double, 3>& a) {
    return (Eigen::AngleAxisd(a[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(a[1], Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(a[0], Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
  };
  std::vector<Eigen::Matrix3d> rotations{Eigen::Quaterniond(0.5, -0.5, -0.5, -0.5).toRotationMatrix()};
  const double quarter = std::numbers::pi / 2;
  for (double pitch : {quarter, -quarter, quarter - 1e-9})
    for (double roll_yaw : {0.0, 0.3, -2.5}) rotations.push_back(rebuilt({roll_yaw, pitch, 1.0 - roll_yaw}));
  std::mt19937 rng(7);
  std::normal_distribution<double> n;
  for (int k = 0; k < 200; ++k)
    rotations.push_back(Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix());
  for (std::size_t k = 0; k < rotations.size(); ++k) {
    const std::array<double, 3> a = urdf_rpy(rotations[k]);
    EXPECT_LT((rebuilt(a) - rotations[k]).cwiseAbs().maxCoeff(), 1e-15) << k;
    EXPECT_LE(std::abs(a[1]), quarter) << k;
  }
}

}  // namespace
}  // namespace flexgait::humanoid
