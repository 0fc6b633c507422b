#include "flexgait/twin/twin_mjcf.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <string_view>

#include "flexgait/twin/model_xml.hpp"

namespace flexgait::twin {
namespace {

template <class T, std::size_t N>
std::string list(const std::array<T, N>& v) {
  std::string s;
  for (std::size_t i = 0; i < N; ++i) s += (i ? " " : "") + fmt::format("{}", v[i]);  // shortest round-trip text
  return s;
}

/// MuJoCo's compiler divides each quaternion and axis by its norm, v / sqrt(Σ v_i²) (the same bits
/// as MuJoCo 2.2.2 on random quaternions), which moves some unit vectors by an ulp: a compiled
/// quaternion written as it is may load back one bit off. Returns the text of a vector within 3
/// ulps per component whose normalisation is `v` to the bit (v's own text first; zeros stay zero),
/// or v's text when there is none.
template <std::size_t N>
std::string unit_list(const std::array<double, N>& v) {
  auto normalised = [](std::array<double, N> w) {
    double s = 0;
    for (const double x : w) s += x * x;
    const double n = std::sqrt(s);
    for (double& x : w) x /= n;
    return w;
  };
  constexpr std::array<int, 7> kSteps = {0, 1, -1, 2, -2, 3, -3};
  std::size_t combinations = 1;
  for (std::size_t i = 0; i < N; ++i) combinations *= kSteps.size();
  for (std::size_t c = 0; c < combinations; ++c) {
    std::array<double, N> w = v;
    std::size_t digits = c;
    bool zero_moved = false;
    for (std::size_t i = 0; i < N; ++i, digits /= kSteps.size()) {
      const int step = kSteps[digits % kSteps.size()];
      zero_moved = zero_moved || (w[i] == 0 && step != 0);
      for (int k = 0; k < std::abs(step); ++k) w[i] = std::nextafter(w[i], step > 0 ? INFINITY : -INFINITY);
    }
    if (!zero_moved && normalised(w) == v) return list(w);
  }
  return list(v);
}

/// The quat attribute of an element in a sole's own frame (humanoid::Sole::quat); "" if it has none.
std::string sole_frame(const humanoid::Sole& s) {
  return s.has_own_frame() ? " quat=\"" + unit_list(s.quat) + "\"" : "";
}

/// A name the twin gives to its own elements: a file geom of that name loses it.
bool reserved(std::string_view name) {
  return name == "floor" || name == "l_sole" || name == "r_sole";
}

void write_body(std::string& out, const humanoid::LoadedRobot& r, const humanoid::RobotParams& robot,
                const PlantParams& p, int b, int depth) {
  const humanoid::LoadedBody& body = r.bodies[static_cast<std::size_t>(b)];
  const std::string pad(static_cast<std::size_t>(2 * depth), ' ');
  const bool root = body.parent < 0;
  out += pad + "<body";
  if (!body.name.empty()) out += fmt::format(" name=\"{}\"", body.name);
  out += fmt::format(" pos=\"{}\" quat=\"{}\">\n", root ? "0 0 1" : list(body.pos),
                     root ? "1 0 0 0" : unit_list(body.quat));
  if (root) out += pad + "  <freejoint name=\"root\"/>\n";
  if (b == r.imu_body) out += pad + "  <site name=\"imu\" pos=\"0 0 0\" size=\"0.01\"/>\n";
  // The F/T sensor at the foot body's origin, its axes the sole's.
  for (int side = 0; side < 2; ++side)
    if (b == r.foot[side])
      out += fmt::format("{}  <site name=\"{}_ft\" pos=\"0 0 0\"{} size=\"0.01\"/>\n", pad, side == 0 ? "l" : "r",
                         sole_frame(r.sole[side]));
  if (body.mass > 0)
    out += fmt::format("{}  <inertial pos=\"{}\" quat=\"{}\" mass=\"{}\" diaginertia=\"{}\"/>\n", pad, list(body.ipos),
                       unit_list(body.iquat), body.mass, list(body.inertia));
  const humanoid::JointVector k = p.gear_stiffness();
  for (const humanoid::LoadedJoint& j : body.joints) {
    if (j.mapped < 0) continue;  // held rigid
    out +=
        fmt::format("{}  <joint name=\"{}\" type=\"hinge\" pos=\"{}\" axis=\"{}\" stiffness=\"{}\" damping=\"{}\"", pad,
                    humanoid::kJointNames[j.mapped], list(j.pos), unit_list(j.axis), k[j.mapped], p.gear_damping);
    if (j.limited) out += fmt::format(" limited=\"true\" range=\"{} {}\"", j.range[0], j.range[1]);
    // (no armature: the file's armature is its rotors' inertia reflected through the gears, which the twin's
    // elastic drive holds behind the gear spring, plant.rotor_inertia; on the link it would be counted twice)
    if (j.frictionloss > 0) out += fmt::format(" frictionloss=\"{}\"", j.frictionloss);
    out += "/>\n";
  }
  const int side = b == r.foot[0] ? 0 : (b == r.foot[1] ? 1 : -1);
  const std::string sole_name = side == 0 ? "l_sole" : "r_sole";
  const std::string sole_contact =
      fmt::format(R"(contype="1" conaffinity="1" condim="3" friction="{} 0.005 0.0001" solref="{} 1")",
                  robot.sole_friction, p.contact_time_constant);
  for (std::size_t g = 0; g < body.geoms.size(); ++g) {
    const humanoid::LoadedGeom& geom = body.geoms[g];
    const bool sole = side >= 0 && r.sole[side].geom == static_cast<int>(g);
    // (a geom of a sole made by the foot's contact geoms: it keeps its name and takes the sole's contact)
    const bool sole_part = side >= 0 && r.sole[side].hull_in_twin &&
                           std::find(r.sole[side].hull_geoms.begin(), r.sole[side].hull_geoms.end(),
                                     static_cast<int>(g)) != r.sole[side].hull_geoms.end();
    std::string name = sole ? sole_name : (reserved(geom.name) ? "" : geom.name);
    out += pad + "  <geom";
    if (!name.empty()) out += fmt::format(" name=\"{}\"", name);
    out += fmt::format(" type=\"{}\" size=\"{}\" pos=\"{}\" quat=\"{}\"", geom.type, list(geom.size), list(geom.pos),
                       unit_list(geom.quat));
    if (sole || sole_part)
      out += " " + sole_contact;
    else
      out += fmt::format(
          R"( contype="{}" conaffinity="{}" condim="{}" friction="{}" solref="{}" solimp="{}" margin="{}" gap="{}")",
          geom.contype, geom.conaffinity, geom.condim, list(geom.friction), list(geom.solref), list(geom.solimp),
          geom.margin, geom.gap);
    out += fmt::format(" rgba=\"{}\"/>\n", list(geom.rgba));
  }
  if (side >= 0 && r.sole[side].geom < 0) {  // a sole plate 10 mm thick on the sole rectangle
    const humanoid::Sole& s = r.sole[side];
    // (on a sole the foot's own geoms make in the twin, the plate only marks it: no contact)
    // Its centre 5 mm above the sole along the sole's z (in the sole's own frame, if it has one).
    std::array<double, 3> c = s.center;
    if (s.has_own_frame()) {
      mjtNum up[3] = {0, 0, 0.005}, shift[3];
      mju_rotVecQuat(shift, up, s.quat.data());
      for (int i = 0; i < 3; ++i) c[static_cast<std::size_t>(i)] += shift[i];
    } else {
      c[2] += 0.005;
    }
    out +=
        fmt::format("{}  <geom name=\"{}\" type=\"box\" size=\"{} {} 0.005\" pos=\"{}\"{} {} rgba=\".3 .3 .8 {}\"/>\n",
                    pad, sole_name, 0.5 * s.length, 0.5 * s.width, list(c), sole_frame(s),
                    s.hull_in_twin ? R"(contype="0" conaffinity="0")" : sole_contact, s.hull_in_twin ? "0.3" : "1");
  }
  for (std::size_t c = 0; c < r.bodies.size(); ++c)
    if (r.bodies[c].parent == b) write_body(out, r, robot, p, static_cast<int>(c), depth + 1);
  out += pad + "</body>\n";
}

}  // namespace

std::array<double, 3> sole_center_in_site(const humanoid::Sole& sole) {
  if (!sole.has_own_frame()) return sole.center;
  mjtNum inverse[4], c[3];
  mju_negQuat(inverse, sole.quat.data());
  mju_rotVecQuat(c, sole.center.data(), inverse);
  return {c[0], c[1], c[2]};
}

std::string twin_mjcf(const humanoid::LoadedRobot& r, const humanoid::RobotParams& robot, const PlantParams& p) {
  std::string bodies;
  write_body(bodies, r, robot, p, 0, 2);
  std::string exclude;
  for (const auto& e : r.exclude)
    exclude += fmt::format("    <exclude body1=\"{}\" body2=\"{}\"/>\n", r.bodies[static_cast<std::size_t>(e[0])].name,
                           r.bodies[static_cast<std::size_t>(e[1])].name);
  return twin_document("flexgait_twin", false, robot.sole_friction, r.gravity, p, bodies,
                       exclude.empty() ? std::string() : "  <contact>\n" + exclude + "  </contact>\n");
}

std::string twin_mjcf_mapping(const humanoid::LoadedRobot& loaded) {
  std::string out;
  for (int j = 0; j < humanoid::kJoints; ++j)
    out += fmt::format("robot.joints.{}={}\n", humanoid::kJointNames[j],
                       loaded.has_joint(j) ? humanoid::kJointNames[j] : "none");
  for (int side = 0; side < 2; ++side) {
    const humanoid::LoadedBody& foot = loaded.bodies[static_cast<std::size_t>(loaded.foot[side])];
    // (a sole the foot's own geoms make in the twin is made again from them on reload)
    out += fmt::format("robot.feet.{0}.body={1}\nrobot.feet.{0}.sole_geom={2}\n", side == 0 ? "left" : "right",
                       foot.name, loaded.sole[side].hull_in_twin ? "none" : (side == 0 ? "l_sole" : "r_sole"));
  }
  return out;
}

}  // namespace flexgait::twin
