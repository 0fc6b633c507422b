#include "flexgait/experiments/walk_markers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/experiments/walk_scorer.hpp"
#include "flexgait/walking/dcm_stabiliser.hpp"

namespace flexgait::experiments {

WalkMarkers::WalkMarkers(const WalkRunParams& params, const walking::WalkingController& controller,
                         const twin::GroundTruth& initial)
    : params_(params),
      controller_(controller),
      offset_(plan_offset(initial, controller.plan())),
      settle_(landing_settle(params)) {}

twin::FootprintMarker WalkMarkers::footprint(double x, double y, double yaw, const twin::Terrain& terrain) const {
  const walking::RobotModel& model = controller_.model();
  twin::FootprintMarker f;
  f.centre = {x, y, terrain.height(x, y)};
  f.yaw = yaw;
  f.half_length = 0.5 * model.sole_length;
  f.half_width = 0.5 * model.sole_width;
  return f;
}

std::vector<twin::FootprintMarker> WalkMarkers::planned(const twin::Terrain& terrain) const {
  const walking::WalkPlan& plan = controller_.plan();
  std::vector<twin::FootprintMarker> out;
  out.reserve(2 + plan.steps.size());
  for (const walking::Footprint& f : plan.initial)
    out.push_back(footprint(f.x + offset_.x(), f.y + offset_.y(), f.yaw, terrain));
  for (const walking::Step& s : plan.steps)
    out.push_back(footprint(s.to.x + offset_.x(), s.to.y + offset_.y(), s.to.yaw, terrain));
  return out;
}

void WalkMarkers::observe(const loop::LoopStep& step) {
  const twin::GroundTruth& g = step.after;
  const twin::Terrain& terrain = step.plant.terrain();
  const walking::WalkPlan& plan = controller_.plan();  // (step adjustment moves its landings: read each period)
  const walking::ControllerStatus& st = controller_.status();
  auto ground = [&](double x, double y) { return std::array<double, 3>{x, y, terrain.height(x, y)}; };

  markers_.planned = planned(terrain);
  if (markers_.actual.empty())  // the soles where they stand at the start
    for (int side = 0; side < 2; ++side)
      markers_.actual.push_back(
          footprint(step.before.sole_pos[side][0], step.before.sole_pos[side][1], step.before.sole_yaw[side], terrain));
  // A landing once the foot has settled (as WalkScorer takes it).
  while (next_landing_ < plan.steps.size() &&
         landing_due(plan, next_landing_, settle_, g.t, g.sole_contact[plan.steps[next_landing_].swing])) {
    const int side = plan.steps[next_landing_++].swing;
    markers_.actual.push_back(footprint(g.sole_pos[side][0], g.sole_pos[side][1], g.sole_yaw[side], terrain));
  }

  // The ZMP of the contact forces is defined only while the floor carries the robot.
  markers_.zmp.reset();
  if (g.normal_force > 1.0) markers_.zmp = ground(g.zmp[0], g.zmp[1]);
  markers_.zmp_ref = ground(st.zmp_ref.x() + offset_.x(), st.zmp_ref.y() + offset_.y());
  markers_.com_ground = ground(g.com[0], g.com[1]);
  // The capture point ξ = c + ċ / ω, ω = √(g / z_c) (Englsberger et al. 2015, eq. D1 of
  // dcm_stabiliser.hpp), from the true COM, its velocity (momentum / mass) and height above the floor.
  const double mass = step.plant.total_mass(), z_c = g.com[2] - terrain.height(g.com[0], g.com[1]);
  markers_.capture_point.reset();
  if (mass > 0 && z_c > 0) {
    const Eigen::Vector2d xi = walking::dcm_of(Eigen::Vector2d(g.com[0], g.com[1]),
                                               Eigen::Vector2d(g.linear_momentum[0], g.linear_momentum[1]) / mass,
                                               std::sqrt(step.plant.gravity() / z_c));
    markers_.capture_point = ground(xi.x(), xi.y());
  }

  const char* phase = "standing";
  if (st.swinging[0])
    phase = "single support, left foot swings";
  else if (st.swinging[1])
    phase = "single support, right foot swings";
  else if (!plan.steps.empty() && g.t >= plan.steps.front().t_begin && g.t < plan.t_settle)
    phase = "double support";
  const int steps = static_cast<int>(plan.steps.size());
  markers_.overlay =
      fmt::format("t = {:.2f} s   step {} of {}   {}\ncompensation {}{}", g.t, std::clamp(st.step + 1, 0, steps), steps,
                  phase, name_of(params_.control.mode), st.safe_stop ? "   safe stop" : "");
}

}  // namespace flexgait::experiments
