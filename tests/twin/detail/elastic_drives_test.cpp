// The elastic drives on MuJoCo hinges (twin/detail/elastic_drives.hpp), on a one-hinge pendulum:
// the joint's own stiffness is taken away, the motors start at rest at the link angles, a step
// puts k dz(θ_m − θ_l) + d θ̇_m (with the motor's new state) into qfrc_applied, an absent joint
// reads 0 and acts on nothing, and a joint that is not a hinge is refused.
#include "flexgait/twin/detail/elastic_drives.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <stdexcept>

#include "flexgait/twin/detail/mujoco.hpp"

namespace flexgait::twin {
namespace {

constexpr const char* kPendulum = R"(<mujoco>
  <option timestep="0.001"/>
  <worldbody>
    <body name="arm" pos="0 0 1">
      <joint name="hinge" type="hinge" axis="0 1 0" stiffness="500" damping="20"/>
      <geom type="sphere" pos="0.3 0 0" size="0.03" mass="2"/>
    </body>
    <body name="slider" pos="1 0 1">
      <joint name="slide" type="slide" axis="1 0 0"/>
      <geom type="sphere" size="0.03" mass="1"/>
    </body>
  </worldbody>
</mujoco>)";

TEST(ElasticDrives, StepAppliesTheGearSpringAndTheMotorSideDamping) {
  mjModel* m = load_mjcf(kPendulum);
  ActuatorParams p;
  p.k = 500;
  p.d = 20;
  p.backlash = 0.002;
  const ElasticDrives drives(m, {0, ElasticDrives::kAbsentJoint}, {p, p});
  drives.take_springs(m);
  EXPECT_EQ(m->jnt_stiffness[0], 0.0);
  mjData* d = mj_makeData(m);
  d->qpos[0] = 0.2;
  d->qvel[0] = -0.5;
  mj_forward(m, d);
  std::vector<ActuatorState> states = drives.at_rest(d);
  ASSERT_EQ(states.size(), 2u);
  EXPECT_EQ(states[0].theta_m, 0.2);
  EXPECT_EQ(states[0].omega_m, -0.5);
  EXPECT_EQ(states[1].theta_m, 0.0);  // absent
  for (int k = 0; k < 50; ++k) {
    const double theta_l = d->qpos[0], omega_l = d->qvel[0];
    ActuatorState expected = states[0];
    step_motor(p, expected, 0.3, theta_l, omega_l, m->opt.timestep);
    const double commands[2] = {0.3, 0.7};
    drives.step(m, d, states, commands);
    EXPECT_EQ(states[0].theta_m, expected.theta_m) << k;
    EXPECT_EQ(d->qfrc_applied[drives.dof_index()[0]],
              p.k * gear_deflection(p, expected.theta_m, theta_l) + p.d * expected.omega_m)
        << k;
    EXPECT_EQ(d->qfrc_applied[1], 0.0);  // the slide carries no drive
    EXPECT_EQ(states[1].theta_m, 0.0);
  }
  EXPECT_EQ(mujoco_warning_count(d), 0);
  mj_deleteData(d);
  EXPECT_THROW(ElasticDrives(m, {1}, {p}), std::invalid_argument);     // a slide joint
  EXPECT_THROW(ElasticDrives(m, {0}, {p, p}), std::invalid_argument);  // one parameter set per joint
  mj_deleteModel(m);
}

}  // namespace
}  // namespace flexgait::twin
