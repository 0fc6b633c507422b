// The twin of a loaded robot (twin/twin_mjcf.hpp): the builtin robot loaded back from its own MJCF
// gives a twin that compiles to exactly the numbers of the builtin twin (bodies, joints, gears,
// geoms, contacts, sites).
#include "flexgait/twin/twin_mjcf.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "compiled_model.hpp"
#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/robot_loader.hpp"

namespace flexgait::twin {
namespace {

using testing::Compiled;

humanoid::LoadedRobot builtin_loaded() {
  return load_robot_text(humanoid_mjcf(humanoid::RobotParams{}, PlantParams{}), "xml", "builtin.xml",
                         humanoid::RobotDescriptionParams{});
}

// The twin made from the loaded builtin compiles to the builtin twin's numbers, bit for bit:
// the loader writes MuJoCo's compiled values at full precision (what makes a reloaded export walk
// as the builtin does).
TEST(TwinMjcf, TwinOfTheLoadedBuiltinCompilesToTheSameNumbers) {
  const PlantParams p;
  const Compiled a(humanoid_mjcf(humanoid::RobotParams{}, p));
  const Compiled b(twin_mjcf(builtin_loaded(), humanoid::RobotParams{}, p));
  ASSERT_EQ(a.m->nbody, b.m->nbody);
  ASSERT_EQ(a.m->njnt, b.m->njnt);
  ASSERT_EQ(a.m->ngeom, b.m->ngeom);
  ASSERT_EQ(a.m->nsensor, b.m->nsensor);
  auto same = [](const mjtNum* x, const mjtNum* y, int n, const char* what) {
    for (int i = 0; i < n; ++i) EXPECT_EQ(x[i], y[i]) << what << "[" << i << "]";
  };
  same(a.m->body_pos, b.m->body_pos, 3 * a.m->nbody, "body_pos");
  same(a.m->body_quat, b.m->body_quat, 4 * a.m->nbody, "body_quat");
  same(a.m->body_mass, b.m->body_mass, a.m->nbody, "body_mass");
  same(a.m->body_ipos, b.m->body_ipos, 3 * a.m->nbody, "body_ipos");
  same(a.m->body_iquat, b.m->body_iquat, 4 * a.m->nbody, "body_iquat");
  same(a.m->body_inertia, b.m->body_inertia, 3 * a.m->nbody, "body_inertia");
  same(a.m->jnt_pos, b.m->jnt_pos, 3 * a.m->njnt, "jnt_pos");
  same(a.m->jnt_axis, b.m->jnt_axis, 3 * a.m->njnt, "jnt_axis");
  same(a.m->jnt_stiffness, b.m->jnt_stiffness, a.m->njnt, "jnt_stiffness");
  same(a.m->dof_damping, b.m->dof_damping, a.m->nv, "dof_damping");
  same(a.m->dof_armature, b.m->dof_armature, a.m->nv, "dof_armature");
  same(a.m->geom_size, b.m->geom_size, 3 * a.m->ngeom, "geom_size");
  same(a.m->geom_pos, b.m->geom_pos, 3 * a.m->ngeom, "geom_pos");
  same(a.m->geom_quat, b.m->geom_quat, 4 * a.m->ngeom, "geom_quat");
  same(a.m->geom_friction, b.m->geom_friction, 3 * a.m->ngeom, "geom_friction");
  same(a.m->geom_solref, b.m->geom_solref, mjNREF * a.m->ngeom, "geom_solref");
  same(a.m->geom_solimp, b.m->geom_solimp, mjNIMP * a.m->ngeom, "geom_solimp");
  for (int g = 0; g < a.m->ngeom; ++g) {
    EXPECT_EQ(a.m->geom_contype[g], b.m->geom_contype[g]) << g;
    EXPECT_EQ(a.m->geom_conaffinity[g], b.m->geom_conaffinity[g]) << g;
    EXPECT_EQ(a.m->geom_type[g], b.m->geom_type[g]) << g;
  }
  same(a.m->site_pos, b.m->site_pos, 3 * a.m->nsite, "site_pos");
}

}  // namespace
}  // namespace flexgait::twin
