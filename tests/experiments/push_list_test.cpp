// A list of pushes: disturbance.pushes read from a file and from --set, each bad field
// refused naming `disturbance.pushes[i].field` and the file's line, the written config.yaml reading
// back to the same run, and a walk with two pushes applying both (the plant's account and the
// robot's momentum), same bytes twice, the single push unchanged beside an empty list; a push
// timed by the walking phase (step, phase) starting where the plan says, and its bad input.
#include <unistd.h>  // getpid: a directory of this process alone (work trees run tests at once)

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "flexgait/core/config.hpp"
#include "flexgait/experiments/push_timing.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/experiments/walk_output.hpp"
#include "flexgait/twin/plant.hpp"

namespace flexgait::experiments {
namespace {

using twin::Push;
using twin::PushBody;

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto path =
      std::filesystem::temp_directory_path() / ("flexgait_push_list_test_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path;
}

WalkRunParams from_file(const std::string& text) {
  return walk_run_from_config(resolve_config(walk_run_schema(), write_temp("ok.yaml", text), {}));
}

// The ConfigError message of resolving `text` as a file with `sets` (fails the test if none).
std::string refusal(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    walk_run_from_config(resolve_config(walk_run_schema(), write_temp("bad.yaml", text), sets));
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
    return what;
  }
  ADD_FAILURE() << "not refused:\n" << text;
  return {};
}

const char* kTwoPushes =
    "disturbance:\n"
    "  pushes:\n"
    "    - {time: 4.1, body: chest, force: [0, 120, 0], duration: 0.1}\n"
    "    - time: 5\n"
    "      body: pelvis\n"
    "      force: [-30.5, 0, 2]\n"
    "      duration: 0.25\n";

TEST(PushList, ReadFromAFileInOrder) {
  const WalkRunParams p = from_file(kTwoPushes);
  ASSERT_EQ(p.pushes.size(), 2u);
  EXPECT_EQ(p.pushes[0].time, 4.1);
  EXPECT_EQ(p.pushes[0].body, PushBody::kChest);
  EXPECT_EQ(p.pushes[0].force, (std::array<double, 3>{0, 120, 0}));
  EXPECT_EQ(p.pushes[0].duration, 0.1);
  EXPECT_EQ(p.pushes[1].time, 5.0);
  EXPECT_EQ(p.pushes[1].body, PushBody::kPelvis);
  EXPECT_EQ(p.pushes[1].force, (std::array<double, 3>{-30.5, 0, 2}));
  EXPECT_EQ(p.pushes[1].duration, 0.25);
  EXPECT_TRUE(from_file("").pushes.empty());  // none by default
}

TEST(PushList, SetTakesFlowYaml) {
  const Config c = resolve_config(walk_run_schema(), std::nullopt,
                                  {"disturbance.pushes=[{time: 1, body: pelvis, force: [5, 0, 0], duration: 0.2}]"});
  const WalkRunParams p = walk_run_from_config(c);
  ASSERT_EQ(p.pushes.size(), 1u);
  EXPECT_EQ(p.pushes[0].force[0], 5.0);
  EXPECT_EQ(c.origin("disturbance.pushes"), "--set");
}

TEST(PushList, EachBadFieldNamedWithItsIndexAndLine) {
  const std::string head = "disturbance:\n  pushes:\n    - {time: 1, body: chest, force: [0, 1, 0], duration: 0.1}\n";
  const auto bad = [&](const std::string& item) { return refusal(head + "    - " + item + "\n"); };
  const std::string file = "_bad.yaml:3";  // the list's line (in this process's file)
  for (const auto& [item, key, what] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"{time: -1, body: chest, force: [0, 1, 0], duration: 0.1}", "disturbance.pushes[1].time", "out of range"},
           {"{time: 1, body: head, force: [0, 1, 0], duration: 0.1}", "disturbance.pushes[1].body",
            "one of pelvis, chest"},
           {"{time: 1, body: chest, force: [0, 1], duration: 0.1}", "disturbance.pushes[1].force",
            "not a list of 3 values"},
           {"{time: 1, body: chest, force: 5, duration: 0.1}", "disturbance.pushes[1].force", "not a list of 3 values"},
           {"{time: 1, body: chest, force: [0, x, 0], duration: 0.1}", "disturbance.pushes[1].force", "not a number"},
           {"{time: 1, body: chest, force: [0, 1, 0], duration: -0.1}", "disturbance.pushes[1].duration",
            "out of range"},
           {"{time: 1, body: chest, force: [0, 1, 0]}", "disturbance.pushes[1].duration", "missing"},
           {"{time: 1, body: chest, force: [0, 1, 0], duration: 0.1, speed: 2}", "disturbance.pushes[1].speed",
            "unknown key"},
           {"{time: [1], body: chest, force: [0, 1, 0], duration: 0.1}", "disturbance.pushes[1].time",
            "a list where one value belongs"},
       }) {
    const std::string msg = bad(item);
    EXPECT_NE(msg.find("'" + key + "'"), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
  }
  // Not a list of mappings; a list on a key of one value.
  EXPECT_NE(refusal("disturbance:\n  pushes: [1, 2]\n").find("item 0 is a name, not a mapping"), std::string::npos);
  EXPECT_NE(refusal("disturbance:\n  pushes: 3\n").find("'disturbance.pushes'"), std::string::npos);
  EXPECT_NE(refusal("disturbance:\n  push:\n    time: [1]\n").find("must be a single value, not a list"),
            std::string::npos);
  EXPECT_NE(refusal("", {"disturbance.pushes=[{time: 1}"}).find("--set: key 'disturbance.pushes'"), std::string::npos);
}

TEST(PushList, WrittenConfigurationReadsBackToTheSameRun) {
  const Config c =
      resolve_config(walk_run_schema(), write_temp("rt.yaml", kTwoPushes), {"disturbance.push.force_y=-40"});
  const std::string yaml = c.to_yaml();
  const Config back = resolve_config(walk_run_schema(), write_temp("rt2.yaml", yaml), {});
  EXPECT_EQ(back.to_yaml(), yaml);
  EXPECT_EQ(back.list("disturbance.pushes"), c.list("disturbance.pushes"));
  const WalkRunParams a = walk_run_from_config(c), b = walk_run_from_config(back);
  ASSERT_EQ(b.pushes.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(a.pushes[i].time, b.pushes[i].time);
    EXPECT_EQ(a.pushes[i].body, b.pushes[i].body);
    EXPECT_EQ(a.pushes[i].force, b.pushes[i].force);
    EXPECT_EQ(a.pushes[i].duration, b.pushes[i].duration);
  }
  EXPECT_EQ(b.push.force[1], -40.0);
  // The empty list too.
  const Config none = resolve_config(walk_run_schema(), std::nullopt, {});
  EXPECT_TRUE(walk_run_from_config(resolve_config(walk_run_schema(), write_temp("rt3.yaml", none.to_yaml()), {}))
                  .pushes.empty());
}

WalkRunParams standing() {
  WalkRunParams p;
  p.walk.steps = 0;
  p.walk.end_time = 0.5;  // 2 s in all
  return p;
}

TEST(PushList, TwoPushesBothApplied) {
  // A list push on the chest and the single push on the pelvis, overlapping over [1.05, 1.1):
  // the plant's impulse is their sum (exact, whole physics steps), and so is the robot's momentum
  // change less the floor's and gravity's impulses (1 %, as push_test.cpp's single push).
  const Push a{1.0, PushBody::kChest, {0, -150, 0}, 0.1}, b{1.05, PushBody::kPelvis, {200, 0, 0}, 0.05};
  twin::HumanoidPlant plant(humanoid::RobotParams{}, twin::PlantParams{});
  const humanoid::JointVector pose = twin::standing_pose(humanoid::RobotParams{}, 0.75);
  plant.reset(pose);
  plant.set_pushes(twin::all_pushes({a}, b));
  const double T = plant.params().control_period;
  const auto run_to = [&](double t) {
    while (plant.time() < t - 0.5 * T) plant.step(pose);
    return plant.truth();
  };
  const twin::GroundTruth s = run_to(1.0), e = run_to(1.1);
  const Eigen::Vector3d expected(200 * 0.05, -150 * 0.1, 0);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(e.push_impulse[i], expected(i), 1e-9 * expected.norm());
  EXPECT_TRUE(e.sole_contact[0] && e.sole_contact[1] && !e.non_sole_contact);
  Eigen::Vector3d measured;
  for (int i = 0; i < 3; ++i)
    measured(i) = (e.linear_momentum[i] - s.linear_momentum[i]) - (e.floor_impulse[i] - s.floor_impulse[i]);
  measured.z() += plant.total_mass() * plant.gravity() * (e.t - s.t);
  EXPECT_LT((measured - expected).norm(), 0.01 * expected.norm()) << measured.transpose();

  // Through run_walk: both logged (their sum while they overlap), push_impulse the net impulse.
  WalkRunParams p = standing();
  p.pushes = {a};
  p.push = b;
  const WalkResult r = run_walk(p);
  EXPECT_NEAR(r.metrics.push_impulse, expected.norm(), 1e-9 * expected.norm());
  for (const WalkSample& w : r.log) {
    const bool on_a = w.t > 1.0 + 1e-9 && w.t<1.1 + 1e-9, on_b = w.t> 1.05 + 1e-9 && w.t < 1.1 + 1e-9;
    EXPECT_DOUBLE_EQ(w.push_force[0], on_b ? 200.0 : 0.0) << "t = " << w.t;
    EXPECT_DOUBLE_EQ(w.push_force[1], on_a ? -150.0 : 0.0) << "t = " << w.t;
  }
  // Same bytes twice.
  const WalkResult again = run_walk(p);
  EXPECT_EQ(walk_log_csv(r), walk_log_csv(again));
  EXPECT_EQ(walk_summary_json(r), walk_summary_json(again));
}

TEST(PushList, SinglePushAloneOrInTheListSameBytes) {
  // The single push keys give the run they gave before the list existed: the same as that push
  // given as the list's only item.
  WalkRunParams single = standing(), listed = standing();
  single.push = Push{1.0, PushBody::kPelvis, {40, 0, 0}, 0.1};
  listed.pushes = {single.push};
  const WalkResult a = run_walk(single), b = run_walk(listed);
  EXPECT_EQ(walk_log_csv(a), walk_log_csv(b));
  EXPECT_EQ(walk_summary_json(a), walk_summary_json(b));
}

}  // namespace
}  // namespace flexgait::experiments

namespace flexgait::experiments {
namespace {

TEST(PushList, TimedByTheWalkingPhase) {
  // {step: 2, phase: 0.25}: the push starts a quarter into the second step's single support,
  // t = t_lift + 0.25 (t_land − t_lift) of plan step 2 (the field's definition), and acts for its
  // duration: every logged sample carries the force exactly while t ∈ (t*, t* + 0.05] (the
  // log's sample at t reports the physics step that ended at t; t* is on the 1 ms grid here).
  const std::string text =
      "walk:\n  steps: 3\noutput:\n  log_period: 0.004\ndisturbance:\n  pushes:\n"
      "    - {step: 2, phase: 0.25, body: pelvis, force: [0, 50, 0], duration: 0.05}\n";
  const WalkRunParams p = from_file(text);
  ASSERT_EQ(p.pushes.size(), 1u);
  EXPECT_EQ(p.pushes[0].step, 2);
  EXPECT_EQ(p.pushes[0].phase, 0.25);
  const walking::WalkPlan plan = walking::plan_footsteps(p.walk);
  const walking::Step& s = plan.steps.at(1);
  const double t_push = s.t_lift + 0.25 * (s.t_land - s.t_lift);
  EXPECT_DOUBLE_EQ(push_start_time(p.pushes[0], plan), t_push);
  Push by_time = p.pushes[0];
  by_time.step = 0;
  by_time.time = 1.25;
  EXPECT_EQ(push_start_time(by_time, plan), 1.25);  // step 0: its own time
  const WalkResult r = run_walk(p);
  int on = 0;
  for (const WalkSample& w : r.log) {
    const bool pushing = w.t > t_push + 1e-9 && w.t < t_push + 0.05 + 1e-9;
    EXPECT_DOUBLE_EQ(w.push_force[1], pushing ? 50.0 : 0.0) << "t = " << w.t;
    on += pushing;
  }
  EXPECT_GT(on, 10);
  EXPECT_NEAR(r.metrics.push_impulse, 50 * 0.05, 1e-9);

  // Left out at their defaults when written; the written file reads back to the same times.
  const Config c = resolve_config(walk_run_schema(), write_temp("phase.yaml", text), {});
  const std::string yaml = c.to_yaml();
  EXPECT_NE(yaml.find("{step: 2, phase: 0.25, body: pelvis"), std::string::npos) << yaml;
  const WalkRunParams back =
      walk_run_from_config(resolve_config(walk_run_schema(), write_temp("phase2.yaml", yaml), {}));
  EXPECT_EQ(back.pushes[0].step, 2);
  EXPECT_EQ(back.pushes[0].time, 0.0);
}

TEST(PushList, BadWalkingPhaseRefusedNamingTheKey) {
  const std::string head = "walk:\n  steps: 3\ndisturbance:\n  pushes:\n";
  const auto item = [&](const std::string& fields) { return refusal(head + "    - {" + fields + "}\n"); };
  const std::string rest = "body: chest, force: [0, 1, 0], duration: 0.1";
  EXPECT_NE(item("step: 4, " + rest).find("'disturbance.pushes[0].step' = '4': the walk has 3 steps"),
            std::string::npos);
  EXPECT_NE(item("time: 2, step: 1, " + rest).find("'disturbance.pushes[0].time'"), std::string::npos);
  EXPECT_NE(item("step: 1, phase: 1.5, " + rest).find("'disturbance.pushes[0].phase'"), std::string::npos);
  EXPECT_NE(item("step: -1, " + rest).find("'disturbance.pushes[0].step'"), std::string::npos);
  EXPECT_NE(refusal("walk:\n  steps: 3\n", {"disturbance.push.step=5", "disturbance.push.force_y=10"})
                .find("'disturbance.push.step' = '5'"),
            std::string::npos);
}

}  // namespace
}  // namespace flexgait::experiments
