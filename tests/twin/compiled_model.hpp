#pragma once
// A MuJoCo model compiled from MJCF text with its data, for the twin's tests; set() poses the
// free-floating pelvis and flexgait's joints (by name) and runs mj_forward.
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <string>

#include "flexgait/robot/joints.hpp"
#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/walking/robot_model.hpp"

namespace flexgait::twin::testing {

using walking::Pose;

struct Compiled {
  mjModel* m;
  mjData* d;
  explicit Compiled(const std::string& xml) : m(load_mjcf(xml)), d(mj_makeData(m)) {}
  ~Compiled() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  int dof(int joint) const {
    return m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, std::string(humanoid::kJointNames[joint]).c_str())];
  }
  void set(const Pose& pelvis, const humanoid::JointVector& q) {
    mj_resetData(m, d);
    for (int i = 0; i < 3; ++i) d->qpos[i] = pelvis.p(i);
    const Eigen::Quaterniond quat(pelvis.R);
    d->qpos[3] = quat.w(), d->qpos[4] = quat.x(), d->qpos[5] = quat.y(), d->qpos[6] = quat.z();
    for (int j = 0; j < humanoid::kJoints; ++j) {
      const int id = mj_name2id(m, mjOBJ_JOINT, std::string(humanoid::kJointNames[j]).c_str());
      if (id >= 0) d->qpos[m->jnt_qposadr[id]] = q[j];  // (a robot without a waist has no waist_yaw)
    }
    mj_forward(m, d);
  }
};

}  // namespace flexgait::twin::testing
