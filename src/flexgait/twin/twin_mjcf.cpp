#include "flexgait/twin/twin_mjcf.hpp"

#include <fmt/format.h>

#include <string_view>

#include "flexgait/twin/model_xml.hpp"

namespace flexgait::humanoid {
namespace {

template <class T, std::size_t N>
std::string list(const std::array<T, N>& v) {
  std::string s;
  for (std::size_t i = 0; i < N; ++i) s += (i ? " " : "") + fmt::format("{}", v[i]);  // shortest round-trip text
  return s;
}

/// A name the twin gives to its own elements: a file geom of that name loses it.
bool reserved(std::string_view name) {
  return name == "floor" || name == "l_sole" || name == "r_sole";
}

void write_body(std::string& out, const LoadedRobot& r, const RobotParams& robot, const PlantParams& p, int b,
                int depth) {
  const LoadedBody& body = r.bodies[static_cast<std::size_t>(b)];
  const std::string pad(static_cast<std::size_t>(2 * depth), ' ');
  const bool root = body.parent < 0;
  out += pad + "<body";
  if (!body.name.empty()) out += fmt::format(" name=\"{}\"", body.name);
  out += fmt::format(" pos=\"{}\" quat=\"{}\">\n", root ? "0 0 1" : list(body.pos), root ? "1 0 0 0" : list(body.quat));
  if (root) out += pad + "  <freejoint name=\"root\"/>\n";
  if (b == r.imu_body) out += pad + "  <site name=\"imu\" pos=\"0 0 0\" size=\"0.01\"/>\n";
  for (int side = 0; side < 2; ++side)
    if (b == r.foot[side])
      out += fmt::format("{}  <site name=\"{}_ft\" pos=\"0 0 0\" size=\"0.01\"/>\n", pad, side == 0 ? "l" : "r");
  if (body.mass > 0)
    out += fmt::format("{}  <inertial pos=\"{}\" quat=\"{}\" mass=\"{}\" diaginertia=\"{}\"/>\n", pad, list(body.ipos),
                       list(body.iquat), body.mass, list(body.inertia));
  const JointVector k = p.gear_stiffness();
  for (const LoadedJoint& j : body.joints) {
    if (j.mapped < 0) continue;  // held rigid
    out += fmt::format("{}  <joint name=\"{}\" type=\"hinge\" pos=\"{}\" axis=\"{}\" stiffness=\"{}\" damping=\"{}\"",
                       pad, kJointNames[j.mapped], list(j.pos), list(j.axis), k[j.mapped], p.gear_damping);
    if (j.limited) out += fmt::format(" limited=\"true\" range=\"{} {}\"", j.range[0], j.range[1]);
    if (j.armature > 0) out += fmt::format(" armature=\"{}\"", j.armature);
    if (j.frictionloss > 0) out += fmt::format(" frictionloss=\"{}\"", j.frictionloss);
    out += "/>\n";
  }
  const int side = b == r.foot[0] ? 0 : (b == r.foot[1] ? 1 : -1);
  const std::string sole_name = side == 0 ? "l_sole" : "r_sole";
  const std::string sole_contact =
      fmt::format(R"(contype="1" conaffinity="1" condim="3" friction="{} 0.005 0.0001" solref="{} 1")",
                  robot.sole_friction, p.contact_time_constant);
  for (std::size_t g = 0; g < body.geoms.size(); ++g) {
    const LoadedGeom& geom = body.geoms[g];
    const bool sole = side >= 0 && r.sole[side].geom == static_cast<int>(g);
    std::string name = sole ? sole_name : (reserved(geom.name) ? "" : geom.name);
    out += pad + "  <geom";
    if (!name.empty()) out += fmt::format(" name=\"{}\"", name);
    out += fmt::format(" type=\"{}\" size=\"{}\" pos=\"{}\" quat=\"{}\"", geom.type, list(geom.size), list(geom.pos),
                       list(geom.quat));
    if (sole)
      out += " " + sole_contact;
    else
      out += fmt::format(
          R"( contype="{}" conaffinity="{}" condim="{}" friction="{}" solref="{}" solimp="{}" margin="{}" gap="{}")",
          geom.contype, geom.conaffinity, geom.condim, list(geom.friction), list(geom.solref), list(geom.solimp),
          geom.margin, geom.gap);
    out += fmt::format(" rgba=\"{}\"/>\n", list(geom.rgba));
  }
  if (side >= 0 && r.sole[side].geom < 0) {  // a sole plate 10 mm thick on the sole rectangle
    const Sole& s = r.sole[side];
    out += fmt::format(
        "{}  <geom name=\"{}\" type=\"box\" size=\"{} {} 0.005\" pos=\"{} {} {}\" {} rgba=\".3 .3 .8 1\"/>\n", pad,
        sole_name, 0.5 * s.length, 0.5 * s.width, s.center[0], s.center[1], s.center[2] + 0.005, sole_contact);
  }
  for (std::size_t c = 0; c < r.bodies.size(); ++c)
    if (r.bodies[c].parent == b) write_body(out, r, robot, p, static_cast<int>(c), depth + 1);
  out += pad + "</body>\n";
}

}  // namespace

std::string twin_mjcf(const LoadedRobot& r, const RobotParams& robot, const PlantParams& p) {
  std::string bodies;
  write_body(bodies, r, robot, p, 0, 2);
  std::string exclude;
  for (const auto& e : r.exclude)
    exclude += fmt::format("    <exclude body1=\"{}\" body2=\"{}\"/>\n", r.bodies[static_cast<std::size_t>(e[0])].name,
                           r.bodies[static_cast<std::size_t>(e[1])].name);
  return twin_document("flexgait_twin", false, robot.sole_friction, p, bodies,
                       exclude.empty() ? std::string() : "  <contact>\n" + exclude + "  </contact>\n");
}

std::string twin_mjcf_mapping(const LoadedRobot& loaded) {
  std::string out;
  for (int j = 0; j < kJoints; ++j)
    out += fmt::format("robot.joints.{}={}\n", kJointNames[j], loaded.has_joint(j) ? kJointNames[j] : "none");
  for (int side = 0; side < 2; ++side) {
    const LoadedBody& foot = loaded.bodies[static_cast<std::size_t>(loaded.foot[side])];
    out += fmt::format("robot.feet.{0}.body={1}\nrobot.feet.{0}.sole_geom={2}\n", side == 0 ? "left" : "right",
                       foot.name, side == 0 ? "l_sole" : "r_sole");
  }
  return out;
}

}  // namespace flexgait::humanoid
