#include "flexgait/twin/robot_loader.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

#include "flexgait/core/text.hpp"
#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/twin_mjcf.hpp"

namespace flexgait::humanoid {
namespace {

using ModelPtr = std::unique_ptr<mjModel, void (*)(mjModel*)>;

[[noreturn]] void fail(const std::string& key, const std::string& value, const std::string& why) {
  throw ConfigError(key, fmt::format("key '{}' = '{}': {}", key, one_line(value), why));
}

/// Compiles description text through MuJoCo's virtual file system.
ModelPtr compile(const std::string& text, const std::string& format, const std::string& source) {
  std::string xml = text;
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

std::string name_of(const mjModel* m, mjtObj type, int id) {
  const char* n = mj_id2name(m, type, id);
  return n ? n : "";
}

std::array<double, 3> vec3(const mjtNum* v) { return {v[0], v[1], v[2]}; }
std::array<double, 4> vec4(const mjtNum* v) { return {v[0], v[1], v[2], v[3]}; }

const char* geom_type_name(int type) {
  switch (type) {
    case mjGEOM_PLANE: return "plane";
    case mjGEOM_SPHERE: return "sphere";
    case mjGEOM_CAPSULE: return "capsule";
    case mjGEOM_ELLIPSOID: return "ellipsoid";
    case mjGEOM_CYLINDER: return "cylinder";
    case mjGEOM_BOX: return "box";
    default: return nullptr;  // meshes and height fields: not carried into the twin
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

/// Refuses a robot whose colliding geoms touch each other at zero joint angles (the twin would
/// start, and stand, in contact with itself), naming the first pair for robot.exclude_contacts.
void check_self_contacts(const LoadedRobot& robot, const std::string& exclude) {
  const ModelPtr twin(load_mjcf(twin_mjcf(robot, RobotParams{}, PlantParams{})), mj_deleteModel);
  mjData* d = mj_makeData(twin.get());
  mj_forward(twin.get(), d);
  const int floor = mj_name2id(twin.get(), mjOBJ_GEOM, "floor");
  std::string pair;
  for (int c = 0; c < d->ncon && pair.empty(); ++c) {
    const mjContact& con = d->contact[c];
    if (con.geom1 == floor || con.geom2 == floor) continue;
    pair = name_of(twin.get(), mjOBJ_BODY, twin->geom_bodyid[con.geom1]) + ":" +
           name_of(twin.get(), mjOBJ_BODY, twin->geom_bodyid[con.geom2]);
  }
  mj_deleteData(d);
  if (!pair.empty())
    fail("robot.exclude_contacts", exclude,
         fmt::format("the bodies {} collide at zero joint angles; exclude the pair (robot.exclude_contacts={}) or "
                     "give their geoms no contact", pair, pair));
}

}  // namespace

LoadedRobot load_robot_text(const std::string& text, const std::string& format, const std::string& source,
                            const RobotDescriptionParams& params) {
  const ModelPtr model = compile(text, format, source);
  const mjModel* m = model.get();
  LoadedRobot out;
  out.source = source;

  // The mapped joints (hinges), then the root: the world's child that holds them.
  std::array<int, kJoints> jid{};
  for (int j = 0; j < kJoints; ++j) {
    const std::string key = "robot.joints." + std::string(kJointNames[j]);
    const std::string& name = params.joints[j];
    if (j == kWaistYaw && name == "none") {  // a trunk without a waist: the chest is rigid on the pelvis
      jid[j] = -1;
      continue;
    }
    jid[j] = mj_name2id(m, mjOBJ_JOINT, name.c_str());
    if (jid[j] < 0) fail(key, name, fmt::format("no joint of that name in {}", source));
    if (m->jnt_type[jid[j]] != mjJNT_HINGE) fail(key, name, "not a hinge (revolute) joint");
    for (int i = 0; i < j; ++i)
      if (jid[i] == jid[j]) fail(key, name, fmt::format("also mapped to robot.joints.{}", kJointNames[i]));
  }
  const int root = m->body_rootid[m->jnt_bodyid[jid[kLeftHipYaw]]];
  for (int j = 0; j < kJoints; ++j)
    if (jid[j] >= 0 && m->body_rootid[m->jnt_bodyid[jid[j]]] != root)
      fail("robot.joints." + std::string(kJointNames[j]), params.joints[j], "not in the same body tree as the legs");

  // The root's subtree, parents before children (MuJoCo's body order is depth-first).
  std::vector<int> index(static_cast<std::size_t>(m->nbody), -1);
  for (int b = root; b < m->nbody; ++b) {
    if (b != root && (m->body_parentid[b] == 0 || index[static_cast<std::size_t>(m->body_parentid[b])] < 0)) continue;
    index[static_cast<std::size_t>(b)] = static_cast<int>(out.bodies.size());
    LoadedBody body;
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
      LoadedJoint joint;
      joint.name = name_of(m, mjOBJ_JOINT, k);
      for (int j = 0; j < kJoints; ++j)
        if (jid[j] == k) joint.mapped = j;
      joint.pos = vec3(m->jnt_pos + 3 * k);
      joint.axis = vec3(m->jnt_axis + 3 * k);
      joint.limited = m->jnt_limited[k] != 0;
      joint.range = {m->jnt_range[2 * k], m->jnt_range[2 * k + 1]};
      joint.armature = m->dof_armature[m->jnt_dofadr[k]];
      joint.frictionloss = m->dof_frictionloss[m->jnt_dofadr[k]];
      if (joint.mapped >= 0) out.joint[joint.mapped] = {static_cast<int>(out.bodies.size()), static_cast<int>(body.joints.size())};
      body.joints.push_back(joint);
    }
    for (int g = m->body_geomadr[b]; g >= 0 && g < m->body_geomadr[b] + m->body_geomnum[b]; ++g) {
      const char* type = geom_type_name(m->geom_type[g]);
      if (type == nullptr) continue;
      LoadedGeom geom;
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
      body.geoms.push_back(geom);
    }
    out.bodies.push_back(std::move(body));
  }
  if (jid[kWaistYaw] < 0) out.joint[kWaistYaw] = {-1, -1};

  // The feet: six joints from the root to each foot, the leg's own, in order.
  for (int side = 0; side < 2; ++side) {
    const FootMapping& f = params.feet[side];
    const std::string prefix = std::string("robot.feet.") + (side == 0 ? "left" : "right");
    const int b = mj_name2id(m, mjOBJ_BODY, f.body.c_str());
    if (b < 0) fail(prefix + ".body", f.body, fmt::format("no body of that name in {}", source));
    if (!is_ancestor(m, root, b) || b == root) fail(prefix + ".body", f.body, "not below the robot's root body");
    std::vector<int> path;  // joints from the root to the foot, in kinematic order
    for (int x = b; x != root; x = m->body_parentid[x])
      for (int k = m->body_jntadr[x] + m->body_jntnum[x] - 1; k >= m->body_jntadr[x] && m->body_jntnum[x] > 0; --k)
        if (m->jnt_type[k] != mjJNT_FREE) path.insert(path.begin(), k);
    if (path.size() != kLegJoints)
      fail(prefix + ".body", f.body,
           fmt::format("the leg from the root to this foot has {} joints; flexgait's legs have {}", path.size(), kLegJoints));
    for (int i = 0; i < kLegJoints; ++i) {
      const int j = leg_first_joint(side) + i;
      if (path[static_cast<std::size_t>(i)] != jid[j])
        fail("robot.joints." + std::string(kJointNames[j]), params.joints[j],
             fmt::format("joint {} of the leg to {} is '{}'", i + 1, f.body, name_of(m, mjOBJ_JOINT, path[static_cast<std::size_t>(i)])));
    }
    out.foot[side] = index[static_cast<std::size_t>(b)];
    Sole& sole = out.sole[side];
    if (f.sole_geom != "none") {
      const int g = mj_name2id(m, mjOBJ_GEOM, f.sole_geom.c_str());
      if (g < 0 || m->geom_bodyid[g] != b)
        fail(prefix + ".sole_geom", f.sole_geom, fmt::format("no geom of that name on body {}", f.body));
      if (m->geom_type[g] != mjGEOM_BOX) fail(prefix + ".sole_geom", f.sole_geom, "not a box");
      const mjtNum* q = m->geom_quat + 4 * g;
      if (std::abs(q[0]) < 1 - 1e-12) fail(prefix + ".sole_geom", f.sole_geom, "its axes are not the foot body's");
      const LoadedBody& foot = out.bodies[static_cast<std::size_t>(out.foot[side])];
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
    } else {
      fail(prefix + ".sole_geom", f.sole_geom, fmt::format("the foot {} has no sole: name its box geom or give {}.sole_size", f.body, prefix));
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
        fail("robot.exclude_contacts", params.exclude_contacts, fmt::format("'{}' is not a pair body:body of the robot", pair));
      out.exclude.push_back(ids);
    }
  }
  check_self_contacts(out, params.exclude_contacts);
  return out;
}

LoadedRobot load_robot(const RobotDescriptionParams& params) {
  const std::string& path = params.description;
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext != ".xml" && ext != ".urdf")
    fail("robot.description", path, "allowed: builtin, or a path ending in .xml (MJCF) or .urdf (URDF)");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail("robot.description", path, "no such file");
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) fail("robot.description", path, "cannot read the file");
  return load_robot_text(text.str(), ext.substr(1), path, params);
}

}  // namespace flexgait::humanoid
