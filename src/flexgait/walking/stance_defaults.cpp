#include "flexgait/walking/stance_defaults.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flexgait::walking {

namespace {

/// Rounded to the millimetre, so a derived default reads as a number a user would type.
double to_millimetre(double x) { return std::round(x * 1000.0) / 1000.0; }

}  // namespace

LegReach leg_reach(const RobotModel& model) {
  LegReach r;
  r.length = std::numeric_limits<double>::infinity();
  Vector3d hip[2];
  for (int side = 0; side < 2; ++side) {
    const LegGeometry& leg = model.leg[static_cast<std::size_t>(side)];
    Vector3d sole = leg.sole;
    for (const Vector3d& a : leg.anchor) sole += a;
    r.stretched_height += -0.5 * sole.z();
    r.length = std::min(r.length, leg.anchor[3].norm() + leg.anchor[4].norm());
    hip[side] = leg.anchor[0] + leg.anchor[1] + leg.anchor[2];
  }
  r.hip_spacing = std::abs(hip[0].y() - hip[1].y());
  return r;
}

StanceDefaults stance_defaults(const RobotModel& model) {
  const LegReach r = leg_reach(model);
  return {to_millimetre(r.stretched_height - kCrouchShare * r.length), to_millimetre(r.hip_spacing)};
}

double hip_to_ankle(const LegReach& reach, double pelvis_height) {
  return pelvis_height - (reach.stretched_height - reach.length);
}

}  // namespace flexgait::walking
