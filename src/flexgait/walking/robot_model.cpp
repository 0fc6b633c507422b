#include "flexgait/walking/robot_model.hpp"

#include <algorithm>
#include <cmath>

#include "flexgait/robot/builtin_inertials.hpp"

namespace flexgait::walking {

using humanoid::leg_first_joint;

namespace {

void set_inertial(RobotModel::Body& b, const humanoid::BodyInertial& in) {
  b.mass = in.mass;
  b.com = Vector3d(in.com[0], in.com[1], in.com[2]);
  const auto& i = in.inertia;
  b.inertia << i[0], i[1], i[2], i[1], i[3], i[4], i[2], i[4], i[5];
}

}  // namespace

RobotModel make_robot_model(const humanoid::RobotParams& r) {
  RobotModel m;
  // THORMANG3's inertials (the twin's, builtin_inertials.hpp): chest, arms and head rigid together.
  const humanoid::BuiltinInertials in = humanoid::builtin_inertials(r);
  set_inertial(m.bodies[0], in.pelvis);
  auto& chest = m.bodies[1];
  chest.parent = 0;
  chest.joint = humanoid::kWaistYaw;
  chest.axis = Vector3d::UnitZ();
  chest.offset = Vector3d(0, 0, r.chest_joint_z);
  set_inertial(chest, in.chest);
  for (int side = 0; side < 2; ++side) {
    const int b0 = 2 + 7 * side, j0 = leg_first_joint(side);
    const double y = side == 0 ? r.hip_yaw_offset_y : -r.hip_yaw_offset_y;
    const std::array<Vector3d, 7> axes = {Vector3d::UnitZ(), Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitY(),
                                          Vector3d::UnitY(), Vector3d::UnitX(), Vector3d::Zero()};
    const std::array<Vector3d, 7> offsets = {Vector3d(0, y, -r.hip_yaw_offset_z),
                                             Vector3d(0, 0, -(r.hip_axes_depth - r.hip_yaw_offset_z)),
                                             Vector3d::Zero(),
                                             Vector3d(0, 0, -r.thigh),
                                             Vector3d(0, 0, -r.shank),
                                             Vector3d::Zero(),
                                             Vector3d::Zero()};
    for (int i = 0; i < 7; ++i) {
      auto& b = m.bodies[b0 + i];
      b.parent = i == 0 ? 0 : b0 + i - 1;
      b.joint = i < 6 ? j0 + i : -1;
      b.axis = axes[i];
      b.offset = offsets[i];
      set_inertial(b, in.leg[side][i]);
    }
    m.foot[side] = b0 + 6;
    m.leg[side] = leg_geometry(r, side);
  }
  for (const auto& b : m.bodies) m.total_mass += b.mass;
  m.sole_length = r.sole_length;
  m.sole_width = r.sole_width;
  m.sole_polygon = {rectangle_sole(r.sole_length, r.sole_width), rectangle_sole(r.sole_length, r.sole_width)};
  m.sole_offset = {Vector3d(0, r.sole_offset_y, -r.ankle_to_sole), Vector3d(0, -r.sole_offset_y, -r.ankle_to_sole)};
  m.ft_to_sole = m.sole_offset;
  fill_leg_chain(m, 0);
  fill_leg_chain(m, 1);
  index_joint_axes(m);
  return m;
}

int outside_ranges(const RobotModel& model, const humanoid::JointVector& q) {
  humanoid::JointVector clamped = q;
  return clamp_to_ranges(model, clamped);
}

int clamp_to_ranges(const RobotModel& model, humanoid::JointVector& q) {
  int hits = 0;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    const auto& r = model.range[static_cast<std::size_t>(j)];
    if (q[j] < r[0] || q[j] > r[1]) {
      q[j] = std::clamp(q[j], r[0], r[1]);
      ++hits;
    }
  }
  return hits;
}

void index_joint_axes(RobotModel& model) {
  for (auto& b : model.bodies) {
    b.axis_index = -1;
    for (int k = 0; k < 3; ++k)
      if (b.axis(k) == 1.0 && b.axis((k + 1) % 3) == 0.0 && b.axis((k + 2) % 3) == 0.0) b.axis_index = k;
  }
}

void fill_leg_chain(RobotModel& m, int side) {
  const int b0 = 2 + 7 * side;
  LegGeometry& leg = m.leg[static_cast<std::size_t>(side)];
  for (int i = 0; i < 6; ++i) {
    leg.role[static_cast<std::size_t>(i)] = m.bodies[static_cast<std::size_t>(b0 + i)].joint - leg_first_joint(side);
    leg.axis[static_cast<std::size_t>(i)] = m.bodies[static_cast<std::size_t>(b0 + i)].axis;
    leg.anchor[static_cast<std::size_t>(i)] = m.bodies[static_cast<std::size_t>(b0 + i)].offset;
  }
  leg.sole = m.bodies[static_cast<std::size_t>(b0 + 6)].offset + m.sole_offset[static_cast<std::size_t>(side)];
  leg.sole_R = m.sole_rotation[static_cast<std::size_t>(side)];
  leg.sole_tilted = m.sole_tilted[static_cast<std::size_t>(side)];
}

namespace {

/// P · Rot(e_k, θ): only the two columns of the plane turn, each entry a sum of at most two nonzero products, so
/// it equals the general 3 × 3 product with the rotation's entries formed as Eigen::AngleAxisd::toRotationMatrix
/// forms them (c + (1 − c) on the axis, 0 ± s off it; the structural zeros add nothing) in every bit but a zero's
/// sign.
Matrix3d turned_about(const Matrix3d& P, int k, double angle) {
  const double s = std::sin(angle), c = std::cos(angle);
  const int i = (k + 1) % 3, j = (k + 2) % 3;  // the plane's axes: R_ii = R_jj = c, R_ji = 0 + s, R_ij = 0 − s
  const double plus = 0.0 + s, minus = 0.0 - s;
  Matrix3d out;
  out.col(k) = P.col(k) * ((1.0 - c) + c);
  out.col(i) = P.col(i) * c + P.col(j) * plus;
  out.col(j) = P.col(i) * minus + P.col(j) * c;
  return out;
}

}  // namespace

void forward_kinematics(const RobotModel& model, RobotModelData& data, const Pose& pelvis,
                        const humanoid::JointVector& q, int first) {
  for (int i = first; i < kBodies; ++i) {
    const auto& b = model.bodies[i];
    Pose& f = data.frame[i];
    if (b.parent < 0) {
      f = pelvis;
    } else {
      const Pose& parent = data.frame[b.parent];
      f.p = parent.p + parent.R * b.offset;
      if (b.joint < 0) {
        f.R = parent.R;
      } else if (b.axis_index >= 0) {
        f.R = turned_about(parent.R, b.axis_index, q[b.joint]);
        data.axis[i] = f.R.col(b.axis_index);
      } else {
        f.R = parent.R * Eigen::AngleAxisd(q[b.joint], b.axis);
        data.axis[i] = f.R * b.axis;
      }
    }
    if (b.joint < 0) data.axis[i].setZero();
    data.com_world[i] = f.p + f.R * b.com;
  }
}

Vector3d center_of_mass(const RobotModel& model, const RobotModelData& data) {
  Vector3d c = Vector3d::Zero();
  for (int i = 0; i < kBodies; ++i) c += model.bodies[i].mass * data.com_world[i];
  return c / model.total_mass;
}

Pose sole_pose(const RobotModel& model, const RobotModelData& data, int side) {
  const Pose& foot = data.frame[model.foot[side]];
  if (model.sole_tilted[side]) return {foot.p + foot.R * model.sole_offset[side], foot.R * model.sole_rotation[side]};
  return {foot.p + foot.R * model.sole_offset[side], foot.R};
}

LegJacobian leg_jacobian(const RobotModel& model, const RobotModelData& data, int side, const Vector3d& point) {
  LegJacobian J;
  const int b0 = 2 + 7 * side;
  for (int i = 0; i < 6; ++i) {
    const Pose& f = data.frame[b0 + i];
    const Vector3d& a = data.axis[b0 + i];
    const int c = model.bodies[b0 + i].joint - leg_first_joint(side);  // the column of the joint's role
    J.block<3, 1>(0, c) = a.cross(point - f.p);
    J.block<3, 1>(3, c) = a;
  }
  return J;
}

LegTorque leg_gravity_torque(const RobotModel& model, const RobotModelData& data, int side) {
  LegTorque tau;
  const int b0 = 2 + 7 * side;
  const Vector3d g(0, 0, -model.gravity);
  for (int i = 0; i < 6; ++i) {
    const Pose& f = data.frame[b0 + i];
    const Vector3d& a = data.axis[b0 + i];
    Vector3d moment = Vector3d::Zero();  // gravity moment of the links below joint i about it
    for (int k = b0 + i; k < b0 + 7; ++k) moment += (data.com_world[k] - f.p).cross(model.bodies[k].mass * g);
    tau(model.bodies[b0 + i].joint - leg_first_joint(side)) = -a.dot(moment);
  }
  return tau;
}

}  // namespace flexgait::walking
