#pragma once
/// \file footstep_plan.hpp
/// Footsteps and their timeline (docs/theory/humanoid.md: "Footstep plan: step length, width, time,
/// double-support ratio, count, turning"), the ZMP reference they imply ("smooth through double
/// support") and the swing foot's path ("quintic or cycloid, with a swing height").
///
/// Timeline: standing for start_time with the ZMP between the feet; then each step i takes
/// step_time: double support (the ZMP moves from the previous support foot to the new stance
/// foot along a quintic blend) then single support (ZMP at the stance sole centre, the other
/// foot swings). After the last step the ZMP returns between the feet in one double-support time
/// and the robot stands for end_time.
#include <array>
#include <vector>

#include "flexgait/walking/rotation.hpp"
#include "flexgait/walking/walk_params.hpp"

namespace flexgait::walking {

struct Footprint {
  double x = 0, y = 0;  ///< sole centre on the floor [m]
  double yaw = 0;       ///< [rad]
  double z = 0;         ///< floor height under it [m]: 0 unless the controller is told the floor (know_floor)
  /// The floor's gradient (dz/dx, dz/dy) under its centre: zero unless the controller is told the
  /// floor; the sole is then commanded flat on that plane (ground_slope.hpp (G2)).
  Eigen::Vector2d slope = Eigen::Vector2d::Zero();
};

struct Step {
  int swing = 0;       ///< side that swings (0 left, 1 right)
  double t_begin = 0;  ///< start of the double support [s]
  double t_lift = 0;   ///< lift-off of the swing foot [s]
  double t_land = 0;   ///< touchdown [s]
  Footprint from, to;  ///< swing foot before and after
  Footprint stance;    ///< the other foot
};

struct WalkPlan {
  std::array<Footprint, 2> initial;  ///< left, right at the start
  std::array<Footprint, 2> final;    ///< at the end
  std::vector<Step> steps;
  double t_settle = 0;  ///< end of the last double support (ZMP back between the feet) [s]
  double duration = 0;  ///< t_settle + end_time [s]
};

/// The plan of `params`. The first swing foot is the right one, or the left one when turning left.
WalkPlan plan_footsteps(const WalkParams& params);

/// ZMP reference (x, y) at time t [m].
Eigen::Vector2d zmp_reference(const WalkPlan& plan, double t);

/// Where each foot should be at time t: sole pose (world) and whether it is swinging.
struct FeetTarget {
  std::array<Pose, 2> sole;
  std::array<bool, 2> swinging{};
  int step = -1;       ///< index of the current step, −1 before the first, steps.size() after the last
  double floor_z = 0;  ///< mean floor height under the feet (the swing foot's blended, without its arc) [m]
};
/// With footprint heights (Footprint::z) the swing blends from.z to to.z and its arc rises
/// swing_height above the higher of the two; with footprint slopes the sole's attitude blends
/// between theirs.
FeetTarget feet_target(const WalkPlan& plan, double swing_height, double t);

/// The time derivatives of feet_target (world): each sole's velocity and acceleration, angular
/// velocity and acceleration, and the floor height's (zero but for a swinging foot).
struct FeetMotion {
  std::array<Vector3d, 2> velocity{Vector3d::Zero(), Vector3d::Zero()};              ///< [m/s]
  std::array<Vector3d, 2> acceleration{Vector3d::Zero(), Vector3d::Zero()};          ///< [m/s^2]
  std::array<Vector3d, 2> angular_velocity{Vector3d::Zero(), Vector3d::Zero()};      ///< [rad/s]
  std::array<Vector3d, 2> angular_acceleration{Vector3d::Zero(), Vector3d::Zero()};  ///< [rad/s^2]
  double floor_velocity = 0, floor_acceleration = 0;  ///< of FeetTarget::floor_z [m/s, m/s^2]
};
FeetMotion feet_motion(const WalkPlan& plan, double swing_height, double t);

/// Sets every footprint's z to height(x, y) [m] and its slope to the height's gradient there, by
/// central differences of ±1 mm (a controller told the floor).
template <class Height>
void set_footprint_heights(WalkPlan& plan, const Height& height) {
  constexpr double h = 1e-3;  // [m]
  auto set = [&](Footprint& f) {
    f.z = height(f.x, f.y);
    f.slope =
        Eigen::Vector2d(height(f.x + h, f.y) - height(f.x - h, f.y), height(f.x, f.y + h) - height(f.x, f.y - h)) /
        (2 * h);
  };
  for (Footprint& f : plan.initial) set(f);
  for (Footprint& f : plan.final) set(f);
  for (Step& s : plan.steps) {
    set(s.from);
    set(s.to);
    set(s.stance);
  }
}

/// Quintic blend 10s³ − 15s⁴ + 6s⁵ of s ∈ [0, 1] (zero velocity and acceleration at both ends).
double quintic_blend(double s);

}  // namespace flexgait::walking
