#include "flexgait/robot/urdf_export.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace flexgait::humanoid {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Vector3d vec(const std::array<double, 3>& v) {
  return {v[0], v[1], v[2]};
}
Matrix3d rotation(const std::array<double, 4>& q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

std::string rpy(const Matrix3d& R) {
  const std::array<double, 3> a = urdf_rpy(R);
  return fmt::format("{} {} {}", a[0] + 0.0, a[1] + 0.0, a[2] + 0.0);  // no "-0"
}
std::string xyz(const Vector3d& v) {
  return fmt::format("{} {} {}", v.x(), v.y(), v.z());
}

/// The anchor of a body's link frame in the body frame: its first kept joint's anchor.
Vector3d anchor(const LoadedBody& b) {
  for (const LoadedJoint& j : b.joints)
    if (j.mapped >= 0) return vec(j.pos);
  return Vector3d::Zero();
}

/// Whether the sole of `side` is the hull of the foot's contact geoms, all of them carried (no mesh).
bool hull_sole(const LoadedRobot& r, int side) {
  const Sole& s = r.sole[static_cast<std::size_t>(side)];
  return !s.hull.empty() && s.hull_in_twin;
}

std::string shape(const LoadedGeom& g) {
  if (g.type == "box") return fmt::format(R"(<box size="{} {} {}"/>)", 2 * g.size[0], 2 * g.size[1], 2 * g.size[2]);
  if (g.type == "sphere") return fmt::format(R"(<sphere radius="{}"/>)", g.size[0]);
  if (g.type == "cylinder" || g.type == "capsule")
    return fmt::format(R"(<cylinder radius="{}" length="{}"/>)", g.size[0], 2 * g.size[1]);
  return {};
}

/// The geom as URDF <collision> elements (origins in the link frame, whose origin is `o` in the
/// body frame): a box, sphere or cylinder as itself; a capsule, which URDF lacks, as the spheres at
/// its two ends (the points it rests on, hence the same sole hull; the straight part between them
/// is left out); an ellipsoid as the sphere of its smallest semi-axis through its lowest point.
std::string collisions(const LoadedGeom& g, const Vector3d& o) {
  const Matrix3d R = rotation(g.quat);
  const Vector3d c = vec(g.pos) - o;
  auto element = [](const Vector3d& at, const std::string& r, const std::string& geometry) {
    return fmt::format(
        "    <collision>\n      <origin xyz=\"{}\" rpy=\"{}\"/>\n      <geometry>{}</geometry>\n    </collision>\n",
        xyz(at), r, geometry);
  };
  auto sphere = [&](double radius) { return fmt::format(R"(<sphere radius="{}"/>)", radius); };
  if (g.type == "box" || g.type == "sphere" || g.type == "cylinder") return element(c, rpy(R), shape(g));
  if (g.type == "capsule") {
    const Vector3d axis = R * Vector3d(0, 0, g.size[1]);
    return element(c + axis, "0 0 0", sphere(g.size[0])) + element(c - axis, "0 0 0", sphere(g.size[0]));
  }
  if (g.type == "ellipsoid") {
    // The lowest point of {x : x' S^-1 x = 1}, S = R diag(a^2) R': x = -S e_z / sqrt(e_z' S e_z).
    const Vector3d a2(g.size[0] * g.size[0], g.size[1] * g.size[1], g.size[2] * g.size[2]);
    const Vector3d Se = R * a2.asDiagonal() * R.transpose().col(2);
    const double r = std::min({g.size[0], g.size[1], g.size[2]});
    return element(c - Se / std::sqrt(Se.z()) + Vector3d(0, 0, r), "0 0 0", sphere(r));
  }
  return {};
}

}  // namespace

std::array<double, 3> urdf_rpy(const Matrix3d& R) {
  // The first column is (cos y cos p, sin y cos p, −sin p): the pitch, and the yaw from its
  // horizontal part (any yaw at gimbal lock, where that part vanishes). Then the roll from the
  // second row of Rz(yaw)ᵀ R = Ry(p) Rx(r), which is (0, cos r, −sin r) whatever the pitch: the
  // roll absorbs the yaw's error, so the three reproduce R to rounding even where the classic
  // roll = atan2(R21, R22) divides rounding by cos p.
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double roll = std::atan2(-(c * R(1, 2) - s * R(0, 2)), c * R(1, 1) - s * R(0, 1));
  return {roll, pitch, yaw};
}

std::string robot_urdf(const LoadedRobot& r) {
  std::string out =
      "<?xml version=\"1.0\"?>\n<!-- written by flexgait humanoid export --format urdf -->\n<robot "
      "name=\"flexgait_robot\">\n";
  for (std::size_t b = 0; b < r.bodies.size(); ++b) {
    const LoadedBody& body = r.bodies[b];
    const Vector3d o = anchor(body);
    out += fmt::format("  <link name=\"{}\">\n", body.name);
    if (body.mass > 0) {
      out += fmt::format("    <inertial>\n      <origin xyz=\"{}\" rpy=\"{}\"/>\n      <mass value=\"{}\"/>\n",
                         xyz(vec(body.ipos) - o), rpy(rotation(body.iquat)), body.mass);
      out += fmt::format(
          "      <inertia ixx=\"{}\" ixy=\"0\" ixz=\"0\" iyy=\"{}\" iyz=\"0\" izz=\"{}\"/>\n    </inertial>\n",
          body.inertia[0], body.inertia[1], body.inertia[2]);
    }
    for (const LoadedGeom& g : body.geoms) {
      const std::string s = shape(g);
      if (s.empty()) continue;
      out += fmt::format(
          "    <visual>\n      <origin xyz=\"{}\" rpy=\"{}\"/>\n      <geometry>{}</geometry>\n    </visual>\n",
          xyz(vec(g.pos) - o), rpy(rotation(g.quat)), s);
    }
    // A sole made of the foot's contact geoms: those geoms as the link's only collisions, so that
    // the loader makes the same hull from them (urdf_mapping names no sole).
    for (int side = 0; side < 2; ++side)
      if (hull_sole(r, side) && r.foot[static_cast<std::size_t>(side)] == static_cast<int>(b))
        for (const int g : r.sole[static_cast<std::size_t>(side)].hull_geoms)
          out += collisions(body.geoms[static_cast<std::size_t>(g)], o);
    out += "  </link>\n";
  }
  for (std::size_t b = 1; b < r.bodies.size(); ++b) {
    const LoadedBody& body = r.bodies[b];
    const LoadedBody& parent = r.bodies[static_cast<std::size_t>(body.parent)];
    const Matrix3d R = rotation(body.quat);
    const Vector3d p = vec(body.pos) + R * anchor(body) - anchor(parent);  // child link frame in the parent link frame
    const LoadedJoint* joint = nullptr;
    for (const LoadedJoint& j : body.joints)
      if (j.mapped >= 0 && joint == nullptr) joint = &j;
    const std::string name = joint ? joint->name : body.name + "_fixed";
    out += fmt::format("  <joint name=\"{}\" type=\"{}\">\n    <parent link=\"{}\"/>\n    <child link=\"{}\"/>\n", name,
                       joint ? (joint->limited ? "revolute" : "continuous") : "fixed", parent.name, body.name);
    out += fmt::format("    <origin xyz=\"{}\" rpy=\"{}\"/>\n", xyz(p), rpy(R));
    if (joint) {
      out += fmt::format("    <axis xyz=\"{}\"/>\n", xyz(vec(joint->axis)));
      if (joint->limited)
        out += fmt::format("    <limit lower=\"{}\" upper=\"{}\" effort=\"1000\" velocity=\"100\"/>\n", joint->range[0],
                           joint->range[1]);
      // URDF's damping and friction; armature (the rotor's reflected inertia) is flexgait's extension
      // of <dynamics>, which MuJoCo's URDF reader passes over and flexgait's loader reads back.
      if (joint->damping > 0 || joint->frictionloss > 0 || joint->armature > 0)
        out += fmt::format("    <dynamics damping=\"{}\" friction=\"{}\" armature=\"{}\"/>\n", joint->damping,
                           joint->frictionloss, joint->armature);
    }
    out += "  </joint>\n";
  }
  out += "</robot>\n";
  return out;
}

std::string urdf_mapping(const LoadedRobot& r) {
  std::string out;
  for (const LoadedBody& body : r.bodies)
    for (const LoadedJoint& j : body.joints)
      if (j.mapped >= 0) out += fmt::format("robot.joints.{}={}\n", kJointNames[j.mapped], j.name);
  if (!r.has_joint(kWaistYaw)) out += fmt::format("robot.joints.{}=none\n", kJointNames[kWaistYaw]);
  for (int side = 0; side < 2; ++side) {
    const std::string f = std::string("robot.feet.") + (side == 0 ? "left" : "right");
    const LoadedBody& foot = r.bodies[static_cast<std::size_t>(r.foot[side])];
    const Vector3d c = vec(r.sole[side].center) - anchor(foot);
    if (hull_sole(r, side))  // (the sole from the exported contact geoms)
      out += fmt::format("{0}.body={1}\n{0}.sole_geom=none\n{0}.sole_size=none\n", f, foot.name);
    else
      out += fmt::format("{0}.body={1}\n{0}.sole_geom=none\n{0}.sole_size={2} {3}\n{0}.sole_center={4}\n", f, foot.name,
                         r.sole[side].length, r.sole[side].width, xyz(c));
  }
  return out;
}

}  // namespace flexgait::humanoid
