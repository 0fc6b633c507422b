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

/// A unit vector n = v/|v| and its first two derivatives along a path, from v's: with r = |v|,
/// r' = n·v', n' = (v' − n r')/r, n'' = (v'' − 2 n' r' − n r'')/r, r'' = n'·v' + n·v''.
std::array<Vector3d, 3> unit_with_derivatives(const Vector3d& v, const Vector3d& dv, const Vector3d& ddv) {
  const double r = v.norm();
  const Vector3d n = v / r;
  const double dr = n.dot(dv);
  const Vector3d dn = (dv - n * dr) / r;
  const double ddr = dn.dot(dv) + n.dot(ddv);
  return {n, dn, (ddv - 2 * dn * dr - n * ddr) / r};
}

/// The angular velocity of sole_attitude(g + b Δg, ψ + b Δψ) per unit of b and its derivative in b,
/// at b (world): with R(b) = [x, z × x, z] of ground_slope.hpp (G2) and Ṙ Rᵀ = [ω]×, ω_b is the
/// skew part of R_b Rᵀ and ω_bb that of R_bb Rᵀ (R_b R_bᵀ is symmetric).
std::array<Vector3d, 2> sole_turn_rates(const Footprint& from, const Footprint& to, double b) {
  const Eigen::Vector2d g = from.slope + b * (to.slope - from.slope), dg = to.slope - from.slope;
  const double yaw = from.yaw + b * (to.yaw - from.yaw), dyaw = to.yaw - from.yaw;
  const Eigen::Vector2d h(std::cos(yaw), std::sin(yaw)), dh = Eigen::Vector2d(-h.y(), h.x()) * dyaw,
                                                         ddh = -h * dyaw * dyaw;
  const auto x =
      unit_with_derivatives(Vector3d(h.x(), h.y(), g.dot(h)), Vector3d(dh.x(), dh.y(), dg.dot(h) + g.dot(dh)),
                            Vector3d(ddh.x(), ddh.y(), 2 * dg.dot(dh) + g.dot(ddh)));
  const auto z =
      unit_with_derivatives(Vector3d(-g.x(), -g.y(), 1.0), Vector3d(-dg.x(), -dg.y(), 0.0), Vector3d::Zero());
  Matrix3d R, dR, ddR;
  R << x[0], z[0].cross(x[0]), z[0];
  dR << x[1], z[1].cross(x[0]) + z[0].cross(x[1]), z[1];
  ddR << x[2], z[2].cross(x[0]) + 2 * z[1].cross(x[1]) + z[0].cross(x[2]), z[2];
  const auto vee = [](const Matrix3d& M) {
    return Vector3d(0.5 * (M(2, 1) - M(1, 2)), 0.5 * (M(0, 2) - M(2, 0)), 0.5 * (M(1, 0) - M(0, 1)));
  };
  return {vee(dR * R.transpose()), vee(ddR * R.transpose())};
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

FeetMotion feet_motion(const WalkPlan& plan, double swing_height, double t) {
  // feet_target's swing, differentiated: u = (t − t_lift)/(t_land − t_lift), b = 10u³ − 15u⁴ + 6u⁵,
  // b' = 30 u²(1 − u)², b'' = 60 u(1 − u)(1 − 2u); the arc 64 H w³, w = u(1 − u), w' = 1 − 2u, w'' = −2.
  FeetMotion out;
  if (plan.steps.empty() || t < plan.steps.front().t_begin || t >= plan.steps.back().t_land) return out;
  const Step& s = plan.steps[step_at(plan, t)];
  if (t < s.t_lift) return out;
  const double duration = s.t_land - s.t_lift;
  const double u = std::clamp((t - s.t_lift) / duration, 0.0, 1.0);
  if (!(u > 0 && u < 1)) return out;
  const double du = 1 / duration;
  const double b1 = 30 * u * u * (1 - u) * (1 - u) * du, b2 = 60 * u * (1 - u) * (1 - 2 * u) * du * du;
  const double w = u * (1 - u), H = 64 * (swing_height + std::abs(s.to.z - s.from.z));
  const double z1 = H * 3 * w * w * (1 - 2 * u) * du,
               z2 = H * (6 * w * (1 - 2 * u) * (1 - 2 * u) - 6 * w * w) * du * du;
  const Vector3d delta(s.to.x - s.from.x, s.to.y - s.from.y, s.to.z - s.from.z);
  out.velocity[s.swing] = delta * b1 + Vector3d(0, 0, z1);
  out.acceleration[s.swing] = delta * b2 + Vector3d(0, 0, z2);
  const auto turn = sole_turn_rates(s.from, s.to, quintic_blend(u));
  out.angular_velocity[s.swing] = turn[0] * b1;
  out.angular_acceleration[s.swing] = turn[1] * b1 * b1 + turn[0] * b2;
  out.floor_velocity = 0.5 * delta.z() * b1;
  out.floor_acceleration = 0.5 * delta.z() * b2;
  return out;
}

}  // namespace flexgait::walking
