#include "flexgait/twin/renderer.hpp"

#include "flexgait/core/config.hpp"

#include <GL/osmesa.h>
#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <stdexcept>

#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"

namespace flexgait::twin {

std::optional<CameraView> camera_view(std::string_view name) {
  if (name == "side") return CameraView::kSide;
  if (name == "follow") return CameraView::kFollow;
  if (name == "front") return CameraView::kFront;
  return std::nullopt;
}

namespace {

/// An OSMesa context with MuJoCo's offscreen buffer, scene and options for one model.
struct Offscreen {
  const mjModel* model = nullptr;
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer;  // OSMesa's default framebuffer (unused: MuJoCo draws offscreen)
  std::vector<unsigned char> flipped;
  mjvScene scene;
  mjvCamera camera;
  mjvOption option;
  mjrContext render;
  int width = 0, height = 0;

  Offscreen(const mjModel* m, int w, int h, int maxgeom) : model(m), width(w), height(h) {
    context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
    if (context == nullptr) throw std::runtime_error("OSMesa: cannot create an OpenGL context");
    buffer.resize(static_cast<std::size_t>(w) * h * 4);
    if (!OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, w, h)) {
      OSMesaDestroyContext(context);
      throw std::runtime_error("OSMesa: cannot make the context current");
    }
    mjv_defaultScene(&scene);
    mjv_defaultCamera(&camera);
    mjv_defaultOption(&option);
    mjr_defaultContext(&render);
    mjv_makeScene(model, &scene, maxgeom);
    mjr_makeContext(model, &render, mjFONTSCALE_150);
    mjr_setBuffer(mjFB_OFFSCREEN, &render);
    flipped.resize(static_cast<std::size_t>(w) * h * 3);
  }
  ~Offscreen() {
    mjr_freeContext(&render);
    mjv_freeScene(&scene);
    OSMesaDestroyContext(context);
  }
  Offscreen(const Offscreen&) = delete;
  Offscreen& operator=(const Offscreen&) = delete;

  void make_current() { OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, width, height); }

  /// Directional lights (not the headlight) placed above and beside `at`, so that the shadows
  /// (MuJoCo's shadow map is a box around the light) fall where the camera looks.
  void light_near(const mjtNum at[3]) {
    for (int i = 0; i < scene.nlight; ++i) {
      mjvLight& l = scene.lights[i];
      if (l.headlight || !l.directional) continue;
      for (int k = 0; k < 3; ++k) l.pos[k] = static_cast<float>(at[k]) - 4.0F * l.dir[k];
    }
  }

  /// Renders the scene (with `overlay` text at the top left) into `rgb`, rows top to bottom.
  void draw(const std::string& overlay, std::vector<unsigned char>& rgb) {
    const mjrRect viewport = {0, 0, width, height};
    mjr_render(viewport, &scene, &render);
    if (!overlay.empty()) mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, overlay.c_str(), nullptr, &render);
    mjr_readPixels(flipped.data(), nullptr, viewport, &render);
    const auto row = static_cast<std::size_t>(width) * 3;
    rgb.resize(row * height);
    for (int y = 0; y < height; ++y)  // OpenGL's rows run bottom to top
      std::copy_n(flipped.begin() + static_cast<std::ptrdiff_t>(row * (height - 1 - y)), row,
                  rgb.begin() + static_cast<std::ptrdiff_t>(row * y));
  }

  mjvGeom* add(int type, const mjtNum size[3], const mjtNum pos[3], const mjtNum mat[9], const float rgba[4]) {
    if (scene.ngeom >= scene.maxgeom) return nullptr;
    mjvGeom* g = scene.geoms + scene.ngeom++;
    mjv_initGeom(g, type, size, pos, mat, rgba);
    g->category = mjCAT_DECOR;
    return g;
  }
  mjvGeom* connect(int type, double width_m, const mjtNum from[3], const mjtNum to[3], const float rgba[4]) {
    mjvGeom* g = add(type, nullptr, nullptr, nullptr, rgba);
    if (g != nullptr) mjv_makeConnector(g, type, width_m, from[0], from[1], from[2], to[0], to[1], to[2]);
    return g;
  }
};

void check_size(int width, int height, int max_width, int max_height) {
  if (width < 1 || height < 1 || width > max_width || height > max_height)
    throw UsageError(fmt::format("render size {}x{} is outside 1x1 .. {}x{}", width, height, max_width, max_height));
}

/// A flat rectangle on the floor (a footprint): a thin box, yawed, its top 2 mm above `centre`.
void add_footprint(Offscreen& o, const FootprintMarker& f, const float rgba[4], double lift = 0) {
  const mjtNum size[3] = {f.half_length, f.half_width, 0.003};
  const mjtNum pos[3] = {f.centre[0], f.centre[1], f.centre[2] - 0.001 + lift};
  const double c = std::cos(f.yaw), s = std::sin(f.yaw);
  const mjtNum mat[9] = {c, -s, 0, s, c, 0, 0, 0, 1};
  o.add(mjGEOM_BOX, size, pos, mat, rgba);
}

/// A point on the floor at `p` (the ZMP, the COM's projection, the capture point): a flat disc,
/// and a ball of 0.8 × its radius resting on it, which the low side camera sees.
void add_point(Offscreen& o, const std::array<double, 3>& p, double radius, const std::array<float, 4>& rgba) {
  const mjtNum size[3] = {radius, 0.004, 0};
  const mjtNum pos[3] = {p[0], p[1], p[2] + 0.004};
  o.add(mjGEOM_CYLINDER, size, pos, nullptr, rgba.data());
  const mjtNum ball[3] = {0.8 * radius, 0, 0};
  const mjtNum top[3] = {p[0], p[1], p[2] + 0.008 + 0.8 * radius};
  o.add(mjGEOM_SPHERE, ball, top, nullptr, rgba.data());
}

void add_markers(Offscreen& o, const RenderMarkers& m) {
  for (const auto& f : m.planned) add_footprint(o, f, kMarkerColours[kPlannedColour].data());
  for (const auto& f : m.actual) add_footprint(o, f, kMarkerColours[kActualColour].data(), 0.001);  // above the plan's
  if (m.zmp_ref) add_point(o, *m.zmp_ref, 0.035, kMarkerColours[kZmpRefColour]);
  if (m.zmp) add_point(o, *m.zmp, 0.03, kMarkerColours[kZmpColour]);
  if (m.com_ground) add_point(o, *m.com_ground, 0.03, kMarkerColours[kComColour]);
  if (m.capture_point) add_point(o, *m.capture_point, 0.03, kMarkerColours[kCaptureColour]);
}

void add_push_arrow(Offscreen& o, const HumanoidPlant& plant) {
  static constexpr float kOrange[4] = {1.0F, 0.5F, 0.0F, 1.0F};
  const auto arrow = push_arrow(plant);
  if (!arrow) return;
  mjvGeom* g = o.connect(mjGEOM_ARROW, 0.03, arrow->from.data(), arrow->to.data(), kOrange);
  if (g != nullptr) std::snprintf(g->label, sizeof(g->label), "%.0f N", arrow->newtons);
}

}  // namespace

// ---- the twin ----------------------------------------------------------------------------------

std::optional<PushArrow> push_arrow(const HumanoidPlant& plant) {
  const mjModel* m = plant_model(plant);
  const mjData* d = plant_data(plant);
  for (int b = 1; b < m->nbody; ++b) {
    const mjtNum* f = d->xfrc_applied + 6 * b;
    const double norm = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(norm > 0)) continue;
    const double length = std::min(0.1 + kPushScale * norm, 1.0);
    PushArrow a;
    a.newtons = norm;
    for (int i = 0; i < 3; ++i) {
      a.to[i] = d->xipos[3 * b + i] - kPushGap * f[i] / norm;
      a.from[i] = a.to[i] - length * f[i] / norm;
    }
    return a;
  }
  return std::nullopt;
}

struct Renderer::Gl : Offscreen {
  using Offscreen::Offscreen;
};

Renderer::Renderer(const HumanoidPlant& plant, const RenderView& view)
    : view_(view), width_(view.width), height_(view.height) {
  const mjModel* model = plant_model(plant);
  check_size(width_, height_, model->vis.global.offwidth, model->vis.global.offheight);
  gl_ = std::make_unique<Gl>(model, width_, height_, 4000);
  gl_->option.label = mjLABEL_NONE;
  rgb_.resize(static_cast<std::size_t>(width_) * height_ * 3);
}

Renderer::~Renderer() = default;

const std::vector<unsigned char>& Renderer::render(const HumanoidPlant& plant, const RenderMarkers& markers) {
  const mjData* data = plant_data(plant);
  Gl& o = *gl_;
  o.make_current();
  mjvCamera& cam = o.camera;
  switch (view_.camera) {
    case CameraView::kSide: {
      // Fixed at the middle of the walk, seen from the robot's right (MuJoCo's azimuth 90°: the
      // camera at lookat − distance · forward, forward along +y), far enough that the walk's
      // stretch plus 1.2 m fits the width of the view (the vertical field of view is 45°).
      const double span = std::abs(view_.walk_to - view_.walk_from) + 1.2;
      const double aspect = static_cast<double>(width_) / height_;
      cam.lookat[0] = 0.5 * (view_.walk_from + view_.walk_to);
      cam.lookat[1] = 0;
      cam.lookat[2] = 0.6;
      cam.distance = std::max(3.0, 0.5 * span / (aspect * std::tan(std::numbers::pi / 8)));
      cam.azimuth = 90;
      cam.elevation = -12;  // the floor markers seen past the feet, the sky behind the robot
      break;
    }
    case CameraView::kFollow:
      cam.lookat[0] = data->qpos[0];
      cam.lookat[1] = data->qpos[1];
      cam.lookat[2] = 0.6;
      cam.distance = 2.8;
      cam.azimuth = 135;
      cam.elevation = -12;
      break;
    case CameraView::kFront:
      cam.lookat[0] = data->qpos[0];
      cam.lookat[1] = data->qpos[1];
      cam.lookat[2] = 0.6;
      cam.distance = 3.0;
      cam.azimuth = 180;  // forward along −x: the camera stands ahead of the robot (+x)
      cam.elevation = -10;
      break;
  }
  mjv_updateScene(o.model, const_cast<mjData*>(data), &o.option, nullptr, &cam, mjCAT_ALL, &o.scene);
  o.light_near(data->qpos);
  add_markers(o, markers);
  add_push_arrow(o, plant);
  o.draw(markers.overlay, rgb_);
  return rgb_;
}

// ---- replay scenes ------------------------------------------------------------------------------

namespace {

/// The replay scenes' model: the twin's look (model_xml.hpp), a light, and one hidden geom.
std::string scene_model(int width, int height) {
  return fmt::format(R"(<mujoco model="flexgait_scene">
{}  <asset>
{}  </asset>
  <worldbody>
    <light pos="0 -2 4" dir="0.3 0.4 -1" directional="true" castshadow="true" diffuse=".75 .75 .75"/>
    <geom name="probe" type="sphere" size="0.01" pos="0 0 -100" rgba="0 0 0 0"/>
  </worldbody>
</mujoco>
)",
                     look_visual_mjcf(width, height), look_assets_mjcf());
}

int mj_type(replay::GeomType t) {
  switch (t) {
    case replay::GeomType::Plane:
      return mjGEOM_PLANE;
    case replay::GeomType::Sphere:
      return mjGEOM_SPHERE;
    case replay::GeomType::Capsule:
      return mjGEOM_CAPSULE;
    case replay::GeomType::Ellipsoid:
      return mjGEOM_ELLIPSOID;
    case replay::GeomType::Cylinder:
      return mjGEOM_CYLINDER;
    case replay::GeomType::Box:
      return mjGEOM_BOX;
    case replay::GeomType::Mesh:
      return mjGEOM_NONE;  // drawn as its bounding box below
  }
  return mjGEOM_SPHERE;
}

}  // namespace

struct SceneRenderer::Gl {
  mjModel* model = nullptr;
  mjData* data = nullptr;
  std::unique_ptr<Offscreen> offscreen;
  int floor_material = -1;
  ~Gl() {
    offscreen.reset();
    if (data != nullptr) mj_deleteData(data);
    if (model != nullptr) mj_deleteModel(model);
  }
};

SceneRenderer::SceneRenderer(int width, int height) : gl_(std::make_unique<Gl>()), width_(width), height_(height) {
  check_size(width, height, 4096, 4096);
  gl_->model = load_mjcf(scene_model(width, height));
  gl_->data = mj_makeData(gl_->model);
  mj_forward(gl_->model, gl_->data);
  gl_->floor_material = mj_name2id(gl_->model, mjOBJ_MATERIAL, "flexgait_floor");
  gl_->offscreen = std::make_unique<Offscreen>(gl_->model, width, height, 6000);
  gl_->offscreen->option.label = mjLABEL_NONE;
  rgb_.resize(static_cast<std::size_t>(width) * height * 3);
}

SceneRenderer::~SceneRenderer() = default;

const std::vector<unsigned char>& SceneRenderer::render(const replay::Scene& scene, int frame) {
  Offscreen& o = *gl_->offscreen;
  const mjModel* m = gl_->model;
  o.make_current();
  const std::size_t nb = scene.bodies.size();
  auto pose = [&](std::size_t b, mjtNum pos[3], mjtNum quat[4]) {
    const float* p = scene.poses.data() + (static_cast<std::size_t>(frame) * nb + b) * 7;
    for (int i = 0; i < 3; ++i) pos[i] = p[i];
    for (int i = 0; i < 4; ++i) quat[i] = p[3 + i];
    mju_normalize4(quat);
  };
  // The camera: the scene's (the page's convention: azimuth of the camera's position about z
  // from +x, elevation above the horizontal; MuJoCo's looks along the opposite direction).
  const replay::Camera& c = scene.camera;
  mjvCamera& cam = o.camera;
  for (int i = 0; i < 3; ++i) cam.lookat[i] = c.target[i];
  for (std::size_t b = 0; b < nb; ++b)
    if (scene.bodies[b].name == c.follow && !c.follow.empty()) {
      mjtNum p0[3], q[4], p[3];
      const int keep = frame;
      frame = 0;
      pose(b, p0, q);
      frame = keep;
      pose(b, p, q);
      cam.lookat[0] += p[0] - p0[0];
      cam.lookat[1] += p[1] - p0[1];
    }
  cam.distance = c.distance;
  cam.azimuth = c.azimuth + 180;
  cam.elevation = -c.elevation;
  mjv_updateScene(m, gl_->data, &o.option, nullptr, &cam, mjCAT_ALL, &o.scene);
  o.light_near(cam.lookat);

  auto add_geom = [&](const replay::Geom& g, const mjtNum body_pos[3], const mjtNum body_quat[4]) {
    mjtNum pos[3], quat[4], gq[4] = {g.quat[0], g.quat[1], g.quat[2], g.quat[3]},
                            gp[3] = {g.pos[0], g.pos[1], g.pos[2]};
    mju_normalize4(gq);
    mju_rotVecQuat(pos, gp, body_quat);
    for (int i = 0; i < 3; ++i) pos[i] += body_pos[i];
    mju_mulQuat(quat, body_quat, gq);
    mjtNum mat[9];
    mju_quat2Mat(mat, quat);
    mjtNum size[3] = {g.size[0], g.size[1], g.size[2]};
    int type = mj_type(g.type);
    if (g.type == replay::GeomType::Mesh) {  // its bounding box (the vertices' extent)
      type = mjGEOM_BOX;
      mjtNum lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
      for (std::size_t v = 0; v + 2 < g.vertices.size(); v += 3)
        for (int i = 0; i < 3; ++i)
          lo[i] = std::min<mjtNum>(lo[i], g.vertices[v + i]), hi[i] = std::max<mjtNum>(hi[i], g.vertices[v + i]);
      mjtNum centre[3], shifted[3];
      for (int i = 0; i < 3; ++i) size[i] = 0.5 * (hi[i] - lo[i]), centre[i] = 0.5 * (hi[i] + lo[i]);
      mju_rotVecQuat(shifted, centre, quat);
      for (int i = 0; i < 3; ++i) pos[i] += shifted[i];
    }
    if (g.type == replay::GeomType::Plane) {
      size[0] = size[0] > 0 ? size[0] : 30;
      size[1] = size[1] > 0 ? size[1] : 30;
      size[2] = 0.5;  // grid spacing of the plane's drawing
    }
    mjvGeom* v = o.add(type, size, pos, mat, g.rgba.data());
    if (v != nullptr && g.type == replay::GeomType::Plane && g.checker && gl_->floor_material >= 0) {
      const int mat_id = gl_->floor_material;
      v->texid = m->mat_texid[mat_id];
      v->texuniform = m->mat_texuniform[mat_id];
      v->texrepeat[0] = m->mat_texrepeat[2 * mat_id];
      v->texrepeat[1] = m->mat_texrepeat[2 * mat_id + 1];
      for (int i = 0; i < 3; ++i) v->rgba[i] = 1.0F;
    }
  };
  const mjtNum origin[3] = {0, 0, 0}, identity[4] = {1, 0, 0, 0};
  for (const replay::Geom& g : scene.statics) add_geom(g, origin, identity);
  for (std::size_t b = 0; b < nb; ++b) {
    mjtNum pos[3], quat[4];
    pose(b, pos, quat);
    if (std::isnan(pos[0])) continue;
    for (const replay::Geom& g : scene.bodies[b].geoms) add_geom(g, pos, quat);
  }
  for (const replay::Layer& l : scene.layers) {
    if (!l.visible) continue;
    const int n = replay::layer_item_floats(l.kind);
    for (int k = 0; k < l.count; ++k) {
      const float* p = l.data.data() + (static_cast<std::size_t>(frame) * l.count + k) * n;
      if (std::isnan(p[0])) continue;
      const auto& rgba = l.palette[l.color[static_cast<std::size_t>(frame) * l.count + k]];
      const mjtNum a[3] = {p[0], p[1], p[2]};
      if (l.kind == replay::LayerKind::Points) {
        const mjtNum size[3] = {l.width, l.width, l.width};
        o.add(mjGEOM_SPHERE, size, a, nullptr, rgba.data());
        continue;
      }
      const mjtNum b[3] = {p[3], p[4], p[5]};
      const double length = mju_dist3(a, b);
      if (!(length > 1e-9)) continue;
      if (l.kind == replay::LayerKind::Arrows) {
        o.connect(mjGEOM_ARROW, 0.02, a, b, rgba.data());
      } else if (l.kind == replay::LayerKind::Segments) {
        o.connect(mjGEOM_CAPSULE, l.width, a, b, rgba.data());
      } else {
        // A spring: straight ends (10 % each) and a zigzag of 2 · turns strokes across the axis,
        // in the plane of the axis and the world's y (the wheel's plane is x–z).
        mjtNum axis[3], side[3];
        for (int i = 0; i < 3; ++i) axis[i] = (b[i] - a[i]) / length;
        const mjtNum y[3] = {0, 1, 0};
        mju_cross(side, axis, y);
        if (mju_normalize3(side) < 1e-6) {
          const mjtNum x[3] = {1, 0, 0};
          mju_cross(side, axis, x);
          mju_normalize3(side);
        }
        const int strokes = 2 * l.turns;
        mjtNum prev[3];
        for (int i = 0; i < 3; ++i) prev[i] = a[i] + 0.1 * length * axis[i];
        o.connect(mjGEOM_CAPSULE, 0.006, a, prev, rgba.data());
        for (int s = 1; s <= strokes; ++s) {
          const double along = 0.1 + 0.8 * s / strokes;
          const double across = s == strokes ? 0 : (s % 2 == 1 ? 1 : -1) * l.width;
          mjtNum next[3];
          for (int i = 0; i < 3; ++i) next[i] = a[i] + along * length * axis[i] + across * side[i];
          o.connect(mjGEOM_CAPSULE, 0.006, prev, next, rgba.data());
          std::memcpy(prev, next, sizeof prev);
        }
        o.connect(mjGEOM_CAPSULE, 0.006, prev, b, rgba.data());
      }
    }
  }
  const std::string overlay = fmt::format("{}\nt = {:.2f} s", scene.title, scene.time[static_cast<std::size_t>(frame)]);
  o.draw(overlay, rgb_);
  return rgb_;
}

// ---- files -------------------------------------------------------------------------------------

namespace {

void put_u32(std::string& s, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) s.push_back(static_cast<char>((v >> shift) & 0xff));
}

void chunk(std::string& png, const char* type, const std::string& body) {
  put_u32(png, static_cast<std::uint32_t>(body.size()));
  const std::string typed = std::string(type, 4) + body;
  png += typed;
  put_u32(png, static_cast<std::uint32_t>(
                   crc32(0, reinterpret_cast<const Bytef*>(typed.data()), static_cast<uInt>(typed.size()))));
}

}  // namespace

std::string encode_png(const std::vector<unsigned char>& rgb, int width, int height) {
  // Scanlines with filter type 0, deflated.
  std::string raw;
  raw.reserve(static_cast<std::size_t>(height) * (1 + 3 * width));
  for (int y = 0; y < height; ++y) {
    raw.push_back('\0');
    raw.append(reinterpret_cast<const char*>(rgb.data()) + static_cast<std::size_t>(y) * 3 * width,
               static_cast<std::size_t>(3 * width));
  }
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string deflated(size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(deflated.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                static_cast<uLong>(raw.size()), 6) != Z_OK)
    throw std::runtime_error("PNG: zlib compression failed");
  deflated.resize(size);
  std::string png = "\x89PNG\r\n\x1a\n";
  std::string header;
  put_u32(header, static_cast<std::uint32_t>(width));
  put_u32(header, static_cast<std::uint32_t>(height));
  header += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, no filter set, no interlace
  chunk(png, "IHDR", header);
  chunk(png, "IDAT", deflated);
  chunk(png, "IEND", "");
  return png;
}

bool encode_video(const std::filesystem::path& dir, double frame_rate) {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) return false;
  const std::string cmd = fmt::format(
      "ffmpeg -loglevel error -y -framerate {} -i '{}/frames/frame_%05d.png' -pix_fmt yuv420p -vf "
      "'scale=trunc(iw/2)*2:trunc(ih/2)*2' '{}/.video.mp4' && mv '{}/.video.mp4' '{}/video.mp4'",
      frame_rate, dir.string(), dir.string(), dir.string(), dir.string());
  return std::system(cmd.c_str()) == 0;
}

}  // namespace flexgait::twin
