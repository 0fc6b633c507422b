// The twin's floor: MuJoCo's floor matches terrain.hpp's heights and the keys (slope,
// step, rough amplitude and correlation), the flat floor is the plane of earlier versions, the
// twin stands on a ramp and a rough floor without a MuJoCo warning, same seed same heights.
#include "flexgait/twin/terrain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "flexgait/twin/detail/mujoco.hpp"
#include "flexgait/twin/model_xml.hpp"
#include "flexgait/twin/plant.hpp"

namespace flexgait::twin {
namespace {

PlantParams on(const TerrainParams& t) {
  PlantParams p;
  p.terrain = t;
  return p;
}

TerrainParams ramp(double angle, double start) {
  return {.kind = TerrainKind::kRamp, .ramp_angle = angle, .ramp_start = start};
}
TerrainParams step(double height, double x) {
  return {.kind = TerrainKind::kStep, .step_height = height, .step_x = x};
}
TerrainParams rough(double amplitude, double correlation, int seed = 1) {
  return {
      .kind = TerrainKind::kRough, .rough_amplitude = amplitude, .rough_correlation = correlation, .rough_seed = seed};
}

/// The floor's height under (x, y) in MuJoCo: a ray down from 3 m. y is kept beside the robot
/// (|y| ≥ 0.6 m, the twin spans |y| < 0.3 m), so the first geom hit is the floor's.
double mujoco_floor(const HumanoidPlant& plant, double x, double y) {
  const mjtNum from[3] = {x, y, 3.0}, down[3] = {0, 0, -1};
  int geom = -1;
  const mjtNum distance = mj_ray(plant_model(plant), plant_data(plant), from, down, nullptr, 1, -1, &geom);
  EXPECT_GE(geom, 0) << "no floor under " << x << ", " << y;
  if (geom >= 0) {
    EXPECT_EQ(plant_model(plant)->geom_bodyid[geom], 0) << "the ray hit the robot";
  }
  return 3.0 - distance;
}

TEST(Terrain, FlatFloorIsThePlaneOfEarlierVersions) {
  const std::string xml = humanoid_mjcf(humanoid::RobotParams{}, PlantParams{});
  EXPECT_NE(
      xml.find(
          R"(    <geom name="floor" type="plane" size="20 20 0.1" contype="1" conaffinity="1" friction="1 0.005 0.0001" solref="0.005 1" material="flexgait_floor"/>
    <body name="pelvis")"),
      std::string::npos);
  EXPECT_EQ(xml.find("<hfield"), std::string::npos);  // no height field (the assets are the look: sky, floor)
  EXPECT_EQ(Terrain(TerrainParams{}).height(1.3, -0.4), 0.0);
}

TEST(Terrain, RampInMuJoCoHasTheSlopeOfTheKey) {
  for (const double angle : {0.0349, 0.0873, -0.0873}) {
    const HumanoidPlant plant(humanoid::RobotParams{}, on(ramp(angle, 0.2)));
    for (const double x : {-1.5, 0.0, 0.19, 0.21, 0.7, 2.5, 6.0})
      for (const double y : {0.6, -0.9})
        // Box faces in double precision: 1e-9 m covers rounding over the 20 m boxes.
        EXPECT_NEAR(mujoco_floor(plant, x, y), plant.terrain().height(x, y), 1e-9) << "angle " << angle << ", x " << x;
    EXPECT_NEAR(mujoco_floor(plant, 0.0, 0.6), 0.0, 1e-9);  // level before the ramp
    EXPECT_NEAR((mujoco_floor(plant, 3.0, 0.6) - mujoco_floor(plant, 1.0, 0.6)) / 2.0, std::tan(angle), 1e-9);
  }
}

TEST(Terrain, StepInMuJoCoHasTheHeightOfTheKeyAtItsX) {
  for (const double h : {0.02, 0.05, -0.03}) {
    const HumanoidPlant plant(humanoid::RobotParams{}, on(step(h, 0.35)));
    EXPECT_NEAR(mujoco_floor(plant, 0.349, 0.6), 0.0, 1e-9);
    EXPECT_NEAR(mujoco_floor(plant, 0.351, 0.6), h, 1e-9);
    EXPECT_NEAR(mujoco_floor(plant, 4.0, -0.8), h, 1e-9);
    EXPECT_EQ(plant.terrain().height(0.349, 0), 0.0);
    EXPECT_EQ(plant.terrain().height(0.351, 0), h);
  }
}

TEST(Terrain, RoughFloorInMuJoCoMatchesItsNodes) {
  const TerrainParams t = rough(0.01, 0.1);
  const HumanoidPlant plant(humanoid::RobotParams{}, on(t));
  const HeightGrid& g = plant.terrain().grid();
  ASSERT_EQ(g.ncol, 501);  // 2 cm nodes over 10 m × 3 m
  ASSERT_EQ(g.nrow, 151);
  int checked = 0;
  for (int c = 3; c < g.ncol; c += 37)
    for (const int r : {5, 10, 120, 140}) {  // y = −1.4, −1.3, 0.9, 1.3 m: beside the robot
      const double x = kRoughXMin + c * g.cell, y = -kRoughHalfWidth + r * g.cell;
      const double h = g.height[static_cast<std::size_t>(r * g.ncol + c)];
      EXPECT_NEAR(plant.terrain().height(x, y), h, 1e-12);
      // MuJoCo stores the heights as float: 2A × 2^-24 ≈ 1e-9 m; 1e-7 m leaves room for its ray test.
      EXPECT_NEAR(mujoco_floor(plant, x, y), h, 1e-7) << "node " << r << ", " << c;
      ++checked;
    }
  EXPECT_GT(checked, 40);
}

TEST(Terrain, RoughFloorHasTheAmplitudeAndCorrelationOfItsKeys) {
  for (const double ell : {0.06, 0.2}) {
    const Terrain terrain(rough(0.015, ell));
    const HeightGrid& g = terrain.grid();
    double peak = 0, mean = 0;
    for (const double h : g.height) {
      peak = std::max(peak, std::abs(h));
      mean += h / static_cast<double>(g.height.size());
    }
    EXPECT_NEAR(peak, 0.015, 1e-15);
    // Autocorrelation along x at lag ℓ: exp(−1) ≈ 0.37 for exp(−r²/ℓ²). The estimate over
    // ~75 000 nodes, with ~(10 m / ℓ)(3 m / ℓ) independent patches (≥ 750), scatters by a few
    // hundredths; 0.1 also covers the lag rounded to whole nodes.
    const int lag = static_cast<int>(std::lround(ell / g.cell));
    double c0 = 0, c1 = 0;
    for (int r = 0; r < g.nrow; ++r)
      for (int c = 0; c + lag < g.ncol; ++c) {
        const double a = g.height[static_cast<std::size_t>(r * g.ncol + c)] - mean;
        const double b = g.height[static_cast<std::size_t>(r * g.ncol + c + lag)] - mean;
        c0 += a * a;
        c1 += a * b;
      }
    EXPECT_NEAR(c1 / c0, std::exp(-std::pow(lag * g.cell / ell, 2)), 0.1) << "correlation length " << ell;
  }
}

TEST(Terrain, SameSeedSameHeightsOtherSeedOthers) {
  EXPECT_EQ(Terrain(rough(0.01, 0.1, 7)).grid().height, Terrain(rough(0.01, 0.1, 7)).grid().height);
  EXPECT_NE(Terrain(rough(0.01, 0.1, 7)).grid().height, Terrain(rough(0.01, 0.1, 8)).grid().height);
}

/// Stands for 3 s with the standing pose commanded (no balance controller) and reports the state.
GroundTruth stand(const TerrainParams& t) {
  HumanoidPlant plant(humanoid::RobotParams{}, on(t));
  const humanoid::JointVector pose = standing_pose(humanoid::RobotParams{}, 0.75);
  plant.reset(pose);
  for (int i = 0; i < 750; ++i) plant.step(pose);
  GroundTruth g = plant.truth();
  EXPECT_EQ(g.warnings, 0);
  EXPECT_FALSE(g.non_sole_contact);
  EXPECT_TRUE(g.sole_contact[0] && g.sole_contact[1]);
  // Still upright: the pelvis within 5 cm of its standing height above the floor under it.
  EXPECT_NEAR(g.pelvis_pos[2] - plant.terrain().height(g.pelvis_pos[0], g.pelvis_pos[1]), 0.75, 0.05);
  return g;
}

TEST(Terrain, TwinStandsOnARampAndARoughFloor) {
  stand(ramp(2 * std::numbers::pi / 180, -1.0));  // both feet on a 2° slope
  stand(ramp(-2 * std::numbers::pi / 180, -1.0));
  stand(rough(0.01, 0.1));
  stand(step(0.03, 1.0));
}

}  // namespace
}  // namespace flexgait::twin
