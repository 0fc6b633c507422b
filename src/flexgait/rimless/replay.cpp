#include "flexgait/rimless/replay.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "flexgait/rimless/output.hpp"

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

  // The plotted signals: log.csv's columns of the same name, their values made by its row writer
  // (output.hpp) from the same samples; phaseK as a number (slip+ 1, stick 0, slip− −1; free: none).
  const std::vector<std::string> columns = log_column_names();
  auto signal = [&](std::string name, const char* unit, const char* panel, const char* plot, std::string label) {
    const auto at = std::find(columns.begin(), columns.end(), name);
    if (at == columns.end()) throw std::logic_error("WheelReplay: no log column " + name);
    columns_.push_back(static_cast<std::size_t>(at - columns.begin()));
    s.signals.push_back({std::move(name), unit, {}, panel, plot, std::move(label)});
  };
  signal("x", "m", "body", "hub x (down the slope)", "x");
  signal("y", "m", "body", "hub y (above the slope)", "y");
  signal("theta", "rad", "body", "body angle θ", "θ");
  signal("thetad", "rad/s", "body", "body rate θ̇", "θ̇");
  for (const char* name : {"E_kinetic", "E_gravity", "E_spring", "E_total"})
    signal(name, "J", "energy", "mechanical energy", name + 2);
  signal("W_damp", "J", "energy", "work dissipated", "damping");
  signal("W_fric", "J", "energy", "work dissipated", "friction");
  signal("balance", "J", "energy", "energy balance residual", "E + W − E(0)");
  for (int i = 1; i <= kMaxContacts; ++i) {
    const std::string slot = fmt::format("slot {}", i);
    signal(fmt::format("N{}", i), "N", "contacts", "normal force N", slot);
    signal(fmt::format("T{}", i), "N", "contacts", "friction force T", slot);
    phase_signals_.push_back(static_cast<int>(s.signals.size()));
    signal(fmt::format("phase{}", i), "", "contacts", "mode: slip+ 1, stick 0, slip− −1", slot);
    signal(fmt::format("leg{}", i), "", "contacts", "leg in contact (-1: none)", slot);
  }
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
    const std::array<double, 3> foot = slope_to_world(w_, c.c, 0.0);
    s.set_item(kNormal, f, i, foot, slope_to_world(w_, c.c, force_scale_ * c.N));
    s.set_item(kFriction, f, i, foot, slope_to_world(w_, c.c + force_scale_ * c.T, 0.0));
  }
  const std::vector<double> row = log_values(sample, energy_initial_);
  for (std::size_t i = 0; i < columns_.size(); ++i) s.set_signal(static_cast<int>(i), f, row[columns_[i]]);
  for (std::size_t k = 0; k < phase_signals_.size(); ++k) {  // (a text column: its mode as a number)
    const ContactSample& c = sample.contact[k];
    s.set_signal(phase_signals_[k], f, c.leg < 0 ? std::numeric_limits<double>::quiet_NaN() : slip_sign(c.mode));
  }
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
