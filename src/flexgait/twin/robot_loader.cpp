#include "flexgait/twin/robot_loader.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <vector>

#include "flexgait/core/text.hpp"
#include "flexgait/robot/convex_hull.hpp"
#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/robot_loader_xml.hpp"
#include "flexgait/twin/twin_mjcf.hpp"

namespace flexgait::twin {
namespace {

using ModelPtr = std::unique_ptr<mjModel, void (*)(mjModel*)>;
using DataPtr = std::unique_ptr<mjData, void (*)(mjData*)>;

[[noreturn]] void fail(const std::string& key, const std::string& value, const std::string& why) {
  throw ConfigError(key, fmt::format("key '{}' = '{}': {}", key, one_line(value), why));
}

std::string name_of(const mjModel* m, mjtObj type, int id) {
  const char* n = mj_id2name(m, type, id);
  return n ? n : "";
}

/// Refuses what MuJoCo's compiler would take silently or fail on without naming the file's fault:
/// no element at all, and a number that is not finite (MuJoCo reads "nan" and "inf" as numbers; a
/// NaN mass then falls back to the geoms' density mass, a NaN axis or an infinite mass reaches the
/// solver).
void check_text(const std::string& text, const std::string& source) {
  if (text.find('<') == std::string::npos)
    fail("robot.description", source,
         text.find_first_not_of(" \t\r\n") == std::string::npos ? "the file is empty"
                                                                : "not an MJCF or URDF file (no XML element)");
  for_each_xml_attribute(text, [&](const XmlAttribute& a) {
    if (names_something(a.name)) return;
    const std::string bad = non_finite_token(a.value);
    if (!bad.empty())
      fail("robot.description", source,
           fmt::format("line {}: <{} {}=\"{}\">: '{}' is not a finite number", a.line, a.element, a.name,
                       one_line(a.value, 60), one_line(bad, 30)));
    // A negative mass: MuJoCo's URDF reader takes it as 0 without a word.
    const bool mass = a.name == "mass" || (a.element == "mass" && a.name == "value");
    const std::optional<double> x = mass ? parse_finite_number(a.value) : std::nullopt;
    if (x && *x < 0)
      fail("robot.description", source,
           fmt::format("line {}: <{} {}=\"{}\">: a mass must be >= 0 kg", a.line, a.element, a.name,
                       one_line(a.value, 60)));
  });
}

/// Refuses a compiled body whose mass or inertia is negative (URDF's <mass value="-1"/> compiles),
/// naming the body (a URDF link).
void check_inertials(const mjModel* m, int b, const std::string& source) {
  const std::string name = name_of(m, mjOBJ_BODY, b);
  if (!(m->body_mass[b] >= 0))
    fail("robot.description", source,
         fmt::format("body '{}' has mass {} kg; allowed: a finite mass >= 0", one_line(name, 60), m->body_mass[b]));
  for (int i = 0; i < 3; ++i)
    if (!(m->body_inertia[3 * b + i] >= 0))
      fail("robot.description", source,
           fmt::format("body '{}' has a principal moment of inertia {} kg m^2; allowed: finite moments >= 0",
                       one_line(name, 60), m->body_inertia[3 * b + i]));
}

/// The directory of the description file (its meshes' paths are relative to it); "" for text
/// that is no file.
std::string description_dir(const std::string& source) {
  std::error_code ec;
  return std::filesystem::is_regular_file(source, ec) ? std::filesystem::path(source).parent_path().string()
                                                      : std::string();
}

/// flexgait's extension of URDF: <dynamics armature="..."/> in a <joint>, the rotor's reflected
/// inertia [kg m^2] (MuJoCo's URDF reader passes it over), by joint name.
std::map<std::string, double> armature_extension(const std::string& text, const std::string& source) {
  std::map<std::string, double> out;
  std::string joint;
  for_each_xml_attribute(text, [&](const XmlAttribute& a) {
    if (a.element == "joint" && a.name == "name") joint = std::string(a.value);
    if (a.element != "dynamics" || a.name != "armature") return;
    const std::optional<double> x = parse_finite_number(a.value);
    if (!x || *x < 0)
      fail("robot.description", source,
           fmt::format("line {}: <dynamics armature=\"{}\">: allowed: a number >= 0 kg m^2", a.line,
                       one_line(a.value, 60)));
    out[joint] = *x;
  });
  return out;
}

/// Compiles description text through MuJoCo's virtual file system (MJCF written for MuJoCo 3
/// translated first, its warnings appended to `warnings`, the names of the meshes whose files are
/// missing to `missing_meshes`, which `missing` decides the fate of).
ModelPtr compile(const std::string& text, const std::string& format, const std::string& source,
                 std::vector<std::string>& warnings, std::vector<std::string>* missing_meshes = nullptr,
                 MissingMeshes missing = MissingMeshes::kDrop) {
  check_text(text, source);
  std::string xml =
      format == "xml" ? translate_mujoco3(text, warnings, description_dir(source), missing, missing_meshes) : text;
  if (format == "urdf") {
    // Keep bodies on fixed joints (the feet, sensor frames): MuJoCo fuses them by default for URDF.
    const auto robot = xml.find("<robot");
    const auto close = robot == std::string::npos ? robot : xml.find('>', robot);
    if (close == std::string::npos) fail("robot.description", source, "not a URDF file (no <robot> element)");
    const std::size_t at = xml[close - 1] == '/' ? close - 1 : close + 1;
    xml.insert(at, R"(<mujoco><compiler fusestatic="false" discardvisual="true" strippath="false"/></mujoco>)");
  }
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const std::string name = "flexgait_description." + format;
  if (mj_makeEmptyFileVFS(vfs.get(), name.c_str(), static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("MuJoCo VFS: cannot create the description file");
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name.c_str())], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = mj_loadXML(name.c_str(), vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (m == nullptr) fail("robot.description", source, std::string("MuJoCo cannot load it: ") + one_line(error));
  return {m, mj_deleteModel};
}

std::array<double, 3> vec3(const mjtNum* v) {
  return {v[0], v[1], v[2]};
}
std::array<double, 4> vec4(const mjtNum* v) {
  return {v[0], v[1], v[2], v[3]};
}

const char* geom_type_name(int type) {
  switch (type) {
    case mjGEOM_PLANE:
      return "plane";
    case mjGEOM_SPHERE:
      return "sphere";
    case mjGEOM_CAPSULE:
      return "capsule";
    case mjGEOM_ELLIPSOID:
      return "ellipsoid";
    case mjGEOM_CYLINDER:
      return "cylinder";
    case mjGEOM_BOX:
      return "box";
    default:
      return nullptr;  // meshes and height fields: not carried into the twin
  }
}

/// "a b c" → numbers; throws naming the key unless there are exactly `n` finite ones.
std::vector<double> numbers(const std::string& key, const std::string& text, std::size_t n) {
  std::istringstream in(text);
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  if (!in.eof() || v.size() != n || !std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }))
    fail(key, text, fmt::format("expected {} numbers separated by spaces", n));
  return v;
}

bool is_ancestor(const mjModel* m, int ancestor, int body) {
  for (int b = body; b > 0; b = m->body_parentid[b])
    if (b == ancestor) return true;
  return ancestor == 0;
}

/// The magnitude of the file's gravity (MuJoCo's `<option gravity>`, default 0 0 −9.81; a URDF states
/// none) [m/s^2]. The controller's models and the twin both take it; it must point along −z.
double file_gravity(const mjModel* m, const std::string& source) {
  const double gx = m->opt.gravity[0], gy = m->opt.gravity[1], gz = m->opt.gravity[2];
  if (gx != 0 || gy != 0 || !(gz < 0))
    fail("robot.description", source,
         fmt::format("its gravity ({} {} {}) must point straight down (0 0 -g with g > 0): a sloped floor is "
                     "terrain.kind=ramp, not a tilted gravity",
                     gx, gy, gz));
  return -gz;
}

/// The largest torque the file's actuators on hinge `joint` can apply (LoadedJoint::force_limit; MuJoCo's
/// actuator model: torque = gear × force, force clamped to forcerange, a motor's force = gain × control
/// clamped to ctrlrange); 0 when none of them is limited.
double actuator_force_limit(const mjModel* m, int joint) {
  double limit = 0;
  for (int a = 0; a < m->nu; ++a) {
    if (m->actuator_trntype[a] != mjTRN_JOINT || m->actuator_trnid[2 * a] != joint) continue;
    const double gear = std::abs(m->actuator_gear[6 * a]);
    double force = 0;
    if (m->actuator_forcelimited[a]) {
      force = std::max(std::abs(m->actuator_forcerange[2 * a]), std::abs(m->actuator_forcerange[2 * a + 1]));
    } else if (m->actuator_ctrllimited[a] && m->actuator_gaintype[a] == mjGAIN_FIXED &&
               m->actuator_biastype[a] == mjBIAS_NONE) {
      force = std::abs(m->actuator_gainprm[mjNGAIN * a]) *
              std::max(std::abs(m->actuator_ctrlrange[2 * a]), std::abs(m->actuator_ctrlrange[2 * a + 1]));
    }
    limit = std::max(limit, gear * force);
  }
  return limit;
}

/// The points of geom `g` (in its body's frame) that can rest on a floor below the body: a sphere's
/// or an ellipsoid's lowest point, a capsule's end spheres' lowest points, a box's eight corners, a
/// cylinder's two rims (64 points each, the four extreme ones among them), a mesh's vertices (the
/// collision shape is their convex hull). Nothing for a plane or a height field. With `frame` (a
/// frame's quaternion in the body's), the points in that frame and "below" along its −z.
std::vector<std::array<double, 3>> floor_points(const mjModel* m, int g, const mjtNum* frame = nullptr) {
  std::vector<std::array<double, 3>> out;
  const mjtNum* c = m->geom_pos + 3 * g;
  const mjtNum* q = m->geom_quat + 4 * g;
  const mjtNum* h = m->geom_size + 3 * g;
  mjtNum c_in[3], q_in[4];
  if (frame != nullptr) {  // the geom's pose in the frame: c' = F⁻¹ c, q' = F⁻¹ q
    mjtNum inverse[4];
    mju_negQuat(inverse, frame);
    mju_rotVecQuat(c_in, c, inverse);
    mju_mulQuat(q_in, inverse, q);
    c = c_in;
    q = q_in;
  }
  auto at = [&](double x, double y, double z, double drop) {
    const mjtNum local[3] = {x, y, z};
    mjtNum v[3];
    mju_rotVecQuat(v, local, q);
    out.push_back({c[0] + v[0], c[1] + v[1], c[2] + v[2] - drop});
  };
  switch (m->geom_type[g]) {
    case mjGEOM_SPHERE:
      at(0, 0, 0, h[0]);
      break;
    case mjGEOM_CAPSULE:
      at(0, 0, h[1], h[0]);
      at(0, 0, -h[1], h[0]);
      break;
    case mjGEOM_ELLIPSOID: {
      // The lowest point of {x : x' S^-1 x = 1}, S = R diag(a^2) R': x = -S e_z / sqrt(e_z' S e_z).
      mjtNum R[9];
      mju_quat2Mat(R, q);
      double s[3] = {0, 0, 0};  // S e_z
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) s[i] += R[3 * i + k] * h[k] * h[k] * R[3 * 2 + k];
      const double n = std::sqrt(s[2]);
      out.push_back({c[0] - s[0] / n, c[1] - s[1] / n, c[2] - s[2] / n});
      break;
    }
    case mjGEOM_BOX:
      for (double x : {-1.0, 1.0})
        for (double y : {-1.0, 1.0})
          for (double z : {-1.0, 1.0}) at(x * h[0], y * h[1], z * h[2], 0);
      break;
    case mjGEOM_CYLINDER:
      for (int i = 0; i < 64; ++i) {
        const double a = 2 * std::numbers::pi * i / 64;
        for (double z : {-1.0, 1.0}) at(h[0] * std::cos(a), h[0] * std::sin(a), z * h[1], 0);
      }
      break;
    case mjGEOM_MESH: {
      const int mesh = m->geom_dataid[g];
      for (int v = m->mesh_vertadr[mesh]; v < m->mesh_vertadr[mesh] + m->mesh_vertnum[mesh]; ++v)
        at(m->mesh_vert[3 * v], m->mesh_vert[3 * v + 1], m->mesh_vert[3 * v + 2], 0);
      break;
    }
    default:
      break;
  }
  return out;
}

/// Points within this height of a foot's lowest point rest on the floor with it: the contact's own
/// penetration under a robot's weight is of this order, and 6-digit printed numbers lie far inside.
constexpr double kSoleBand = 1e-3;  // [m]

/// The sole as the foot's contact geoms make it (Sole::hull): every geom of foot body `b` that
/// touches the twin's floor (contype or conaffinity bit 1), its floor points; those within
/// kSoleBand of the lowest make the hull, whose bounding rectangle is the sole rectangle.
/// `carried`: each model geom's index among its body's loaded geoms, −1 when not carried. False
/// when the foot has no such geom.
bool sole_from_contact_geoms(const mjModel* m, int b, const std::vector<int>& carried, humanoid::Sole& sole) {
  struct Point {
    std::array<double, 3> x;
    int geom;
  };
  std::vector<Point> points;
  double lowest = INFINITY;
  const bool turned = sole.has_own_frame();
  for (int g = m->body_geomadr[b]; g >= 0 && g < m->body_geomadr[b] + m->body_geomnum[b]; ++g) {
    if (!((m->geom_contype[g] & 1) || (m->geom_conaffinity[g] & 1))) continue;
    for (const auto& x : floor_points(m, g, turned ? sole.quat.data() : nullptr)) {
      points.push_back({x, g});
      lowest = std::min(lowest, x[2]);
    }
  }
  if (points.empty()) return false;
  std::vector<std::array<double, 2>> on_plane;
  std::vector<int> geoms;  // model ids, ascending
  for (const Point& p : points) {
    if (p.x[2] > lowest + kSoleBand) continue;
    on_plane.push_back({p.x[0], p.x[1]});
    if (std::find(geoms.begin(), geoms.end(), p.geom) == geoms.end()) geoms.push_back(p.geom);
  }
  sole.hull = humanoid::convex_hull(std::move(on_plane));
  std::array<double, 2> lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (const auto& p : sole.hull)
    for (int i = 0; i < 2; ++i) {
      lo[static_cast<std::size_t>(i)] = std::min(lo[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(i)]);
      hi[static_cast<std::size_t>(i)] = std::max(hi[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(i)]);
    }
  sole.center = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), lowest};
  if (turned) {  // the centre in the foot body's frame
    mjtNum in_body[3];
    mju_rotVecQuat(in_body, sole.center.data(), sole.quat.data());
    sole.center = {in_body[0], in_body[1], in_body[2]};
  }
  sole.length = hi[0] - lo[0];
  sole.width = hi[1] - lo[1];
  sole.hull_in_twin = true;
  for (const int g : geoms) {
    const int k = carried[static_cast<std::size_t>(g)];
    if (k < 0)
      sole.hull_in_twin = false;  // a mesh: the twin does not carry it
    else
      sole.hull_geoms.push_back(k);
  }
  return true;
}

/// Body b's orientation in the frame of its ancestor `root` at zero joint angles (w x y z).
std::array<double, 4> zero_pose_quat(const mjModel* m, int b, int root) {
  std::array<double, 4> q{1, 0, 0, 0};
  for (int x = b; x != root; x = m->body_parentid[x]) {
    std::array<double, 4> t{};
    mju_mulQuat(t.data(), m->body_quat + 4 * x, q.data());
    q = t;
  }
  return q;
}

/// The sole's frame of a foot body turned at zero joint angles (Sole::quat), given the body's
/// orientation `foot` in the root's frame there: the contact box with the lowest point in the
/// root's frame; its axis nearest the vertical is the sole's z (pointing up), of the other two the
/// one nearest the root's x is its x (pointing forward). Without a contact box, the root's axes.
std::array<double, 4> turned_sole_frame(const mjModel* m, int b, const std::array<double, 4>& foot) {
  mjtNum Rf[9];
  mju_quat2Mat(Rf, foot.data());
  auto in_root = [&](const std::array<double, 3>& v, int i) {
    return Rf[3 * i] * v[0] + Rf[3 * i + 1] * v[1] + Rf[3 * i + 2] * v[2];
  };
  int box = -1;
  double lowest = INFINITY;
  for (int g = m->body_geomadr[b]; g >= 0 && g < m->body_geomadr[b] + m->body_geomnum[b]; ++g) {
    if (m->geom_type[g] != mjGEOM_BOX || !((m->geom_contype[g] & 1) || (m->geom_conaffinity[g] & 1))) continue;
    for (const auto& x : floor_points(m, g))
      if (in_root(x, 2) < lowest) lowest = in_root(x, 2), box = g;
  }
  std::array<double, 9> S{1, 0, 0, 0, 1, 0, 0, 0, 1};  // the sole's axes in the root's frame, as columns
  if (box >= 0) {
    mjtNum Rg[9], A[9];  // the box's axes in the body's frame, then in the root's
    mju_quat2Mat(Rg, m->geom_quat + 4 * box);
    mju_mulMatMat(A, Rf, Rg, 3, 3, 3);
    auto column = [&](int k) { return std::array<double, 3>{A[k], A[3 + k], A[6 + k]}; };
    int up = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(A[6 + k]) > std::abs(A[6 + up])) up = k;
    int forward = up == 0 ? 1 : 0;
    for (int k = 0; k < 3; ++k)
      if (k != up && std::abs(A[k]) > std::abs(A[forward])) forward = k;
    std::array<double, 3> z = column(up), x = column(forward);
    if (z[2] < 0) z = {-z[0], -z[1], -z[2]};
    if (x[0] < 0) x = {-x[0], -x[1], -x[2]};
    const std::array<double, 3> y{z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]};
    S = {x[0], y[0], z[0], x[1], y[1], z[1], x[2], y[2], z[2]};
  }
  mjtNum RfT[9], R[9];  // the sole's axes in the body's frame: Rfᵀ S
  mju_transpose(RfT, Rf, 3, 3);
  mju_mulMatMat(R, RfT, S.data(), 3, 3, 3);
  std::array<double, 4> q{};
  mju_mat2Quat(q.data(), R);
  return q;
}

/// Refuses a foot whose sole the mapping does not give when one of its colliding geoms showed a
/// mesh whose file is missing (its sole cannot be made from it), naming the mesh and the geom: the
/// text compiled again with the missing meshes as placeholders tells which geoms showed them and
/// whether their classes make them collide.
void check_foot_meshes(const std::string& text, const std::string& source, const std::vector<std::string>& missing,
                       const humanoid::FootMapping& f, const std::string& prefix) {
  std::vector<std::string> ignored;
  ModelPtr m(nullptr, mj_deleteModel);
  try {
    m = compile(text, "xml", source, ignored, nullptr, MissingMeshes::kPlaceholder);
  } catch (const ConfigError&) {
    return;  // (the placeholders do not compile: nothing to tell beyond the dropped meshes' warning)
  }
  const int b = mj_name2id(m.get(), mjOBJ_BODY, f.body.c_str());
  for (int g = b < 0 ? 0 : m->body_geomadr[b]; b >= 0 && g < m->body_geomadr[b] + m->body_geomnum[b]; ++g) {
    if (m->geom_type[g] != mjGEOM_MESH || !((m->geom_contype[g] & 1) || (m->geom_conaffinity[g] & 1))) continue;
    const std::string mesh = name_of(m.get(), mjOBJ_MESH, m->geom_dataid[g]);
    if (std::find(missing.begin(), missing.end(), mesh) == missing.end()) continue;
    const std::string geom = name_of(m.get(), mjOBJ_GEOM, g);
    fail(prefix + ".sole_size", f.sole_size,
         fmt::format("the file of mesh '{}', which the contact geom '{}' of the foot {} shows, is missing: the sole "
                     "cannot be made from it; give {}.sole_size and .sole_center (or put the mesh file beside {})",
                     mesh, geom.empty() ? fmt::format("#{}", g - m->body_geomadr[b]) : geom, f.body, prefix, source));
  }
}

/// Each degree of freedom's link-side inertia: the joint-space mass matrix's diagonal at the file's zero angles (the
/// composite rigid body inertia below the joint about its axis, Featherstone 2008, ch. 6), less the armature [kg m^2].
std::vector<double> link_side_inertia(const mjModel* m) {
  const DataPtr d(mj_makeData(m), mj_deleteData);
  mj_forward(m, d.get());
  std::vector<double> out(static_cast<std::size_t>(m->nv), 0.0);
  for (int v = 0; v < m->nv; ++v) out[static_cast<std::size_t>(v)] = d->qM[m->dof_Madr[v]] - m->dof_armature[v];
  return out;
}

/// Refuses a robot whose colliding geoms touch each other at zero joint angles (the twin would
/// start, and stand, in contact with itself), naming the first pair for robot.exclude_contacts.
void check_self_contacts(const humanoid::LoadedRobot& robot, const std::string& exclude) {
  const ModelPtr twin(load_mjcf(twin_mjcf(robot, humanoid::RobotParams{}, PlantParams{})), mj_deleteModel);
  const DataPtr data(mj_makeData(twin.get()), mj_deleteData);
  const mjData* d = data.get();
  mj_forward(twin.get(), data.get());
  const int floor = mj_name2id(twin.get(), mjOBJ_GEOM, "floor");
  std::string pair;
  for (int c = 0; c < d->ncon && pair.empty(); ++c) {
    const mjContact& con = d->contact[c];
    if (con.geom1 == floor || con.geom2 == floor) continue;
    pair = name_of(twin.get(), mjOBJ_BODY, twin->geom_bodyid[con.geom1]) + ":" +
           name_of(twin.get(), mjOBJ_BODY, twin->geom_bodyid[con.geom2]);
  }
  if (!pair.empty())
    fail("robot.exclude_contacts", exclude,
         fmt::format("the bodies {} collide at zero joint angles; exclude the pair (robot.exclude_contacts={}) or "
                     "give their geoms no contact",
                     pair, pair));
}

}  // namespace

humanoid::LoadedRobot load_robot_text(const std::string& text, const std::string& format, const std::string& source,
                                      const humanoid::RobotDescriptionParams& params) {
  humanoid::LoadedRobot out;
  out.source = source;
  std::vector<std::string> missing_meshes;
  const ModelPtr model = compile(text, format, source, out.warnings, &missing_meshes);
  const bool ranges_as_user = format == "xml" && joint_force_ranges_as_user(text);
  const std::map<std::string, double> urdf_armature =
      format == "urdf" ? armature_extension(text, source) : std::map<std::string, double>{};
  const mjModel* m = model.get();
  for (int b = 1; b < m->nbody; ++b) check_inertials(m, b, source);

  // The mapped joints (hinges), then the root: the world's child that holds them.
  // A role left at the builtin's name that the file does not have is unmapped: the waist is then
  // rigid, a leg role is an error listing every unmapped one (a loaded robot has no defaults).
  std::array<int, humanoid::kJoints> jid{};
  std::string unmapped;
  int first_unmapped = -1;
  for (int j = 0; j < humanoid::kJoints; ++j) {
    const std::string& name = params.joints[j];
    if (name == humanoid::kJointNames[j] && mj_name2id(m, mjOBJ_JOINT, name.c_str()) < 0 && j != humanoid::kWaistYaw) {
      unmapped += (unmapped.empty() ? "" : ", ") + name;
      if (first_unmapped < 0) first_unmapped = j;
    }
  }
  if (first_unmapped >= 0)
    fail("robot.joints." + std::string(humanoid::kJointNames[first_unmapped]), params.joints[first_unmapped],
         fmt::format("{} has no joint of that name; map every leg role to a joint of the file (unmapped: {})", source,
                     unmapped));
  for (int j = 0; j < humanoid::kJoints; ++j) {
    const std::string key = "robot.joints." + std::string(humanoid::kJointNames[j]);
    const std::string& name = params.joints[j];
    // A trunk without a waist (none, or left unmapped): the chest is rigid on the pelvis.
    if (j == humanoid::kWaistYaw &&
        (name == "none" || (name == humanoid::kJointNames[j] && mj_name2id(m, mjOBJ_JOINT, name.c_str()) < 0))) {
      jid[j] = -1;
      continue;
    }
    jid[j] = mj_name2id(m, mjOBJ_JOINT, name.c_str());
    if (jid[j] < 0) fail(key, name, fmt::format("no joint of that name in {}", source));
    if (m->jnt_type[jid[j]] != mjJNT_HINGE) fail(key, name, "not a hinge (revolute) joint");
    for (int i = 0; i < j; ++i)
      if (jid[i] == jid[j]) fail(key, name, fmt::format("also mapped to robot.joints.{}", humanoid::kJointNames[i]));
  }
  const int root = m->body_rootid[m->jnt_bodyid[jid[humanoid::kLeftHipYaw]]];
  for (int j = 0; j < humanoid::kJoints; ++j)
    if (jid[j] >= 0 && m->body_rootid[m->jnt_bodyid[jid[j]]] != root)
      fail("robot.joints." + std::string(humanoid::kJointNames[j]), params.joints[j],
           "not in the same body tree as the legs");

  const std::vector<double> link_inertia = link_side_inertia(m);
  // The root's subtree, parents before children (MuJoCo's body order is depth-first).
  std::vector<int> index(static_cast<std::size_t>(m->nbody), -1);
  std::vector<int> carried(static_cast<std::size_t>(m->ngeom), -1);  // model geom → index in its body's geoms
  for (int b = root; b < m->nbody; ++b) {
    if (b != root && (m->body_parentid[b] == 0 || index[static_cast<std::size_t>(m->body_parentid[b])] < 0)) continue;
    index[static_cast<std::size_t>(b)] = static_cast<int>(out.bodies.size());
    humanoid::LoadedBody body;
    body.name = name_of(m, mjOBJ_BODY, b);
    body.parent = b == root ? -1 : index[static_cast<std::size_t>(m->body_parentid[b])];
    body.pos = vec3(m->body_pos + 3 * b);
    body.quat = vec4(m->body_quat + 4 * b);
    body.mass = m->body_mass[b];
    body.ipos = vec3(m->body_ipos + 3 * b);
    body.iquat = vec4(m->body_iquat + 4 * b);
    body.inertia = vec3(m->body_inertia + 3 * b);
    for (int k = m->body_jntadr[b]; k >= 0 && k < m->body_jntadr[b] + m->body_jntnum[b]; ++k) {
      if (m->jnt_type[k] == mjJNT_FREE) continue;
      humanoid::LoadedJoint joint;
      joint.name = name_of(m, mjOBJ_JOINT, k);
      for (int j = 0; j < humanoid::kJoints; ++j)
        if (jid[j] == k) joint.mapped = j;
      joint.pos = vec3(m->jnt_pos + 3 * k);
      joint.axis = vec3(m->jnt_axis + 3 * k);
      joint.limited = m->jnt_limited[k] != 0;
      joint.range = {m->jnt_range[2 * k], m->jnt_range[2 * k + 1]};
      joint.armature = m->dof_armature[m->jnt_dofadr[k]];
      joint.frictionloss = m->dof_frictionloss[m->jnt_dofadr[k]];
      joint.damping = m->dof_damping[m->jnt_dofadr[k]];
      joint.link_inertia = link_inertia[static_cast<std::size_t>(m->jnt_dofadr[k])];
      if (const auto a = urdf_armature.find(joint.name); a != urdf_armature.end()) joint.armature = a->second;
      joint.force_limit = actuator_force_limit(m, k);
      if (ranges_as_user && m->nuser_jnt >= 2) {  // the joint's actuatorfrcrange clamps its actuators' sum
        const double range =
            std::max(std::abs(m->jnt_user[m->nuser_jnt * k]), std::abs(m->jnt_user[m->nuser_jnt * k + 1]));
        if (range > 0) joint.force_limit = joint.force_limit > 0 ? std::min(joint.force_limit, range) : range;
      }
      if (joint.mapped >= 0)
        out.joint[joint.mapped] = {static_cast<int>(out.bodies.size()), static_cast<int>(body.joints.size())};
      body.joints.push_back(joint);
    }
    for (int g = m->body_geomadr[b]; g >= 0 && g < m->body_geomadr[b] + m->body_geomnum[b]; ++g) {
      const char* type = geom_type_name(m->geom_type[g]);
      if (type == nullptr) continue;
      humanoid::LoadedGeom geom;
      geom.name = name_of(m, mjOBJ_GEOM, g);
      geom.type = type;
      geom.size = vec3(m->geom_size + 3 * g);
      geom.pos = vec3(m->geom_pos + 3 * g);
      geom.quat = vec4(m->geom_quat + 4 * g);
      geom.contype = m->geom_contype[g];
      geom.conaffinity = m->geom_conaffinity[g];
      geom.condim = m->geom_condim[g];
      geom.friction = vec3(m->geom_friction + 3 * g);
      geom.solref = {m->geom_solref[mjNREF * g], m->geom_solref[mjNREF * g + 1]};
      for (int i = 0; i < mjNIMP; ++i) geom.solimp[static_cast<std::size_t>(i)] = m->geom_solimp[mjNIMP * g + i];
      geom.margin = m->geom_margin[g];
      geom.gap = m->geom_gap[g];
      for (int i = 0; i < 4; ++i) geom.rgba[static_cast<std::size_t>(i)] = m->geom_rgba[4 * g + i];
      // The twin's own mark of a sole its foot's geoms make (an exported twin loaded back): made again.
      if ((geom.name == "l_sole" || geom.name == "r_sole") && geom.contype == 0 && geom.conaffinity == 0) continue;
      carried[static_cast<std::size_t>(g)] = static_cast<int>(body.geoms.size());
      body.geoms.push_back(geom);
    }
    out.bodies.push_back(std::move(body));
  }
  if (jid[humanoid::kWaistYaw] < 0) out.joint[humanoid::kWaistYaw] = {-1, -1};

  // The feet: six joints from the root to each foot, the leg's own, in order.
  for (int side = 0; side < 2; ++side) {
    const humanoid::FootMapping& f = params.feet[side];
    const std::string prefix = std::string("robot.feet.") + (side == 0 ? "left" : "right");
    const int b = mj_name2id(m, mjOBJ_BODY, f.body.c_str());
    if (b < 0) fail(prefix + ".body", f.body, fmt::format("no body of that name in {}", source));
    if (!is_ancestor(m, root, b) || b == root) fail(prefix + ".body", f.body, "not below the robot's root body");
    std::vector<int> path;  // joints from the root to the foot, in kinematic order
    for (int x = b; x != root; x = m->body_parentid[x])
      for (int k = m->body_jntadr[x] + m->body_jntnum[x] - 1; k >= m->body_jntadr[x] && m->body_jntnum[x] > 0; --k)
        if (m->jnt_type[k] != mjJNT_FREE) path.insert(path.begin(), k);
    // Joints between the root and the hips (a waist below the root): held rigid when unmapped;
    // the legs hang from the root in the controller's model, so a mapped waist cannot be there.
    auto leg_role = [&](int k) {
      for (int j = 0; j < humanoid::kJoints; ++j)
        if (jid[j] == k && j != humanoid::kWaistYaw) return true;
      return false;
    };
    while (!path.empty() && !leg_role(path.front())) {
      if (path.front() == jid[humanoid::kWaistYaw])
        fail("robot.joints.waist_yaw", params.joints[humanoid::kWaistYaw],
             fmt::format("this joint is between the root and the leg to {}; flexgait's legs hang from the root: map "
                         "robot.joints.waist_yaw=none to hold it rigid",
                         f.body));
      path.erase(path.begin());
    }
    if (path.size() != humanoid::kLegJoints)
      fail(prefix + ".body", f.body,
           fmt::format("the leg from the root to this foot has {} joints; flexgait's legs have {}", path.size(),
                       humanoid::kLegJoints));
    // The leg's joints by role, whatever their order within the hip and within the ankle.
    const int j0 = humanoid::leg_first_joint(side);
    for (int i = 0; i < humanoid::kLegJoints; ++i) {
      const int k = path[static_cast<std::size_t>(i)];
      int role = -1;
      for (int j = 0; j < humanoid::kJoints; ++j)
        if (jid[j] == k) role = j;
      if (role < 0 || !humanoid::in_leg(role, side)) {
        // A joint of the other leg's roles, or of none: name the role that is missing here.
        int missing = j0;
        for (int r = 0; r < humanoid::kLegJoints; ++r)
          if (std::find(path.begin(), path.end(), jid[j0 + r]) == path.end()) missing = j0 + r;
        if (role >= 0)
          fail("robot.joints." + std::string(humanoid::kJointNames[role]), params.joints[role],
               fmt::format("this joint is on the leg to {} (the {} foot); map the {} leg's roles to that leg's joints",
                           f.body, side == 0 ? "left" : "right", side == 0 ? "right" : "left"));
        fail("robot.joints." + std::string(humanoid::kJointNames[missing]), params.joints[missing],
             fmt::format("not on the leg to {}, whose joint {} is '{}' (mapped to no role)", f.body, i + 1,
                         name_of(m, mjOBJ_JOINT, k)));
      }
      const int r = role - j0;
      const int group = r < 3 ? 0 : (r == 3 ? 1 : 2), at = i < 3 ? 0 : (i == 3 ? 1 : 2);
      if (group != at)
        fail("robot.joints." + std::string(humanoid::kJointNames[role]), params.joints[role],
             fmt::format("joint {} of the leg to {}; a leg's joints from the root are the three hip joints (any "
                         "order), the knee, then the two ankle joints (any order)",
                         i + 1, f.body));
      out.leg_order[side][static_cast<std::size_t>(i)] = r;
    }
    out.foot[side] = index[static_cast<std::size_t>(b)];
    humanoid::Sole& sole = out.sole[side];
    // A foot body turned from the root at zero joint angles (frames that follow the joint axes): the
    // sole has its own frame (Sole::quat).
    const std::array<double, 4> foot_quat = zero_pose_quat(m, b, root);
    const bool turned = 2 * std::acos(std::min(1.0, std::abs(foot_quat[0]))) >= humanoid::kLevelFootTilt;
    // (the builtin's sole name left as it is, and the file has no such geom: no sole geom named)
    const bool builtin_name =
        f.sole_geom == humanoid::RobotDescriptionParams{}.feet[static_cast<std::size_t>(side)].sole_geom &&
        mj_name2id(m, mjOBJ_GEOM, f.sole_geom.c_str()) < 0;
    if (f.sole_geom != "none" && !builtin_name) {
      const int g = mj_name2id(m, mjOBJ_GEOM, f.sole_geom.c_str());
      if (g < 0 || m->geom_bodyid[g] != b)
        fail(prefix + ".sole_geom", f.sole_geom, fmt::format("no geom of that name on body {}", f.body));
      if (m->geom_type[g] != mjGEOM_BOX) fail(prefix + ".sole_geom", f.sole_geom, "not a box");
      const mjtNum* q = m->geom_quat + 4 * g;
      if (std::abs(q[0]) < 1 - 1e-12) fail(prefix + ".sole_geom", f.sole_geom, "its axes are not the foot body's");
      const humanoid::LoadedBody& foot = out.bodies[static_cast<std::size_t>(out.foot[side])];
      for (std::size_t i = 0; i < foot.geoms.size(); ++i)
        if (foot.geoms[i].name == f.sole_geom) sole.geom = static_cast<int>(i);
      const mjtNum* p = m->geom_pos + 3 * g;
      const mjtNum* h = m->geom_size + 3 * g;
      sole.center = {p[0], p[1], p[2] - h[2]};
      sole.length = 2 * h[0];
      sole.width = 2 * h[1];
    } else if (f.sole_size != "none") {
      const std::vector<double> size = numbers(prefix + ".sole_size", f.sole_size, 2);
      if (!(size[0] > 0 && size[1] > 0)) fail(prefix + ".sole_size", f.sole_size, "length and width must be > 0");
      const std::vector<double> c = numbers(prefix + ".sole_center", f.sole_center, 3);
      sole.center = {c[0], c[1], c[2]};
      sole.length = size[0];
      sole.width = size[1];
      if (turned) mju_negQuat(sole.quat.data(), foot_quat.data());  // the root's axes at zero angles
    } else {
      if (turned) sole.quat = turned_sole_frame(m, b, foot_quat);
      // The sole from the foot's contact geoms (a foot whose collision mesh is missing cannot have it).
      if (!missing_meshes.empty() && format == "xml") check_foot_meshes(text, source, missing_meshes, f, prefix);
      if (!sole_from_contact_geoms(m, b, carried, sole))
        fail(prefix + ".sole_size", f.sole_size,
             fmt::format("the foot {} has no contact geom to make its sole; give {}.sole_size and .sole_center, or "
                         "name a box geom in {}.sole_geom",
                         f.body, prefix, prefix));
      if (!(sole.length > 0 && sole.width > 0))
        fail(prefix + ".sole_size", f.sole_size,
             fmt::format("the contact geoms of the foot {} touch the floor along a line or at a point ({} x {} m); "
                         "give {}.sole_size and .sole_center",
                         f.body, sole.length, sole.width, prefix));
    }
  }
  if (params.imu_body != "root") {
    const int b = mj_name2id(m, mjOBJ_BODY, params.imu_body.c_str());
    if (b < 0 || index[static_cast<std::size_t>(b)] < 0)
      fail("robot.imu_body", params.imu_body, fmt::format("no body of that name in the robot of {}", source));
    out.imu_body = index[static_cast<std::size_t>(b)];
  }
  if (params.exclude_contacts != "none") {
    std::istringstream in(params.exclude_contacts);
    for (std::string pair; std::getline(in, pair, ',');) {
      const auto colon = pair.find(':');
      std::array<int, 2> ids{-1, -1};
      if (colon != std::string::npos) {
        const std::string a = pair.substr(0, colon), b = pair.substr(colon + 1);
        const int ia = mj_name2id(m, mjOBJ_BODY, a.c_str()), ib = mj_name2id(m, mjOBJ_BODY, b.c_str());
        if (ia >= 0 && ib >= 0) ids = {index[static_cast<std::size_t>(ia)], index[static_cast<std::size_t>(ib)]};
      }
      if (ids[0] < 0 || ids[1] < 0)
        fail("robot.exclude_contacts", params.exclude_contacts,
             fmt::format("'{}' is not a pair body:body of the robot", pair));
      out.exclude.push_back(ids);
    }
  }
  // The file's own <contact><exclude> pairs (MuJoCo 2.2.2's signature: (body1 + 1) << 16 | (body2 + 1)).
  for (int e = 0; e < m->nexclude; ++e) {
    const int a = (m->exclude_signature[e] >> 16) - 1, b = (m->exclude_signature[e] & 0xFFFF) - 1;
    if (a < 0 || b < 0 || a >= m->nbody || b >= m->nbody) continue;
    const std::array<int, 2> ids{index[static_cast<std::size_t>(a)], index[static_cast<std::size_t>(b)]};
    if (ids[0] >= 0 && ids[1] >= 0 && std::find(out.exclude.begin(), out.exclude.end(), ids) == out.exclude.end())
      out.exclude.push_back(ids);
  }
  check_self_contacts(out, params.exclude_contacts);
  out.gravity = file_gravity(m, source);
  return out;
}

humanoid::LoadedRobot load_robot(const humanoid::RobotDescriptionParams& params) {
  const std::string& path = params.description;
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext != ".xml" && ext != ".urdf")
    fail("robot.description", path, "allowed: builtin, or a path ending in .xml (MJCF) or .urdf (URDF)");
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (st.type() == std::filesystem::file_type::not_found) fail("robot.description", path, "no such file");
  if (!std::filesystem::is_regular_file(st))
    fail("robot.description", path, "not a regular file (a directory, FIFO, socket or device)");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("robot.description", path, "cannot read the file");
  std::string text(kMaxDescriptionBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) fail("robot.description", path, "cannot read the file");
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxDescriptionBytes)
    fail("robot.description", path,
         fmt::format("larger than {} bytes; a robot description is at most a few megabytes (meshes are separate files)",
                     kMaxDescriptionBytes));
  humanoid::LoadedRobot robot = load_robot_text(text, ext.substr(1), path, params);
  for (const std::string& w : robot.warnings)
    fmt::print(stderr, "warning: robot.description {}: {}\n", one_line(path), w);
  return robot;
}

}  // namespace flexgait::twin
