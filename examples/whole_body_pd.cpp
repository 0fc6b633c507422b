// Your own controller on the elastic twin, in C++ (docs/guide/loop.md).
//
// A whole-body controller that stands, then shifts its weight over the left foot: the pelvis moves
// sideways by tilting both legs about the ankles' roll axes (hip roll and ankle roll turn
// together), with a PD on the IMU's roll and pitch righting the pelvis through the ankles. It
// subclasses loop::Controller and runs in loop::HumanoidLoop with the deformation compensators on
// its command (control.compensation = both, the gears' sag taken out), as configured.
//
// Usage: whole_body_pd [SECONDS]   (default 4: 1 s standing, 2 s shifting, 1 s holding)
// Prints the load on each foot [N] and the pelvis's tilt once a second; exits 1 if the robot did
// not end standing with most of its weight on the left foot.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/loop/closed_loop.hpp"

namespace {

using flexgait::humanoid::JointVector;
using flexgait::humanoid::SensorReadings;

class WeightShift final : public flexgait::loop::Controller {
 public:
  WeightShift(const JointVector& pose, double lean) : pose_(pose), lean_(lean) {}

  JointVector update(const SensorReadings& s, double t) override {
    namespace h = flexgait::humanoid;
    // The lean [rad] rises smoothly from 0 at t = 1 s to lean_ at t = 3 s.
    const double u = std::clamp((t - 1.0) / 2.0, 0.0, 1.0);
    const double lean = lean_ * (3 * u * u - 2 * u * u * u);
    const auto& q = s.imu.quat;  // (w, x, y, z)
    const double roll = std::atan2(2 * (q[0] * q[1] + q[2] * q[3]), 1 - 2 * (q[1] * q[1] + q[2] * q[2]));
    const double pitch = std::asin(std::clamp(2 * (q[0] * q[2] - q[3] * q[1]), -1.0, 1.0));
    JointVector command = pose_;
    for (int side = 0; side < 2; ++side) {
      const int hip_roll = h::leg_first_joint(side) + 1, ankle_pitch = h::leg_first_joint(side) + 4,
                ankle_roll = h::leg_first_joint(side) + 5;
      // A parallelogram: hip and ankle roll turn together, the pelvis stays level and moves left.
      command[hip_roll] += lean;
      command[ankle_roll] += lean;
      // The feet are flat on the floor: turning an ankle by +δ turns its leg, and the pelvis, by −δ
      // about the foot, so the ankles turn with the pelvis's tilt to undo it.
      command[ankle_roll] += kp_ * roll + kd_ * s.imu.gyro[0];
      command[ankle_pitch] += kp_ * pitch + kd_ * s.imu.gyro[1];
    }
    return command;
  }

 private:
  JointVector pose_;
  double lean_;
  double kp_ = 0.5, kd_ = 0.05;  // [rad/rad], [rad s/rad]
};

}  // namespace

int main(int argc, char** argv) {
  namespace fg = flexgait;
  const double seconds = argc > 1 ? std::atof(argv[1]) : 4.0;
  if (!(seconds > 0 && seconds <= 60)) {
    std::fprintf(stderr, "usage: whole_body_pd [SECONDS]  (0 < SECONDS <= 60)\n");
    return 2;
  }
  fg::experiments::WalkRunParams params;  // the builtin robot, the defaults of `flexgait humanoid walk`
  const fg::walking::RobotModel model = fg::experiments::walk_controller_model(params);
  const fg::loop::LoopSetup setup =
      fg::experiments::walk_loop_setup(params, model, fg::walking::plan_footsteps(params.walk));
  const JointVector pose = fg::twin::standing_pose(params.robot, params.walk.pelvis_height);
  // Lean the legs by an angle that puts the pelvis over the left sole: half the step width.
  const double lean = std::atan2(0.5 * params.walk.step_width, params.walk.pelvis_height);
  fg::loop::HumanoidLoop loop(setup, std::make_shared<WeightShift>(pose, lean));
  loop.reset(pose);

  const long periods = std::lround(seconds / params.plant.control_period);
  for (long k = 1; k <= periods; ++k) {
    if (const auto failure = loop.step()) {
      std::fprintf(stderr, "the simulation failed at t = %.3f s: %s\n", loop.time(),
                   std::string(fg::name_of(*failure)).c_str());
      return 1;
    }
    if (k % std::lround(1.0 / params.plant.control_period) == 0) {
      const auto& s = loop.sensors();
      std::printf("t = %4.1f s  load left %6.1f N  right %6.1f N  pelvis z %.3f m\n", loop.time(), -s.ft[0].force[2],
                  -s.ft[1].force[2], loop.truth().pelvis_pos[2]);
    }
  }
  const auto& g = loop.truth();
  const auto& s = loop.sensors();
  const double left = -s.ft[0].force[2], right = -s.ft[1].force[2];
  const bool standing = !g.non_sole_contact && g.pelvis_pos[2] > params.walk.pelvis_height - 0.1;
  const bool shifted = seconds < 3 || left > 2.0 * right;
  std::printf("%s: left foot carries %.0f %% of the load\n", standing && shifted ? "stood and shifted" : "FAILED",
              100.0 * left / (left + right));
  return standing && shifted ? 0 : 1;
}
