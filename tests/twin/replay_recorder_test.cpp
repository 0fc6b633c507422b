// The twin's replay: every visible body is recorded with its geoms, a frame's poses are the
// state's (xpos, xquat) to float32, the floor is a checkered static plane, frames come every
// frame_dt, and the push arrow is the renderer's.
#include "flexgait/twin/replay_recorder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "flexgait/twin/detail/mujoco.hpp"

namespace flexgait::twin {
namespace {

TEST(ReplayRecorder, FramesHoldTheStatesBodyPoses) {
  HumanoidPlant plant(humanoid::RobotParams{}, PlantParams{});
  const humanoid::JointVector pose = standing_pose(humanoid::RobotParams{}, 0.75);
  plant.reset(pose);
  ReplayRecorder rec(plant, "standing", {{"pelvis z", "m", {}, "", "", ""}}, 0.02);
  const mjModel* m = plant_model(plant);
  ASSERT_GT(rec.scene().bodies.size(), 10u);
  EXPECT_EQ(rec.scene().bodies.front().name, "pelvis");
  bool floor = false;
  for (const auto& g : rec.scene().statics) floor |= g.type == replay::GeomType::Plane && g.checker;
  EXPECT_TRUE(floor);
  plant.set_push(Push{0.0, PushBody::kChest, {10, 0, 0}, 0.1});
  double t = 0;
  for (int i = 0; i < 20; ++i, t += m->opt.timestep) {
    plant.step(pose);
    const double z = plant_data(plant)->qpos[2];  // the pelvis's free joint: its height
    rec.record(plant, t, {}, std::vector<double>{z});
  }
  const replay::Scene& s = rec.scene();
  // A frame every 0.02 s over 20 physics steps of dt.
  EXPECT_EQ(s.frames(), static_cast<int>(std::ceil(20 * m->opt.timestep / 0.02 - 1e-9)));
  const mjData* d = plant_data(plant);
  const int last = s.frames() - 1;
  // The last frame was recorded from an earlier state; record it now and compare with the forward
  // kinematics of the state's positions (after mj_step, d's own xpos are the step's start's).
  ReplayRecorder now(plant, "now", {}, 1.0);
  now.record(plant, 0);
  mjData* k_data = mj_makeData(m);
  std::copy_n(d->qpos, m->nq, k_data->qpos);
  mj_kinematics(m, k_data);
  for (std::size_t k = 0; k < now.body_ids().size(); ++k) {
    const int b = now.body_ids()[k];
    const float* p = &now.scene().poses[7 * k];
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(p[i], k_data->xpos[3 * b + i], 1e-6);  // float32 of |x| < 2 m
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(p[3 + i], k_data->xquat[4 * b + i], 1e-7);
  }
  mj_deleteData(k_data);
  // The root (the pelvis's free joint): its position is qpos's, as the walk's log has it.
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(now.scene().poses[static_cast<std::size_t>(i)], d->qpos[i], 1e-6);
  EXPECT_FLOAT_EQ(s.signals[0].data[static_cast<std::size_t>(last)],
                  s.poses[static_cast<std::size_t>(last) * s.bodies.size() * 7 + 2]);
  // The push: the renderer's arrow.
  const auto arrow = push_arrow(plant);
  ASSERT_TRUE(arrow);
  const auto& layers = now.scene().layers;
  const auto push = std::find_if(layers.begin(), layers.end(), [](const auto& l) { return l.name == "push"; });
  ASSERT_NE(push, layers.end());
  const auto& layer = *push;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(layer.data[3 + i], arrow->to[i], 1e-6);
  EXPECT_NEAR(std::hypot(arrow->to[0] - arrow->from[0], arrow->to[2] - arrow->from[2]), 0.1 + kPushScale * 10, 1e-12);
  EXPECT_THROW(now.record(plant, 5.0, {}, std::vector<double>{1.0}), std::logic_error);  // no such signal
}

TEST(ReplayRecorder, ATenStepWalksPageStaysUnderFiveMegabytes) {
  // A 10-step walk: ~13.5 s at 25 frames per second (the walk's replay rate, walk_pictures.hpp),
  // ~340 frames, with the plan's 12 footprints planned and landed, every point marker and 45 signals.
  // The page: the viewer (~0.6 MB) and the data block. (A real walk's page: web/test/humanoid_replay.test.mjs.)
  HumanoidPlant plant(humanoid::RobotParams{}, PlantParams{});
  plant.reset(standing_pose(humanoid::RobotParams{}, 0.75));
  // 45 signals: more than a walk plots (WalkPictures::replay_signals: 36, 43 with the DCM and a push).
  std::vector<replay::Signal> signals;
  for (int i = 0; i < 45; ++i) signals.push_back({"s" + std::to_string(i), "m", {}, "p", "q", ""});
  ReplayRecorder rec(plant, "walk", signals, 0.04);
  rec.set_planned_footprints(std::vector<FootprintMarker>(12));
  const std::vector<double> values(signals.size(), 1.0);
  RenderMarkers markers;
  markers.zmp = markers.zmp_ref = markers.com_ground = markers.capture_point = std::array<double, 3>{0.1, 0.2, 0};
  markers.actual.resize(12);
  rec.record(plant, 0.0, markers, values);
  const double one = static_cast<double>(replay::replay_json(rec.scene()).size());
  for (int f = 1; f <= 100; ++f) rec.record(plant, f * 0.04, markers, values);
  const double per_frame = (static_cast<double>(replay::replay_json(rec.scene()).size()) - one) / 100;
  const double page = 0.6e6 + one + 340 * per_frame;
  std::printf("humanoid replay: %.0f bytes a frame, %.0f bytes of scene; a 340-frame page ~%.2f MB\n", per_frame, one,
              page / 1e6);
  EXPECT_LT(page, 5e6);
}

TEST(ReplayRecorder, MemoryIsBoundedByThinningTheFrames) {
  // 10 frames due (every 0.1 s over 0.9 s) into at most 4: full at 4, every other one goes and the
  // interval doubles (0.2 s), and again (0.4 s). The frames kept are the recorded times 0, 0.4, 0.8:
  // evenly spaced samples of the same run, each with its own pose and signal.
  HumanoidPlant plant(humanoid::RobotParams{}, PlantParams{});
  plant.reset(standing_pose(humanoid::RobotParams{}, 0.75));
  ReplayRecorder rec(plant, "thin", {{"t", "s", {}, "", "", ""}}, 0.1, 4);
  for (int i = 0; i <= 9; ++i) {
    const double t = 0.1 * i;
    rec.record(plant, t, {}, std::vector<double>{t});
  }
  const replay::Scene& s = rec.scene();
  EXPECT_NO_THROW(s.check());
  ASSERT_EQ(s.frames(), 3);
  EXPECT_NEAR(rec.frame_dt(), 0.4, 1e-12);
  for (int f = 0; f < 3; ++f) {
    EXPECT_NEAR(s.time[static_cast<std::size_t>(f)], 0.4 * f, 1e-12);
    EXPECT_FLOAT_EQ(s.signals[0].data[static_cast<std::size_t>(f)],
                    static_cast<float>(s.time[static_cast<std::size_t>(f)]));
  }
  EXPECT_THROW(ReplayRecorder(plant, "bad", {}, 0.0), std::invalid_argument);
  EXPECT_THROW(ReplayRecorder(plant, "bad", {}, 0.1, 1), std::invalid_argument);
}

TEST(ReplayRecorder, PlannedFootprintsAreStaticBoxes) {
  HumanoidPlant plant(humanoid::RobotParams{}, PlantParams{});
  ReplayRecorder rec(plant, "plan");
  const std::size_t before = rec.scene().statics.size();
  rec.set_planned_footprints({FootprintMarker{{0.2, 0.1, 0}, 0.3}, FootprintMarker{{0.4, -0.1, 0}, 0}});
  ASSERT_EQ(rec.scene().statics.size(), before + 2);
  const auto& g = rec.scene().statics[before];
  EXPECT_EQ(g.type, replay::GeomType::Box);
  EXPECT_NEAR(2 * std::atan2(g.quat[3], g.quat[0]), 0.3, 1e-12);  // the yaw about z
}

// A recovery step lands beyond the plan's footprints: the actual footprints' layer grows to hold it,
// and the frames before it show it hidden.
TEST(ReplayRecorder, ActualFootprintsBeyondThePlanAreRecorded) {
  HumanoidPlant plant(humanoid::RobotParams{}, PlantParams{});
  ReplayRecorder rec(plant, "recovery", {}, 0.01);
  rec.set_planned_footprints({FootprintMarker{{0.2, 0.1, 0}, 0}});
  RenderMarkers markers;
  markers.actual = {FootprintMarker{{0.2, 0.1, 0}, 0}};
  rec.record(plant, 0.0, markers);
  markers.actual.push_back(FootprintMarker{{0.5, -0.1, 0}, 0});
  markers.actual.push_back(FootprintMarker{{0.7, 0.1, 0}, 0});  // beyond the plan
  rec.record(plant, 0.01, markers);
  const auto& layer = std::find_if(rec.scene().layers.begin(), rec.scene().layers.end(),
                                   [](const replay::Layer& l) { return l.name == "actual footprints"; });
  ASSERT_NE(layer, rec.scene().layers.end());
  ASSERT_EQ(layer->count, 3);
  ASSERT_EQ(layer->data.size(), 2u * 3u * 6u);
  EXPECT_TRUE(std::isnan(layer->data[2 * 6]));                  // frame 0: the third not yet landed
  EXPECT_NEAR(layer->data[(3 + 2) * 6 + 0], 0.7 - 0.11, 1e-6);  // frame 1: its heel, x (float32)
  EXPECT_NEAR(layer->data[(3 + 2) * 6 + 3], 0.7 + 0.11, 1e-6);  // and its toe
}

}  // namespace
}  // namespace flexgait::twin
