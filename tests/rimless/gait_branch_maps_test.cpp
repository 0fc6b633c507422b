// The continuation's maps in the normalised parameter q (rimless/gait_branch_maps.hpp): q ↦ value,
// the cache of maps (one per q, at most four, invalid values reported with the key), the parameter
// direction for ∂P/∂q, and the family of the rigid wheel mapping McGeer's fixed point to itself.
#include "flexgait/rimless/gait_branch_maps.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "flexgait/rimless/rigid_wheel.hpp"
#include "flexgait/rimless/wheel_setup.hpp"

namespace flexgait::rimless::detail {
namespace {

std::shared_ptr<MapCache> slope_cache(const std::string& param = "rimless.slope", double from = 0.08,
                                      double to = 0.12) {
  auto cache = std::make_shared<MapCache>();
  cache->base = resolve_config(rimless_analysis_schema(), std::nullopt, {"sim.model=rigid", "rimless.I=0"});
  cache->spec.param = param;
  cache->spec.from = from;
  cache->spec.to = to;
  cache->sim = simulation_from_config(cache->base);
  cache->opt = analysis_from_config(cache->base);
  cache->model = Model::Rigid;
  return cache;
}

TEST(GaitBranchMaps, QRunsFromTheStartToTheEndOfTheInterval) {
  const auto cache = slope_cache();
  EXPECT_EQ(cache->value(0.0), 0.08);
  EXPECT_EQ(cache->value(1.0), 0.12);
  EXPECT_NEAR(cache->wheel_at(0.5).slope, 0.1, 1e-16);
  EXPECT_EQ(cache->config_at(0.09).origin("rimless.slope"), "sweep point 0");
}

TEST(GaitBranchMaps, CacheKeepsOneMapPerQAndAtMostFour) {
  const auto cache = slope_cache();
  std::string why;
  PoincareMap* first = cache->at(0.0, why);
  ASSERT_NE(first, nullptr) << why;
  EXPECT_EQ(cache->at(0.0, why), first);
  for (double q : {0.1, 0.2, 0.3, 0.4}) ASSERT_NE(cache->at(q, why), nullptr);
  EXPECT_EQ(cache->maps.size(), 4u);
  EXPECT_EQ(cache->maps.front().first, 0.1);  // q = 0 went first
}

TEST(GaitBranchMaps, InvalidValueIsReportedWithItsKey) {
  const auto cache = slope_cache("rimless.slope", 0.5, 1.0);  // the slope is bounded by π/4
  std::string why;
  EXPECT_EQ(cache->at(1.0, why), nullptr);
  EXPECT_NE(why.find("rimless.slope = 1 is not valid"), std::string::npos) << why;
  EXPECT_TRUE(cache->maps.empty());
}

TEST(GaitBranchMaps, ParameterDirectionOnlyForWheelKeysWithinTheirBounds) {
  const auto cache = slope_cache();
  const auto d = cache->direction_at(0.5);
  ASSERT_TRUE(d.has_value());
  // Central: the two wheels' slopes straddle 0.1 by ± h with h = half the q step times the width.
  EXPECT_NEAR(0.5 * (d->plus.slope + d->minus.slope), 0.1, 1e-15);
  EXPECT_NEAR(d->plus.slope - d->minus.slope, 2 * d->step * 0.04, 1e-15);
  EXPECT_GT(d->step, 0.0);
  EXPECT_FALSE(slope_cache("initial.omega", 1.0, 2.0)->direction_at(0.5).has_value());
  auto off = slope_cache();
  off->spec.parameter_sensitivity = false;
  EXPECT_FALSE(off->direction_at(0.5).has_value());
}

TEST(GaitBranchMaps, RigidFamilyMapsMcGeersFixedPointToItself) {
  const auto cache = slope_cache();
  const double q = 0.25;
  const WheelParams w = cache->wheel_at(q);
  const FixedPointReport fp =
      find_fixed_point(w, cache->sim, cache->opt, Model::Rigid, Section::Touchdown, InitialState{});
  ASSERT_TRUE(fp.converged) << fp.failure();
  const numerics::MapFamily family = family_in_mode(cache, fp.point, false);
  Eigen::VectorXd out;
  const auto failure = family.map(fp.point.z, q, out);
  ASSERT_FALSE(failure.has_value()) << *failure;
  // McGeer's ω* maps to itself; Newton's tolerance 1e-10, with margin 1e-8.
  EXPECT_NEAR(out(0), rigid_step_map(w).fixed_point(), 1e-8);
  EXPECT_NEAR(fp.point.z(0), rigid_step_map(w).fixed_point(), 1e-8);
}

}  // namespace
}  // namespace flexgait::rimless::detail
