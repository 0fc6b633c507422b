#include "flexgait/rimless/replay.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

namespace flexgait::rimless {
namespace {

enum LayerIndex { kLegs = 0, kFeet = 1, kNormal = 2, kFriction = 3 };

std::array<double, 4> about_y(double angle) {  // quaternion (w, x, y, z) of a turn about +y [rad]
  return {std::cos(angle / 2), 0, std::sin(angle / 2), 0};
}

}  // namespace

std::array<double, 3> slope_to_world(const WheelParams& w, double x, double y) {
  const double c = std::cos(w.slope), s = std::sin(w.slope);
  return {x * c + y * s, 0.0, -x * s + y * c};
}

WheelReplay::WheelReplay(const WheelParams& w, RunSink& next, double frame_dt, std::string title, int max_frames)
    : w_(w), next_(next), frame_dt_(frame_dt), force_scale_(0.4 * w.L0 / (w.m * w.g)), max_frames_(max_frames) {
  replay::Scene& s = scene_;
  s.title = title.empty() ? fmt::format("rimless wheel: {} legs, slope {:g} rad, mu_s {:g}, mu_k {:g}", w.legs, w.slope,
                                        w.mu_s, w.mu_k)
                          : std::move(title);
  const double L = w.L0;
  s.camera = {{0, 0, L}, 5 * L, -90, 4, "hub"};
  s.shadow_extent = 4 * L;
  // The hub: a disc (axis along y) with a cap that shows the wheel's turn.
  replay::Body hub{"hub", {}};
  replay::Geom disc;
  disc.type = replay::GeomType::Cylinder;
  disc.size = {0.1 * L, 0.03 * L, 0};
  disc.quat = {std::sqrt(0.5), -std::sqrt(0.5), 0, 0};  // local z → world y
  disc.rgba = {0.25F, 0.3F, 0.4F, 1.0F};
  replay::Geom mark;
  mark.type = replay::GeomType::Box;
  mark.size = {0.015 * L, 0.035 * L, 0.09 * L};
  mark.pos = {0, 0, -0.045 * L};  // along leg 0, half way to the disc's rim
  mark.rgba = {0.95F, 0.85F, 0.2F, 1.0F};
  hub.geoms = {disc, mark};
  s.bodies.push_back(hub);

  replay::Layer legs;
  legs.name = "springs";
  legs.kind = replay::LayerKind::Springs;
  legs.count = w.legs;
  legs.width = 0.03 * L;
  legs.turns = 9;
  legs.palette = {{0.2F, 0.2F, 0.25F, 1.0F}};
  s.layers.push_back(legs);
  replay::Layer feet;
  feet.name = "feet";
  feet.kind = replay::LayerKind::Points;
  feet.count = w.legs;
  feet.width = 0.035 * L;
  feet.palette = {{0.1F, 0.7F, 0.2F, 1.0F}, {0.95F, 0.35F, 0.1F, 1.0F}, {0.6F, 0.6F, 0.6F, 1.0F}};
  feet.legend = {"stick", "slip", "free"};
  s.layers.push_back(feet);
  replay::Layer normal;
  normal.name = "normal force";
  normal.kind = replay::LayerKind::Arrows;
  normal.count = kMaxContacts;
  normal.palette = {{0.15F, 0.35F, 0.9F, 1.0F}};
  s.layers.push_back(normal);
  replay::Layer friction = normal;
  friction.name = "friction force";
  friction.palette = {{0.85F, 0.1F, 0.5F, 1.0F}};
  s.layers.push_back(friction);

  for (const auto& [name, unit] : std::initializer_list<std::pair<const char*, const char*>>{
           {"x", "m"}, {"y", "m"}, {"thetad", "rad/s"}, {"E_total", "J"}, {"N total", "N"}, {"T total", "N"}})
    s.signals.push_back({name, unit, {}});
}

void WheelReplay::on_sample(const LogSample& sample) {
  next_.on_sample(sample);
  if (sample.t < next_frame_ && scene_.frames() > 0) return;
  if (scene_.frames() >= max_frames_) {
    truncated_ = true;
    return;
  }
  while (next_frame_ <= sample.t) next_frame_ += frame_dt_;
  replay::Scene& s = scene_;
  const int f = s.add_frame(sample.t);
  const double x = sample.q[0], y = sample.q[1], theta = sample.q[2];
  x_min_ = f == 0 ? x : std::min(x_min_, x);
  x_max_ = f == 0 ? x : std::max(x_max_, x);
  const std::array<double, 3> hub = slope_to_world(w_, x, y);
  s.set_pose(f, 0, hub, about_y(w_.slope + theta));
  double n_total = 0, t_total = 0;
  for (int k = 0; k < w_.legs; ++k) {
    const double beta = theta + 2 * w_.alpha() * k;
    int slot = -1;
    for (int i = 0; i < kMaxContacts; ++i)
      if (sample.contact[i].leg == k) slot = i;
    std::array<double, 3> foot;
    int mode = kFree;
    if (slot >= 0) {
      const ContactSample& c = sample.contact[slot];
      foot = slope_to_world(w_, c.c, 0.0);
      mode = c.mode == FootMode::Stick ? kStick : kSlip;
    } else {
      foot = slope_to_world(w_, x - w_.L0 * std::sin(beta), y - w_.L0 * std::cos(beta));
    }
    s.set_item(kLegs, f, k, hub, foot);
    s.set_item(kFeet, f, k, foot, foot, mode);
  }
  for (int i = 0; i < kMaxContacts; ++i) {
    const ContactSample& c = sample.contact[i];
    if (c.leg < 0) continue;
    n_total += c.N;
    t_total += c.T;
    const std::array<double, 3> foot = slope_to_world(w_, c.c, 0.0);
    s.set_item(kNormal, f, i, foot, slope_to_world(w_, c.c, force_scale_ * c.N));
    s.set_item(kFriction, f, i, foot, slope_to_world(w_, c.c + force_scale_ * c.T, 0.0));
  }
  const double values[] = {x, y, sample.q[5], sample.energy.total(), n_total, t_total};
  for (int i = 0; i < 6; ++i) s.set_signal(i, f, values[i]);
}

const replay::Scene& WheelReplay::finish() {
  // The slope: a checkered plane along the hub's travel, 3 L0 beyond each end.
  const double margin = 3 * w_.L0, mid = 0.5 * (x_min_ + x_max_);
  replay::Geom slope;
  slope.type = replay::GeomType::Plane;
  slope.size = {0.5 * (x_max_ - x_min_) + margin, 1.5 * w_.L0, 0};
  slope.pos = slope_to_world(w_, mid, 0.0);
  slope.quat = about_y(w_.slope);
  slope.rgba = {0.82F, 0.78F, 0.7F, 1.0F};
  slope.checker = true;
  scene_.statics = {slope};
  if (truncated_ && scene_.frames() > 0)
    scene_.title += fmt::format(" (the first {:.1f} s of the run)", scene_.time.back());
  truncated_ = false;
  return scene_;
}

}  // namespace flexgait::rimless
