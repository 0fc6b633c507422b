#include "flexgait/walking/footstep_plan.hpp"

#include "flexgait/walking/ground_slope.hpp"

#include <algorithm>
#include <cmath>

namespace flexgait::walking {
namespace {

Eigen::Vector2d xy(const Footprint& f) {
  return {f.x, f.y};
}

Eigen::Vector2d blend(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double s) {
  return a + quintic_blend(s) * (b - a);
}

Pose pose_of(const Footprint& f) {
  return {Vector3d(f.x, f.y, f.z), sole_attitude(f.slope, f.yaw)};
}

// The step whose interval holds t, for t within the walk (steps are contiguous and equally long).
std::size_t step_at(const WalkPlan& plan, double t) {
  const double T = plan.steps.front().t_land - plan.steps.front().t_begin;
  return std::min<std::size_t>(static_cast<std::size_t>((t - plan.steps.front().t_begin) / T), plan.steps.size() - 1);
}

}  // namespace

double quintic_blend(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * s * (10 + s * (-15 + 6 * s));
}

WalkPlan plan_footsteps(const WalkParams& w) {
  WalkPlan plan;
  const double half = 0.5 * w.step_width;
  plan.initial = {Footprint{0, half, 0}, Footprint{0, -half, 0}};
  std::array<Footprint, 2> feet = plan.initial;
  int swing = w.turn > 0 ? 0 : 1;
  double heading = 0;
  const double ds = w.dsp_ratio * w.step_time;
  for (int i = 0; i < w.steps; ++i) {
    Step s;
    s.swing = swing;
    s.t_begin = w.start_time + i * w.step_time;
    s.t_lift = s.t_begin + ds;
    s.t_land = s.t_begin + w.step_time;
    s.from = feet[swing];
    s.stance = feet[1 - swing];
    const bool last = i == w.steps - 1;
    if (!last) heading += w.turn;
    // The swing foot lands ahead of the stance foot (the last step: beside it), across the width.
    const double advance = last ? 0.0 : w.step_length;
    const double side = swing == 0 ? 1.0 : -1.0;
    const double c = std::cos(heading), sn = std::sin(heading);
    s.to = Footprint{s.stance.x + c * advance - sn * side * w.step_width,
                     s.stance.y + sn * advance + c * side * w.step_width, heading};
    feet[swing] = s.to;
    plan.steps.push_back(s);
    swing = 1 - swing;
  }
  plan.final = feet;
  const double t_walk_end = w.start_time + w.steps * w.step_time;
  plan.t_settle = t_walk_end + (w.steps > 0 ? std::max(ds, 0.2 * w.step_time) : 0.0);
  plan.duration = plan.t_settle + w.end_time;
  return plan;
}

Eigen::Vector2d zmp_reference(const WalkPlan& plan, double t) {
  const auto mid = [](const std::array<Footprint, 2>& f) { return Eigen::Vector2d(0.5 * (xy(f[0]) + xy(f[1]))); };
  if (plan.steps.empty() || t < plan.steps.front().t_begin) return mid(plan.initial);
  const Step& last = plan.steps.back();
  if (t >= last.t_land) {
    const double s = (t - last.t_land) / std::max(plan.t_settle - last.t_land, 1e-9);
    return blend(xy(last.stance), mid(plan.final), s);
  }
  const std::size_t i = step_at(plan, t);
  const Step& s = plan.steps[i];
  if (t >= s.t_lift) return xy(s.stance);
  const Eigen::Vector2d previous = i == 0 ? mid(plan.initial) : xy(plan.steps[i - 1].stance);
  return blend(previous, xy(s.stance), (t - s.t_begin) / std::max(s.t_lift - s.t_begin, 1e-9));
}

FeetTarget feet_target(const WalkPlan& plan, double swing_height, double t) {
  FeetTarget out;
  if (plan.steps.empty() || t < plan.steps.front().t_begin) {
    for (int side = 0; side < 2; ++side) out.sole[side] = pose_of(plan.initial[side]);
    out.floor_z = 0.5 * (plan.initial[0].z + plan.initial[1].z);
    return out;
  }
  if (t >= plan.steps.back().t_land) {
    for (int side = 0; side < 2; ++side) out.sole[side] = pose_of(plan.final[side]);
    out.step = static_cast<int>(plan.steps.size());
    out.floor_z = 0.5 * (plan.final[0].z + plan.final[1].z);
    return out;
  }
  const std::size_t i = step_at(plan, t);
  const Step& s = plan.steps[i];
  out.step = static_cast<int>(i);
  out.sole[1 - s.swing] = pose_of(s.stance);
  if (t < s.t_lift) {
    out.sole[s.swing] = pose_of(s.from);
    out.floor_z = 0.5 * (s.from.z + s.stance.z);
    return out;
  }
  // Swing: quintic blend in x, y, yaw; height 64 h s³(1 − s)³ (apex h at s = 1/2, smooth ends).
  const double u = std::clamp((t - s.t_lift) / (s.t_land - s.t_lift), 0.0, 1.0);
  const double b = quintic_blend(u);
  // (on known footprint heights: the base blends from.z → to.z, the arc clears the higher one)
  const double base = s.from.z + b * (s.to.z - s.from.z);
  const double z = 64 * (swing_height + std::abs(s.to.z - s.from.z)) * std::pow(u * (1 - u), 3);
  out.floor_z = 0.5 * (base + s.stance.z);
  Pose p;
  p.p = Vector3d(s.from.x + b * (s.to.x - s.from.x), s.from.y + b * (s.to.y - s.from.y), base + z);
  p.R = sole_attitude(s.from.slope + b * (s.to.slope - s.from.slope), s.from.yaw + b * (s.to.yaw - s.from.yaw));
  out.sole[s.swing] = p;
  out.swinging[s.swing] = u > 0 && u < 1;
  return out;
}

}  // namespace flexgait::walking
