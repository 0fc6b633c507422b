#include "flexgait/twin/replay_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "flexgait/twin/detail/mujoco.hpp"

namespace flexgait::twin {
namespace {

enum LayerIndex { kZmp = 0, kCom = 1, kCapture = 2, kPush = 3, kZmpRef = 4, kActual = 5 };

/// A height field as a triangle mesh in its geom's frame: MuJoCo's elevation h = z_top · data on
/// an (nrow × ncol) grid spanning ±size_x, ±size_y.
void hfield_mesh(const mjModel* m, int h, replay::Geom& g) {
  const int nrow = m->hfield_nrow[h], ncol = m->hfield_ncol[h];
  const mjtNum* size = m->hfield_size + 4 * h;
  const float* data = m->hfield_data + m->hfield_adr[h];
  for (int r = 0; r < nrow; ++r)
    for (int c = 0; c < ncol; ++c) {
      g.vertices.push_back(static_cast<float>(size[0] * (2.0 * c / (ncol - 1) - 1)));
      g.vertices.push_back(static_cast<float>(size[1] * (2.0 * r / (nrow - 1) - 1)));
      g.vertices.push_back(static_cast<float>(size[2] * data[r * ncol + c]));
    }
  for (int r = 0; r + 1 < nrow; ++r)
    for (int c = 0; c + 1 < ncol; ++c) {
      const auto a = static_cast<std::uint32_t>(r * ncol + c), b = a + 1, d = a + static_cast<std::uint32_t>(ncol),
                 e = d + 1;
      for (std::uint32_t i : {a, b, e, a, e, d}) g.faces.push_back(i);
    }
}

bool shape(const mjModel* m, int i, replay::Geom& g) {
  const mjtNum* s = m->geom_size + 3 * i;
  g.size = {s[0], s[1], s[2]};
  switch (m->geom_type[i]) {
    case mjGEOM_PLANE:
      g.type = replay::GeomType::Plane;
      g.checker = true;
      break;
    case mjGEOM_SPHERE:
      g.type = replay::GeomType::Sphere;
      break;
    case mjGEOM_CAPSULE:
      g.type = replay::GeomType::Capsule;
      break;
    case mjGEOM_ELLIPSOID:
      g.type = replay::GeomType::Ellipsoid;
      break;
    case mjGEOM_CYLINDER:
      g.type = replay::GeomType::Cylinder;
      break;
    case mjGEOM_BOX:
      g.type = replay::GeomType::Box;
      break;
    case mjGEOM_MESH: {
      g.type = replay::GeomType::Mesh;
      const int k = m->geom_dataid[i];
      const float* v = m->mesh_vert + 3 * m->mesh_vertadr[k];
      g.vertices.assign(v, v + 3 * m->mesh_vertnum[k]);
      const int* f = m->mesh_face + 3 * m->mesh_faceadr[k];
      g.faces.assign(f, f + 3 * m->mesh_facenum[k]);
      break;
    }
    case mjGEOM_HFIELD:
      g.type = replay::GeomType::Mesh;
      hfield_mesh(m, m->geom_dataid[i], g);
      break;
    default:
      return false;
  }
  const int mat = m->geom_matid[i];
  const float* rgba = mat >= 0 && g.type != replay::GeomType::Plane ? m->mat_rgba + 4 * mat : m->geom_rgba + 4 * i;
  g.rgba = {rgba[0], rgba[1], rgba[2], rgba[3]};
  if (mat >= 0 && (g.type == replay::GeomType::Plane || m->geom_type[i] == mjGEOM_HFIELD || m->geom_bodyid[i] == 0))
    g.rgba = {0.82F, 0.83F, 0.8F, 1.0F};  // the checkered floor's mean colour
  for (int k = 0; k < 3; ++k) g.pos[k] = m->geom_pos[3 * i + k];
  for (int k = 0; k < 4; ++k) g.quat[k] = m->geom_quat[4 * i + k];
  return true;
}

}  // namespace

struct ReplayRecorder::Kinematics {
  const mjModel* model;
  mjData* data;
  explicit Kinematics(const mjModel* m) : model(m), data(mj_makeData(m)) {
    if (data == nullptr) throw std::runtime_error("ReplayRecorder: MuJoCo could not allocate its state");
  }
  ~Kinematics() { mj_deleteData(data); }
  Kinematics(const Kinematics&) = delete;
  Kinematics& operator=(const Kinematics&) = delete;
  /// The bodies' poses of the positions `qpos`.
  const mjData* of(const mjData* state) {
    std::copy_n(state->qpos, model->nq, data->qpos);
    if (model->nmocap > 0) {
      std::copy_n(state->mocap_pos, 3 * model->nmocap, data->mocap_pos);
      std::copy_n(state->mocap_quat, 4 * model->nmocap, data->mocap_quat);
    }
    mj_kinematics(model, data);
    return data;
  }
};

ReplayRecorder::~ReplayRecorder() = default;

ReplayRecorder::ReplayRecorder(const HumanoidPlant& plant, std::string title, std::vector<replay::Signal> signals,
                               double frame_dt, int max_frames)
    : frame_dt_(frame_dt), max_frames_(max_frames) {
  if (!(frame_dt > 0) || !std::isfinite(frame_dt) || max_frames < 2)
    throw std::invalid_argument("ReplayRecorder: frame_dt > 0 and max_frames >= 2 expected");
  const mjModel* m = plant_model(plant);
  kinematics_ = std::make_unique<Kinematics>(m);
  scene_.title = std::move(title);
  scene_.camera = {{0, 0, 0.8}, 3.5, -90, 8, "pelvis"};
  scene_.shadow_extent = 3;
  std::vector<int> scene_body(static_cast<std::size_t>(m->nbody), -1);
  for (int i = 0; i < m->ngeom; ++i) {
    if (m->geom_rgba[4 * i + 3] <= 0 && m->geom_matid[i] < 0) continue;  // invisible (collision-only) geoms
    if (m->geom_group[i] > 2) continue;                                  // MuJoCo hides groups 3-5 by default
    replay::Geom g;
    if (!shape(m, i, g)) continue;
    const int b = m->geom_bodyid[i];
    if (b == 0) {
      scene_.statics.push_back(std::move(g));
      continue;
    }
    if (scene_body[static_cast<std::size_t>(b)] < 0) {
      scene_body[static_cast<std::size_t>(b)] = static_cast<int>(scene_.bodies.size());
      const char* name = mj_id2name(m, mjOBJ_BODY, b);
      scene_.bodies.push_back({name != nullptr ? name : "body" + std::to_string(b), {}});
      body_ids_.push_back(b);
    }
    scene_.bodies[static_cast<std::size_t>(scene_body[static_cast<std::size_t>(b)])].geoms.push_back(std::move(g));
  }
  if (!body_ids_.empty()) scene_.camera.follow = scene_.bodies.front().name;  // the root: the pelvis
  auto points = [&](const char* name, std::array<float, 4> rgba, double radius) {
    replay::Layer l;
    l.name = name;
    l.kind = replay::LayerKind::Points;
    l.count = 1;
    l.width = radius;
    l.palette = {rgba};
    scene_.layers.push_back(l);
  };
  points("ZMP", kMarkerColours[kZmpColour], 0.03);
  points("COM ground projection", kMarkerColours[kComColour], 0.025);
  points("capture point", kMarkerColours[kCaptureColour], 0.025);
  replay::Layer push;
  push.name = "push";
  push.kind = replay::LayerKind::Arrows;
  push.count = 1;
  push.palette = {{1, 0.5F, 0, 1}};
  scene_.layers.push_back(push);
  points("reference ZMP", kMarkerColours[kZmpRefColour], 0.03);
  replay::Layer actual;  // (items added by set_planned_footprints)
  actual.name = "actual footprints";
  actual.kind = replay::LayerKind::Segments;
  actual.width = 0.012;
  actual.palette = {kMarkerColours[kActualColour]};
  scene_.layers.push_back(actual);
  for (replay::Signal& s : signals) {
    s.data.clear();
    scene_.signals.push_back(std::move(s));
  }
}

void ReplayRecorder::set_planned_footprints(const std::vector<FootprintMarker>& footprints) {
  if (scene_.frames() > 0) throw std::logic_error("ReplayRecorder::set_planned_footprints: after the first frame");
  for (const auto& f : footprints) {
    replay::Geom g;
    g.type = replay::GeomType::Box;
    g.size = {f.half_length, f.half_width, 0.002};
    g.pos = {f.centre[0], f.centre[1], f.centre[2] + 0.001};
    g.quat = {std::cos(f.yaw / 2), 0, 0, std::sin(f.yaw / 2)};
    g.rgba = kMarkerColours[kPlannedColour];
    scene_.statics.push_back(g);
  }
}

void ReplayRecorder::record(const HumanoidPlant& plant, double t, const RenderMarkers& markers,
                            std::span<const double> values) {
  if (scene_.frames() > 0 && t < next_) return;
  if (values.size() != scene_.signals.size())
    throw std::logic_error("ReplayRecorder::record: one value per signal expected");
  if (scene_.frames() >= max_frames_) {  // full: half the frames, twice the interval
    scene_.drop_odd_frames();
    frame_dt_ *= 2;
    next_ = scene_.time.back() + frame_dt_;
    if (t < next_) return;
  }
  while (next_ <= t) next_ += frame_dt_;
  const mjData* d = kinematics_->of(plant_data(plant));
  const int f = scene_.add_frame(t);
  for (std::size_t k = 0; k < body_ids_.size(); ++k) {
    const int b = body_ids_[k];
    scene_.set_pose(f, static_cast<int>(k), {d->xpos[3 * b], d->xpos[3 * b + 1], d->xpos[3 * b + 2]},
                    {d->xquat[4 * b], d->xquat[4 * b + 1], d->xquat[4 * b + 2], d->xquat[4 * b + 3]});
  }
  if (markers.zmp) scene_.set_item(kZmp, f, 0, *markers.zmp, *markers.zmp);
  if (markers.com_ground) scene_.set_item(kCom, f, 0, *markers.com_ground, *markers.com_ground);
  if (markers.capture_point) scene_.set_item(kCapture, f, 0, *markers.capture_point, *markers.capture_point);
  if (const auto arrow = push_arrow(plant)) scene_.set_item(kPush, f, 0, arrow->from, arrow->to);
  if (markers.zmp_ref) scene_.set_item(kZmpRef, f, 0, *markers.zmp_ref, *markers.zmp_ref);
  scene_.grow_layer(kActual, static_cast<int>(markers.actual.size()));
  for (std::size_t k = 0; k < markers.actual.size(); ++k) {  // heel to toe, 3 mm above the floor
    const FootprintMarker& m = markers.actual[k];
    const double c = m.half_length * std::cos(m.yaw), s = m.half_length * std::sin(m.yaw), z = m.centre[2] + 0.003;
    scene_.set_item(kActual, f, static_cast<int>(k), {m.centre[0] - c, m.centre[1] - s, z},
                    {m.centre[0] + c, m.centre[1] + s, z});
  }
  for (std::size_t i = 0; i < values.size(); ++i) scene_.set_signal(static_cast<int>(i), f, values[i]);
}

}  // namespace flexgait::twin
