// The controller's model of a loaded description (robot_model.hpp, docs/guide/robot.md): the file's bodies
// lumped onto the model's 16 links — each file body onto the nearest link anchor at or above it
// (the root: the pelvis; the waist joint's body: the chest; each leg joint's body; each foot
// body) — with the zero-pose frames of the file expressed in the root frame, so that every link
// frame is parallel to the pelvis at zero angles (the model's convention).
#include <fmt/format.h>

#include <Eigen/SVD>
#include <algorithm>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/walking/robot_model.hpp"

namespace flexgait::walking {
namespace {

using humanoid::LoadedBody;
using humanoid::LoadedRobot;

Matrix3d rotation(const std::array<double, 4>& q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
}
Vector3d vec(const std::array<double, 3>& v) {
  return {v[0], v[1], v[2]};
}

/// Pose of body b in the frame of its ancestor a (a == b: identity), composed down the chain.
Pose relative(const LoadedRobot& r, int a, int b) {
  Pose out;
  for (int x = b; x != a; x = r.bodies[static_cast<std::size_t>(x)].parent) {
    const LoadedBody& body = r.bodies[static_cast<std::size_t>(x)];
    if (body.parent < 0) throw std::logic_error("relative(): not an ancestor");
    const Matrix3d R = rotation(body.quat);
    out.p = vec(body.pos) + R * out.p;
    out.R = R * out.R;
  }
  return out;
}

bool close(const Vector3d& a, const Vector3d& b) {
  return (a - b).cwiseAbs().maxCoeff() < 1e-9;
}

/// One link of the model: a point of a file body (its joint's anchor) and the file bodies lumped on it.
struct Anchor {
  int body = 0;                       ///< file body
  Vector3d point = Vector3d::Zero();  ///< anchor in that body's frame
};

/// The layout's axes (leg_kinematics.hpp), by role.
const std::array<Vector3d, 6> kLayoutAxes = {Vector3d::UnitZ(), Vector3d::UnitX(), Vector3d::UnitY(),
                                             Vector3d::UnitY(), Vector3d::UnitY(), Vector3d::UnitX()};

/// The leg's joints whose motions the others repeat (none when the six place the foot in 6 DOF): the
/// chain's Jacobian (sole twist per joint rate, its translation rows divided by the leg's length)
/// at a generic bent pose; a rank below 6 there is a rank below 6 everywhere (the rank is maximal
/// on an open dense set of poses). The joints (humanoid::Joint) of the Jacobian's null space, in
/// chain order.
std::vector<int> dependent_leg_joints(const LegGeometry& leg, int side) {
  const LegAngles q = {0.11, 0.13, -0.37, 0.71 * leg.sign[3] * leg.knee_branch(), -0.29, 0.17};
  double length = 0;
  for (const Vector3d& a : leg.anchor) length += a.norm();
  length += leg.sole.norm();
  Eigen::Matrix<double, 6, 6> J = leg_chain_jacobian(leg, q).J;
  J.topRows<3>() /= length;
  const Eigen::JacobiSVD<Eigen::Matrix<double, 6, 6>> svd(J, Eigen::ComputeFullV);
  const auto& sigma = svd.singularValues();
  // (a sound leg: the smallest singular value ~0.1 of the largest; parallel axes: rounding, 1e-16)
  if (sigma(5) > 1e-9 * sigma(0)) return {};
  std::vector<int> out;
  for (int i = 0; i < 6; ++i)
    if (std::abs(svd.matrixV()(i, 5)) > 1e-6)
      out.push_back(humanoid::leg_first_joint(side) + leg.role[static_cast<std::size_t>(i)]);
  return out;
}

/// Why leg `side` of m lacks the analytic IK's layout ("" when it has it): the joints in the
/// layout's order, each axis along the layout's either way (LegGeometry::sign), the offsets.
std::string layout_mismatch(const RobotModel& m, int side) {
  const int b0 = 2 + 7 * side, j0 = humanoid::leg_first_joint(side);
  auto offset = [&](int i) { return m.bodies[static_cast<std::size_t>(b0 + i)].offset; };
  for (int i = 0; i < 6; ++i)
    if (m.bodies[static_cast<std::size_t>(b0 + i)].joint != j0 + i)
      return fmt::format("joint {} from the root is {}, not {}", i + 1,
                         humanoid::kJointNames[m.bodies[static_cast<std::size_t>(b0 + i)].joint],
                         humanoid::kJointNames[j0 + i]);
  for (int i = 0; i < 6; ++i) {
    const Vector3d& a = m.bodies[static_cast<std::size_t>(b0 + i)].axis;
    if (!close(a, kLayoutAxes[static_cast<std::size_t>(i)]) && !close(a, -kLayoutAxes[static_cast<std::size_t>(i)]))
      return fmt::format("the axis of {} is not ±{} at zero angles", humanoid::kJointNames[j0 + i],
                         i == 0 ? "z" : (i == 1 || i == 5 ? "x" : "y"));
  }
  auto vertical = [](const Vector3d& v) { return std::abs(v.x()) < 1e-9 && std::abs(v.y()) < 1e-9 && v.z() < 0; };
  if (!(std::abs(offset(1).x()) < 1e-9 && std::abs(offset(1).y()) < 1e-9 && close(offset(2), Vector3d::Zero())))
    return "the hip yaw, roll and pitch axes do not meet in a point";
  if (!vertical(offset(3))) return "the knee is not straight below the hip";
  if (!vertical(offset(4)) || !close(offset(5), Vector3d::Zero()))
    return "the ankle pitch and roll axes do not meet straight below the knee";
  if (!((offset(6) + m.sole_offset[static_cast<std::size_t>(side)]).z() < 0))
    return "the sole centre is not below the ankle";
  return {};
}

}  // namespace

std::string analytic_ik_mismatch(const LoadedRobot& r, int side) {
  return layout_mismatch(make_robot_model(r), side);
}

RobotModel make_robot_model(const LoadedRobot& r) {
  const int n = static_cast<int>(r.bodies.size());
  // Zero-pose orientation of every file body in the root frame.
  std::vector<Matrix3d> R0(static_cast<std::size_t>(n), Matrix3d::Identity());
  for (int b = 1; b < n; ++b)
    R0[static_cast<std::size_t>(b)] = R0[static_cast<std::size_t>(r.bodies[static_cast<std::size_t>(b)].parent)] *
                                      rotation(r.bodies[static_cast<std::size_t>(b)].quat);

  RobotModel m;
  std::array<Anchor, kBodies> anchor{};
  auto joint_anchor = [&](int j) {
    const auto [body, k] = r.joint[j];
    return Anchor{body, vec(r.bodies[static_cast<std::size_t>(body)].joints[static_cast<std::size_t>(k)].pos)};
  };
  auto joint_axis = [&](int j) {
    const auto [body, k] = r.joint[j];
    return Vector3d(R0[static_cast<std::size_t>(body)] *
                    vec(r.bodies[static_cast<std::size_t>(body)].joints[static_cast<std::size_t>(k)].axis));
  };
  m.bodies[1].parent = 0;
  if (r.has_joint(humanoid::kWaistYaw)) {
    m.bodies[1].joint = humanoid::kWaistYaw;
    m.bodies[1].axis = joint_axis(humanoid::kWaistYaw);
    anchor[1] = joint_anchor(humanoid::kWaistYaw);
  } else {  // a trunk without a waist: the chest is the root's rigid part and takes its mass
    m.bodies[1].axis = Vector3d::UnitZ();
    anchor[1] = {0, Vector3d::Zero()};
  }
  for (int side = 0; side < 2; ++side) {
    const int b0 = 2 + 7 * side, j0 = humanoid::leg_first_joint(side);
    for (int i = 0; i < 7; ++i) {
      auto& b = m.bodies[static_cast<std::size_t>(b0 + i)];
      b.parent = i == 0 ? 0 : b0 + i - 1;
      // The leg's bodies in the file's order from the root (LoadedRobot::leg_order).
      const int j = i < 6 ? j0 + r.leg_order[side][static_cast<std::size_t>(i)] : -1;
      b.joint = j;
      if (i < 6) {
        b.axis = joint_axis(j);
        anchor[static_cast<std::size_t>(b0 + i)] = joint_anchor(j);
      } else {
        anchor[static_cast<std::size_t>(b0 + i)] = {r.foot[side], Vector3d::Zero()};
      }
    }
    m.foot[side] = b0 + 6;
  }
  // Offsets: each anchor from its parent's, in the parent's (root-parallel) frame.
  for (int k = 1; k < kBodies; ++k) {
    const Anchor& a = anchor[static_cast<std::size_t>(k)];
    const Anchor& p = anchor[static_cast<std::size_t>(m.bodies[static_cast<std::size_t>(k)].parent)];
    const Pose rel = relative(r, p.body, a.body);
    m.bodies[static_cast<std::size_t>(k)].offset =
        R0[static_cast<std::size_t>(p.body)] * (rel.p + rel.R * a.point - p.point);
  }
  // Each file body's link: the nearest anchor at or above it (of anchors in one body, the last).
  std::vector<int> link(static_cast<std::size_t>(n), -1);
  for (int b = 0; b < n; ++b) {
    int owner = -1;
    for (int x = b; x >= 0 && owner < 0; x = r.bodies[static_cast<std::size_t>(x)].parent)
      for (int k = kBodies - 1; k >= 0 && owner < 0; --k)
        if (anchor[static_cast<std::size_t>(k)].body == x) owner = k;
    link[static_cast<std::size_t>(b)] = owner < 0 ? 0 : owner;
  }
  // (The foot link takes its whole body even when that body also carries the ankle-roll joint.)
  // Mass, centre of mass and inertia of each link, in its (root-parallel) frame.
  for (int k = 0; k < kBodies; ++k) {
    auto& body = m.bodies[static_cast<std::size_t>(k)];
    const Anchor& a = anchor[static_cast<std::size_t>(k)];
    double mass = 0;
    Vector3d first = Vector3d::Zero(), moment = Vector3d::Zero();
    int count = 0;
    std::vector<std::pair<int, Vector3d>> parts;
    for (int b = 0; b < n; ++b) {
      const LoadedBody& f = r.bodies[static_cast<std::size_t>(b)];
      if (link[static_cast<std::size_t>(b)] != k || !(f.mass > 0)) continue;
      const Pose rel = relative(r, a.body, b);
      const Vector3d c = R0[static_cast<std::size_t>(a.body)] * (rel.p + rel.R * vec(f.ipos) - a.point);
      parts.emplace_back(b, c);
      if (count++ == 0) first = c;
      mass += f.mass;
      moment += f.mass * c;
    }
    body.mass = mass;
    body.com = count == 1 ? first : (mass > 0 ? Vector3d(moment / mass) : Vector3d::Zero());
    for (const auto& [b, c] : parts) {
      const LoadedBody& f = r.bodies[static_cast<std::size_t>(b)];
      const Matrix3d Ri = R0[static_cast<std::size_t>(b)] * rotation(f.iquat);
      const Vector3d d = c - body.com;
      body.inertia += Ri * vec(f.inertia).asDiagonal() * Ri.transpose() +
                      f.mass * (d.squaredNorm() * Matrix3d::Identity() - d * d.transpose());
    }
  }
  for (const auto& b : m.bodies) m.total_mass += b.mass;
  m.gravity = r.gravity;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    if (!r.has_joint(j)) continue;
    const humanoid::LoadedJoint& lj =
        r.bodies[static_cast<std::size_t>(r.joint[j][0])].joints[static_cast<std::size_t>(r.joint[j][1])];
    if (lj.limited) m.range[static_cast<std::size_t>(j)] = {lj.range[0], lj.range[1]};
  }

  // The soles and the analytic IK's layout.
  for (int side = 0; side < 2; ++side) {
    const int b0 = 2 + 7 * side;
    const int fb = r.foot[side];
    const Matrix3d& Rf = R0[static_cast<std::size_t>(fb)];
    // The sole's frame in the foot link's (root-parallel) frame: the foot body's orientation at zero
    // angles, times the sole's own frame in it (Sole::quat; identity for a level foot, whose printed
    // tilt below kMaxFootTilt is modelled as such).
    const humanoid::Sole& sole = r.sole[side];
    const bool own_frame = sole.has_own_frame();
    const Matrix3d Rs = own_frame ? Matrix3d(Rf * rotation(sole.quat)) : Rf;
    m.sole_tilted[side] = Rs != Matrix3d::Identity();
    m.sole_rotation[side] = Rs;
    m.sole_offset[side] = m.sole_tilted[side] ? Vector3d(Rf * vec(sole.center)) : vec(sole.center);
    // The sole centre from the F/T sensor (the foot body's origin, its axes the sole's), in the sole's frame.
    m.ft_to_sole[side] = own_frame ? Vector3d(Rs.transpose() * m.sole_offset[side]) : m.sole_offset[side];
    LegGeometry& leg = m.leg[static_cast<std::size_t>(side)];
    fill_leg_chain(m, side);
    leg.analytic = layout_mismatch(m, side).empty() && !m.sole_tilted[side];
    // Each joint's direction against the layout's axis and its range (the file's angles).
    for (int i = 0; i < 6; ++i) {
      const auto& body = m.bodies[static_cast<std::size_t>(b0 + i)];
      const int role = body.joint - humanoid::leg_first_joint(side);
      leg.sign[static_cast<std::size_t>(role)] =
          body.axis.dot(kLayoutAxes[static_cast<std::size_t>(role)]) < 0 ? -1.0 : 1.0;
      leg.lower[static_cast<std::size_t>(role)] = m.range[static_cast<std::size_t>(body.joint)][0];
      leg.upper[static_cast<std::size_t>(role)] = m.range[static_cast<std::size_t>(body.joint)][1];
    }
    if (const std::vector<int> dependent = dependent_leg_joints(leg, side); !dependent.empty()) {
      auto file_name = [&](int j) {
        return r.bodies[static_cast<std::size_t>(r.joint[j][0])].joints[static_cast<std::size_t>(r.joint[j][1])].name;
      };
      std::string list;
      for (const int j : dependent)
        list += fmt::format("{}{} '{}'", list.empty() ? "" : ", ", humanoid::kJointNames[j], file_name(j));
      const std::string key = "robot.joints." + std::string(humanoid::kJointNames[dependent.front()]);
      throw ConfigError(key,
                        fmt::format("key '{}' = '{}': the {} leg's joint axes cannot place the foot in 6 degrees "
                                    "of freedom: the motions of {} repeat one another (parallel axes, or axes "
                                    "through one point); allowed: six joints that move the foot in every direction",
                                    key, file_name(dependent.front()), side == 0 ? "left" : "right", list));
    }
    auto offset = [&](int i) { return m.bodies[static_cast<std::size_t>(b0 + i)].offset; };
    leg.hip = offset(0) + offset(1);
    leg.thigh = -offset(3).z();
    leg.shank = -offset(4).z();
    // The F/T sensor (the foot body's origin) to the sole; for the analytic layout, the ankle to the sole.
    leg.ankle_to_sole = leg.analytic ? -(offset(6) + m.sole_offset[static_cast<std::size_t>(side)]).z()
                                     : -m.ft_to_sole[static_cast<std::size_t>(side)].z();
    // For the analytic layout, the sole centre's horizontal shift from below the ankle.
    if (leg.analytic)
      leg.sole_shift = Vector3d((offset(6) + m.sole_offset[static_cast<std::size_t>(side)]).x(),
                                (offset(6) + m.sole_offset[static_cast<std::size_t>(side)]).y(), 0);
  }
  // One sole rectangle for both feet (the plan's support polygons, the CoP limits): a robot
  // whose soles differ is refused rather than walked on the left foot's numbers.
  if (std::abs(r.sole[0].length - r.sole[1].length) > 1e-9 || std::abs(r.sole[0].width - r.sole[1].width) > 1e-9)
    throw ConfigError("robot.feet.right.body",
                      fmt::format("key 'robot.feet.right.body' = '{}': its sole ({} x {} m) differs from the left "
                                  "foot's ({} x {} m); flexgait needs the same sole on both feet",
                                  r.bodies[static_cast<std::size_t>(r.foot[1])].name, r.sole[1].length, r.sole[1].width,
                                  r.sole[0].length, r.sole[0].width));
  m.sole_length = r.sole[0].length;
  m.sole_width = r.sole[0].width;
  // Each sole's polygon about its centre, in the sole's frame (the foot body's unless the sole has
  // its own, Sole::quat): the hull of the foot's contact geoms, unless it is its bounding rectangle
  // (then the rectangle's own numbers).
  for (int side = 0; side < 2; ++side) {
    const humanoid::Sole& s = r.sole[static_cast<std::size_t>(side)];
    const Vector3d center = s.has_own_frame() ? Vector3d(rotation(s.quat).transpose() * vec(s.center)) : vec(s.center);
    auto distinct = [&](int axis) {
      std::vector<double> v;
      for (const auto& p : s.hull) v.push_back(p[static_cast<std::size_t>(axis)]);
      std::sort(v.begin(), v.end());
      return std::unique(v.begin(), v.end()) - v.begin();
    };
    const bool box = s.hull.empty() || (s.hull.size() == 4 && distinct(0) == 2 && distinct(1) == 2);
    std::vector<Eigen::Vector2d> corners;
    for (const auto& p : s.hull) corners.emplace_back(p[0] - center[0], p[1] - center[1]);
    m.sole_polygon[static_cast<std::size_t>(side)] = box ? rectangle_sole(s.length, s.width) : polygon_sole(corners);
  }
  index_joint_axes(m);
  return m;
}

}  // namespace flexgait::walking
