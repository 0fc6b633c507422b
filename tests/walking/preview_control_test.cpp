// ZMP preview control (Kajita 2003): the gains' Riccati residual, the horizon, and the closed-loop
// cart-table tracking a footstep plan's ZMP from a perturbed start (as Drake's ZMP planner tests).
#include "flexgait/walking/preview_control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "flexgait/robot/robot_params.hpp"
#include "flexgait/walking/footstep_plan.hpp"

namespace flexgait::walking {
namespace {

constexpr double kPeriod = 0.004, kHeight = 0.705;

TEST(PreviewControl, RiccatiResidualIsTiny) {
  for (double T : {0.001, 0.004, 0.008}) {
    const PreviewGains g = preview_gains(T, kHeight, humanoid::kDefaultGravity, 1.6, 1.0, 1e-6);
    // Relative to ||P||: the 1e-9 (measured ~1e-13 after the Newton refinement).
    EXPECT_LE(g.riccati_residual, 1e-9 * g.P.cwiseAbs().maxCoeff()) << "T = " << T;
    // 1.6 s is long enough: the preview gains decay geometrically, the last below 1 % of the first
    // (measured 0.5 %).
    EXPECT_LT(std::abs(g.G_p.back()), 1e-2 * std::abs(g.G_p.front())) << "T = " << T;
  }
}

TEST(PreviewControl, CartTableTracksAPlanFromAPerturbedStart) {
  WalkParams w;
  w.steps = 8;
  w.step_time = 1.0;
  const WalkPlan plan = plan_footsteps(w);
  const PreviewGains g =
      preview_gains(kPeriod, kHeight, humanoid::kDefaultGravity, w.preview_time, w.preview_q, w.preview_r);
  const auto n = static_cast<std::size_t>(std::ceil(plan.duration / kPeriod)) + g.G_p.size() + 2;
  std::vector<double> ref(n);
  for (std::size_t k = 0; k < n; ++k) ref[k] = zmp_reference(plan, static_cast<double>(k) * kPeriod).y();
  CartTable cart;
  cart.x = Eigen::Vector3d(0.03, -0.05, 0.0);  // 3 cm off, moving at 5 cm/s the wrong way
  double worst_late = 0, worst_end = 0;
  const auto steps = static_cast<std::size_t>(std::lround(plan.duration / kPeriod));
  for (std::size_t k = 0; k < steps; ++k) {
    const double p = cart_zmp(g, cart);
    if (k * kPeriod > w.start_time) worst_late = std::max(worst_late, std::abs(p - ref[k]));
    if (k * kPeriod > plan.t_settle + 1.0) worst_end = std::max(worst_end, std::abs(p - ref[k]));
    preview_step(g, cart, &ref[k]);
  }
  // Once the start-up transient has passed, the ZMP follows the plan within 5 mm (the preview
  // anticipates the steps; the residual error is the quintic double-support transitions) and
  // settles on it at the end (integral action): 1e-5 m.
  EXPECT_LT(worst_late, 5e-3);
  EXPECT_LT(worst_end, 1e-5);
}

}  // namespace
}  // namespace flexgait::walking
