// A walk's files (experiments/walk_output.hpp) from a hand-made result: log.csv and joints.csv have
// a row per sample and are the Tables' text byte for byte (the bindings' arrays), footsteps.csv has
// the initial feet and every planned step with its landing (empty cells for steps not landed),
// summary.json is the metrics record (plus the stiffness estimates when estimated), and write_walk
// writes the five files.
#include "flexgait/experiments/walk_output.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/walking/footstep_plan.hpp"

namespace flexgait::experiments {
namespace {

// The lines of a file's text (each ends in '\n').
std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out = split_text(text, '\n');
  out.pop_back();
  return out;
}

WalkResult made_result() {
  WalkResult r;
  walking::WalkParams w;
  w.steps = 3;
  r.plan = walking::plan_footsteps(w);
  for (int i = 0; i < 4; ++i) {
    WalkSample s;
    s.t = 0.004 * i;
    s.step = i / 2;
    s.zmp_ref_x = 0.01 * i;
    s.desired[humanoid::kLeftHipRoll] = 0.02 * i;
    r.log.push_back(s);
  }
  Landing l;
  l.actual_x = 0.25;
  l.error = 0.003;
  r.landings.push_back(l);  // one of three steps landed
  r.metrics.steps_completed = 1;
  return r;
}

TEST(WalkOutput, LogAndJointsHaveARowPerSampleAndAreTheTablesText) {
  const WalkResult r = made_result();
  const auto log = lines(walk_log_csv(r));
  ASSERT_EQ(log.size(), r.log.size() + 1);
  EXPECT_EQ(log[0].rfind("t,step,zmp_ref_x,", 0), 0u) << log[0];
  EXPECT_EQ(walk_log_table(r).csv(), walk_log_csv(r));
  EXPECT_EQ(walk_joints_table(r).csv(), walk_joints_csv(r));
  EXPECT_EQ(lines(walk_joints_csv(r)).size(), r.log.size() + 1);
  const Table table = walk_log_table(r);
  EXPECT_EQ(table.columns()[2].name, "zmp_ref_x");
  EXPECT_EQ(table.columns()[2].numbers[3], 0.03);
}

TEST(WalkOutput, ColumnsByNameAreTheFilesCells) {
  WalkResult r = made_result();
  r.log[3].foot_force = {512.5, -3.25};
  r.log[3].torque_true[humanoid::kRightAnkleRoll] = 7.5;
  const WalkColumns columns({"zmp_ref_x", "l_ft_fz", "r_ft_fz", "r_ankle_roll_torque_true", "step", "t"});
  const std::vector<double> v = columns.values(r.log[3]);
  // The cells of the files' row (log.csv, then joints.csv for a name log.csv lacks).
  const Table log = walk_log_table(r), joints = walk_joints_table(r);
  auto cell = [](const Table& t, const std::string& name) {
    for (const auto& c : t.columns())
      if (c.name == name) return c.numbers.at(3);
    ADD_FAILURE() << name;
    return 0.0;
  };
  EXPECT_EQ(v, (std::vector<double>{cell(log, "zmp_ref_x"), cell(log, "l_ft_fz"), cell(log, "r_ft_fz"),
                                    cell(joints, "r_ankle_roll_torque_true"), cell(log, "step"), cell(log, "t")}));
  EXPECT_EQ(v[1], 512.5);
  EXPECT_EQ(v[3], 7.5);
  EXPECT_THROW(WalkColumns({"zmp_ref_z"}), std::invalid_argument);
  EXPECT_THROW(WalkColumns({"k_est_l_knee"}), std::invalid_argument);  // only with the stiffness estimates
  EXPECT_NO_THROW(WalkColumns({"k_est_l_knee"}, true));
}

TEST(WalkOutput, FootstepsListTheInitialFeetAndEveryStepWithItsLanding) {
  const WalkResult r = made_result();
  const auto rows = lines(walk_footsteps_csv(r));
  ASSERT_EQ(rows.size(), 1u + 2u + r.plan.steps.size());
  EXPECT_EQ(rows[0], "kind,step,side,x,y,yaw,landed_x,landed_y,landed_yaw,error");
  EXPECT_EQ(rows[1].rfind("initial,-1,left,", 0), 0u);
  EXPECT_EQ(rows[2].rfind("initial,-1,right,", 0), 0u);
  EXPECT_EQ(rows[3].rfind("step,0,", 0), 0u);
  EXPECT_NE(rows[3].find(",0.25,"), std::string::npos) << rows[3];   // landed
  EXPECT_EQ(rows[4].substr(rows[4].size() - 4), ",,,,") << rows[4];  // not landed: four empty cells
}

TEST(WalkOutput, SummaryIsTheMetricsAndTheEstimatesWhenEstimated) {
  WalkResult r = made_result();
  nlohmann::json j = nlohmann::json::parse(walk_summary_json(r));
  EXPECT_EQ(j["steps_completed"], 1);
  EXPECT_FALSE(j.contains("k_estimate"));
  r.k_estimation = true;
  r.k_identified[humanoid::kLeftHipRoll] = r.k_identified[humanoid::kRightHipRoll] = true;
  r.k_estimate[humanoid::kLeftHipRoll] = 900.0;
  r.k_estimate[humanoid::kRightHipRoll] = 1100.0;
  r.k_relative_std[humanoid::kLeftHipRoll] = 0.003;
  j = nlohmann::json::parse(walk_summary_json(r));
  EXPECT_EQ(j["k_estimate"].size(), 2u);
  EXPECT_EQ(j["k_estimate_mean"], 1000.0);
  EXPECT_EQ(j["k_estimate_relative_std"].size(), 2u);  // each identified joint's confidence
  EXPECT_EQ(j["k_estimate_relative_std"]["l_hip_roll"], 0.003);
  EXPECT_EQ(walk_summary_json(r), walk_summary_json(r));  // deterministic
  // Wall-clock numbers only in timing.json.
  EXPECT_FALSE(j.contains("wall_time"));
  EXPECT_TRUE(nlohmann::json::parse(walk_timing_json(r)).contains("wall_time"));
}

TEST(WalkOutput, WriteWalkWritesTheFiveFilesUnderItsSubfolder) {
  const auto dir = std::filesystem::temp_directory_path() / ("flexgait_walk_output_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const WalkResult r = made_result();
  std::string summary;
  {
    const RunDirectory run(dir);
    summary = json_file_text(write_walk(run, "case/", r));
  }
  for (const char* f : {"log.csv", "footsteps.csv", "joints.csv", "summary.json", "timing.json"})
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "case" / f)) << f;
  EXPECT_EQ(read_text_file(dir / "case" / "summary.json"), summary);
  EXPECT_EQ(read_text_file(dir / "case" / "log.csv"), walk_log_csv(r));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace flexgait::experiments
