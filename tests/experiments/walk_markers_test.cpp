// The walk's markers (walk_markers.hpp) hold what they claim, read from a real 2-step walk with no
// renderer: the actual footprints are where the soles landed (the scorer's landings) and near the
// plan's; when the robot stands still the capture point meets the COM's ground projection and the
// true ZMP the COM's (static balance); the overlay names the step.
#include "flexgait/experiments/walk_markers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

namespace flexgait::experiments {
namespace {

TEST(WalkMarkers, HoldTheLandingsAndMeetTheComWhenStanding) {
  WalkRunParams p;
  p.walk.steps = 2;
  const walking::WalkPlan plan = walking::plan_footsteps(p.walk);
  std::unique_ptr<WalkMarkers> markers;
  const WalkResult r = run_walk(p, {}, [&](WalkLoop& w) {
    markers = std::make_unique<WalkMarkers>(p, w.control->controller(), w.loop->truth());
    w.loop->attach(*markers);
  });
  ASSERT_TRUE(r.metrics.completed()) << r.metrics.outcome();
  const twin::RenderMarkers& m = markers->markers();
  ASSERT_EQ(m.planned.size(), 2 + plan.steps.size());
  ASSERT_EQ(m.actual.size(), 2 + plan.steps.size());  // the start's soles and every landing
  ASSERT_EQ(r.landings.size(), plan.steps.size());
  const Eigen::Vector2d& o = markers->offset();
  for (std::size_t k = 0; k < plan.steps.size(); ++k) {
    // The landing the scorer took (plan frame) is the actual footprint (world) less the offset: the
    // same numbers through one addition (1e-12 m).
    const auto& a = m.actual[2 + k];
    EXPECT_NEAR(a.centre[0] - o.x(), r.landings[k].actual_x, 1e-12);
    EXPECT_NEAR(a.centre[1] - o.y(), r.landings[k].actual_y, 1e-12);
    // and lies within the judge's tolerance of the planned one (a completed walk's landings).
    const auto& q = m.planned[2 + k];
    EXPECT_LT(std::hypot(a.centre[0] - q.centre[0], a.centre[1] - q.centre[1]), 0.03);
  }
  // Standing still (2 s after the last step): ċ ≈ 0, so ξ = c + ċ/ω meets the COM's projection
  // within millimetres, and the true ZMP the COM's (static balance) within a centimetre.
  ASSERT_TRUE(m.capture_point && m.com_ground && m.zmp && m.zmp_ref);
  EXPECT_LT(std::hypot((*m.capture_point)[0] - (*m.com_ground)[0], (*m.capture_point)[1] - (*m.com_ground)[1]), 0.005);
  EXPECT_LT(std::hypot((*m.zmp)[0] - (*m.com_ground)[0], (*m.zmp)[1] - (*m.com_ground)[1]), 0.01);
  EXPECT_NE(m.overlay.find("step 2 of 2"), std::string::npos) << m.overlay;
}

}  // namespace
}  // namespace flexgait::experiments
