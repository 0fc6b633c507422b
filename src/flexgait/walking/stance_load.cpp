#include "flexgait/walking/stance_load.hpp"

namespace flexgait::walking {

LegTorque stance_joint_torques(const RobotModel& model, const RobotModelData& data, int side, const Vector3d& force,
                               const Vector3d& point) {
  return leg_jacobian(model, data, side, point).topRows<3>().transpose() * force;  // (L1)
}

}  // namespace flexgait::walking
