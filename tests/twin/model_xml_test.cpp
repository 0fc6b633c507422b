// The builtin twin as MJCF (twin/model_xml.hpp): compiled, its bodies carry the builtin inertials
// (THORMANG3's table plus the extra mass, robot/builtin_inertials.hpp) and its joints the gears'
// stiffness and damping; loaded back through robot.description it walks with the same
// summary, to the last bit.
#include "flexgait/twin/model_xml.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <memory>
#include <string>

#include "compiled_model.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/robot/builtin_inertials.hpp"
#include "flexgait/twin/robot_loader.hpp"

namespace flexgait::twin {
namespace {

using testing::Compiled;

TEST(ModelXml, CompiledTwinHasTheBuiltinMassesAndGears) {
  humanoid::RobotParams robot;
  robot.total_mass = 61.5;
  PlantParams plant;
  plant.k_joint = 1500.0;
  plant.k_scale[3] = 2.0;
  const Compiled twin(humanoid_mjcf(robot, plant));
  // Sums of a few dozen masses: 1e-12 kg.
  EXPECT_NEAR(twin.m->body_subtreemass[0], robot.total_mass, 1e-12);
  const humanoid::BuiltinInertials b = humanoid::builtin_inertials(robot);
  const int pelvis = mj_name2id(twin.m, mjOBJ_BODY, "pelvis");
  ASSERT_GE(pelvis, 0);
  EXPECT_NEAR(twin.m->body_mass[pelvis], b.pelvis.mass, 1e-12);
  for (int j = 0; j < humanoid::kJoints; ++j) {
    const int id =
        mj_name2id(twin.m, mjOBJ_JOINT, std::string(humanoid::kJointNames[static_cast<std::size_t>(j)]).c_str());
    ASSERT_GE(id, 0) << humanoid::kJointNames[static_cast<std::size_t>(j)];
    // Written as shortest round-trip decimals: exact.
    EXPECT_EQ(twin.m->jnt_stiffness[id], plant.k_joint * plant.k_scale[static_cast<std::size_t>(j)]) << j;
    EXPECT_EQ(twin.m->dof_damping[twin.m->jnt_dofadr[id]], plant.gear_damping) << j;
  }
  for (const char* site : {"imu", "l_ft", "r_ft"}) EXPECT_GE(mj_name2id(twin.m, mjOBJ_SITE, site), 0) << site;
}

experiments::WalkRunParams one_second_steps() {
  experiments::WalkRunParams p;
  p.walk.step_time = 1.0;  // walk-robotis.yaml's gait, 6 steps
  p.walk.steps = 6;
  return p;
}

TEST(ModelXml, ExportedMjcfWalksWithTheSameSummary) {
  const experiments::WalkRunParams builtin = one_second_steps();
  experiments::WalkRunParams loaded = builtin;
  loaded.description.description = "exported.xml";
  loaded.loaded = std::make_shared<const humanoid::LoadedRobot>(
      load_robot_text(humanoid_mjcf(builtin.robot, builtin.plant), "xml", "exported.xml", loaded.description));
  const auto a = experiments::run_walk(builtin);
  const auto b = experiments::run_walk(loaded);
  EXPECT_TRUE(a.metrics.completed());
  EXPECT_EQ(record_json(a.metrics).dump(), record_json(b.metrics).dump());
}

}  // namespace
}  // namespace flexgait::twin
