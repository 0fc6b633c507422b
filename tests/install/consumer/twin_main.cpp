// A user's program on the installed twin, built without MuJoCo's headers or CMake package: the
// builtin robot stands for 0.2 s on its elastic gears and the feet carry it.
#include <flexgait/twin/plant.hpp>

#include <cstdio>

int main() {
  using namespace flexgait::humanoid;
  using namespace flexgait::twin;
  const RobotParams robot;
  HumanoidPlant plant(robot, PlantParams{});
  const JointVector pose = standing_pose(robot, 0.75);
  plant.reset(pose);
  for (int i = 0; i < 50; ++i) plant.step(pose);
  const GroundTruth t = plant.truth();
  std::printf("twin: pelvis at %.4f m, floor force %.1f N of weight %.1f N\n", t.pelvis_pos[2], t.normal_force,
              plant.total_mass() * plant.gravity());
  return t.pelvis_pos[2] > 0.6 && t.warnings == 0 ? 0 : 1;
}
