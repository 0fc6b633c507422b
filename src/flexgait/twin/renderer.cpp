#include "flexgait/twin/renderer.hpp"

#include "flexgait/core/config.hpp"

#include <GL/osmesa.h>
#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "flexgait/twin/detail/mujoco.hpp"

namespace flexgait::humanoid {

struct Renderer::Gl {
  const mjModel* model = nullptr;  ///< the plant's (const, shared by the plant and its copies)
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer;  // OSMesa's default framebuffer (unused: MuJoCo draws offscreen)
  mjvScene scene;
  mjvCamera camera;
  mjvOption option;
  mjrContext render;
};

Renderer::Renderer(const HumanoidPlant& plant, int width, int height)
    : gl_(std::make_unique<Gl>()), width_(width), height_(height) {
  const mjModel* model = gl_->model = plant_model(plant);
  if (width > model->vis.global.offwidth || height > model->vis.global.offheight)
    throw UsageError(fmt::format("render size {}x{} exceeds the model's offscreen buffer {}x{}", width,
                                            height, model->vis.global.offwidth, model->vis.global.offheight));
  gl_->context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (gl_->context == nullptr) throw std::runtime_error("OSMesa: cannot create an OpenGL context");
  gl_->buffer.resize(static_cast<std::size_t>(width) * height * 4);
  if (!OSMesaMakeCurrent(gl_->context, gl_->buffer.data(), GL_UNSIGNED_BYTE, width, height)) {
    OSMesaDestroyContext(gl_->context);
    throw std::runtime_error("OSMesa: cannot make the context current");
  }
  mjv_defaultScene(&gl_->scene);
  mjv_defaultCamera(&gl_->camera);
  mjv_defaultOption(&gl_->option);
  mjr_defaultContext(&gl_->render);
  mjv_makeScene(model, &gl_->scene, 2000);
  mjr_makeContext(model, &gl_->render, mjFONTSCALE_100);
  mjr_setBuffer(mjFB_OFFSCREEN, &gl_->render);
  gl_->camera.distance = 2.6;
  gl_->camera.azimuth = 135;
  gl_->camera.elevation = -12;
  rgb_.resize(static_cast<std::size_t>(width) * height * 3);
  flipped_.resize(rgb_.size());
}

Renderer::~Renderer() {
  mjr_freeContext(&gl_->render);
  mjv_freeScene(&gl_->scene);
  OSMesaDestroyContext(gl_->context);
}

namespace {

void add_force_arrows(const mjModel* model, const mjData* data, mjvScene& scene) {
  // A push (xfrc_applied, disturbance.hpp): an orange arrow ending at the body's centre of mass,
  // pointing along the force, kArrowScale long per newton (at most kArrowMax).
  constexpr double kArrowScale = 0.003, kArrowMax = 0.8, kWidth = 0.03;  // [m/N], [m], [m]
  for (int b = 1; b < model->nbody && scene.ngeom < scene.maxgeom; ++b) {
    const mjtNum* f = data->xfrc_applied + 6 * b;
    const double norm = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(norm > 0)) continue;
    const double length = std::min(kArrowScale * norm, kArrowMax);
    const mjtNum* to = data->xipos + 3 * b;
    mjtNum from[3];
    for (int i = 0; i < 3; ++i) from[i] = to[i] - length * f[i] / norm;
    mjvGeom* g = scene.geoms + scene.ngeom++;
    const float rgba[4] = {1.0F, 0.5F, 0.0F, 1.0F};
    mjv_initGeom(g, mjGEOM_ARROW, nullptr, nullptr, nullptr, rgba);
    mjv_makeConnector(g, mjGEOM_ARROW, kWidth, from[0], from[1], from[2], to[0], to[1], to[2]);
  }
}

}  // namespace

const std::vector<unsigned char>& Renderer::render(const HumanoidPlant& plant) {
  const mjData* data = plant_data(plant);
  OSMesaMakeCurrent(gl_->context, gl_->buffer.data(), GL_UNSIGNED_BYTE, width_, height_);
  // Follow the pelvis (the free joint's position) at a fixed height.
  gl_->camera.lookat[0] = data->qpos[0];
  gl_->camera.lookat[1] = data->qpos[1];
  gl_->camera.lookat[2] = 0.6;
  mjv_updateScene(gl_->model, const_cast<mjData*>(data), &gl_->option, nullptr, &gl_->camera, mjCAT_ALL, &gl_->scene);
  add_force_arrows(gl_->model, data, gl_->scene);
  const mjrRect viewport = {0, 0, width_, height_};
  mjr_render(viewport, &gl_->scene, &gl_->render);
  mjr_readPixels(flipped_.data(), nullptr, viewport, &gl_->render);
  const auto row = static_cast<std::size_t>(width_) * 3;
  for (int y = 0; y < height_; ++y)  // OpenGL's rows run bottom to top
    std::copy_n(flipped_.begin() + static_cast<std::ptrdiff_t>(row * (height_ - 1 - y)), row,
                rgb_.begin() + static_cast<std::ptrdiff_t>(row * y));
  return rgb_;
}

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

}  // namespace flexgait::humanoid
