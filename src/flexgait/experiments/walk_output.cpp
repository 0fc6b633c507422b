#include "flexgait/experiments/walk_output.hpp"

#include <nlohmann/json.hpp>

#include "flexgait/core/record_json.hpp"
#include "flexgait/core/text.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace flexgait::experiments {
namespace {

// The columns and rows of log.csv and joints.csv, into a CsvWriter (the files, whole or streamed)
// or a Table (the bindings).
std::vector<std::string> log_header() {
  return {"t",
          "step",
          "zmp_ref_x",
          "zmp_ref_y",
          "zmp_ft_x",
          "zmp_ft_y",
          "zmp_true_x",
          "zmp_true_y",
          "com_ref_x",
          "com_ref_y",
          "com_x",
          "com_y",
          "com_z",
          "pelvis_z",
          "imu_roll",
          "imu_pitch",
          "roll_correction",
          "pitch_correction",
          "support_margin",
          "roll_kin_encoder",
          "roll_kin_estimate",
          "l_sole_x",
          "l_sole_y",
          "l_sole_z",
          "r_sole_x",
          "r_sole_y",
          "r_sole_z",
          "roll_true",
          "pitch_true",
          "sensor_faults",
          "safe_stop",
          "push_force_x",
          "push_force_y",
          "push_force_z",
          "dcm_x",
          "dcm_y",
          "dcm_ref_x",
          "dcm_ref_y",
          "dcm_error_x",
          "dcm_error_y",
          "l_ft_fz",
          "r_ft_fz",
          "pelvis_x",
          "pelvis_y"};
}

template <class Writer>
void log_row(Writer& csv, const WalkSample& w) {
  csv.cell(w.t).cell(static_cast<long long>(w.step)).cell(w.zmp_ref_x).cell(w.zmp_ref_y).cell(w.zmp_ft_x);
  csv.cell(w.zmp_ft_y).cell(w.zmp_true_x).cell(w.zmp_true_y).cell(w.com_ref_x).cell(w.com_ref_y).cell(w.com_x);
  csv.cell(w.com_y).cell(w.com_z).cell(w.pelvis_z).cell(w.imu_roll).cell(w.imu_pitch).cell(w.roll_correction);
  csv.cell(w.pitch_correction).cell(w.support_margin).cell(w.roll_kin_encoder).cell(w.roll_kin_estimate);
  for (const auto& s : w.sole) csv.cell(s[0]).cell(s[1]).cell(s[2]);
  csv.cell(w.roll_true).cell(w.pitch_true).cell(static_cast<long long>(w.sensor_faults));
  csv.cell(static_cast<long long>(w.safe_stop ? 1 : 0));
  for (const double f : w.push_force) csv.cell(f);
  csv.cell(w.dcm[0])
      .cell(w.dcm[1])
      .cell(w.dcm_ref[0])
      .cell(w.dcm_ref[1])
      .cell(w.dcm[0] - w.dcm_ref[0])
      .cell(w.dcm[1] - w.dcm_ref[1]);
  csv.cell(w.foot_force[0]).cell(w.foot_force[1]).cell(w.pelvis_x).cell(w.pelvis_y);
  csv.end_row();
}

constexpr std::array<std::string_view, 10> kJointFields = {
    "desired",   "command",      "encoder",         "link",       "estimate", "conventional",
    "per_joint", "torque_model", "torque_estimate", "torque_true"};

std::vector<std::string> joints_header(bool k_estimation) {
  std::vector<std::string> header{"t"};
  for (int j = humanoid::kLeftHipYaw; j < humanoid::kJoints; ++j)
    for (const auto f : kJointFields) header.push_back(std::string(humanoid::kJointNames[j]) + "_" + std::string(f));
  // control.k_estimation on: each leg joint's stiffness estimate over time.
  if (k_estimation)
    for (int j = humanoid::kLeftHipYaw; j < humanoid::kJoints; ++j)
      header.push_back("k_est_" + std::string(humanoid::kJointNames[j]));
  return header;
}

template <class Writer>
void joints_row(Writer& csv, const WalkSample& w, bool k_estimation) {
  csv.cell(w.t);
  for (int j = humanoid::kLeftHipYaw; j < humanoid::kJoints; ++j) {
    csv.cell(w.desired[j]).cell(w.command[j]).cell(w.encoder[j]).cell(w.link[j]).cell(w.estimate[j]);
    csv.cell(w.conventional[j]).cell(w.per_joint[j]).cell(w.torque_model[j]).cell(w.torque_estimate[j]);
    csv.cell(w.torque_true[j]);
  }
  if (k_estimation)
    for (int j = humanoid::kLeftHipYaw; j < humanoid::kJoints; ++j) csv.cell(w.k_estimate[j]);
  csv.end_row();
}

template <class Writer>
Writer walk_log_rows(const WalkResult& r) {
  Writer csv(log_header());
  for (const auto& w : r.log) log_row(csv, w);
  return csv;
}

template <class Writer>
Writer walk_joints_rows(const WalkResult& r) {
  Writer csv(joints_header(r.k_estimation));
  for (const auto& w : r.log) joints_row(csv, w, r.k_estimation);
  return csv;
}

/// A row's cells as numbers, the calls of CsvWriter and Table (log_row, joints_row): the numbers
/// Table's columns would hold for that row.
struct RowNumbers {
  std::vector<double> numbers;
  RowNumbers& cell(double v) {
    numbers.push_back(v);
    return *this;
  }
  RowNumbers& cell(long long v) { return cell(static_cast<double>(v)); }
  void end_row() {}
};

}  // namespace

WalkColumns::WalkColumns(const std::vector<std::string>& names, bool k_estimation) : k_estimation_(k_estimation) {
  const std::vector<std::string> log = log_header(), joints = joints_header(k_estimation);
  for (const std::string& name : names) {
    const auto in_log = std::find(log.begin(), log.end(), name);
    const auto in_joints = std::find(joints.begin(), joints.end(), name);
    if (in_log != log.end())
      where_.emplace_back(false, static_cast<std::size_t>(in_log - log.begin()));
    else if (in_joints != joints.end())
      where_.emplace_back(true, static_cast<std::size_t>(in_joints - joints.begin()));
    else
      throw std::invalid_argument("WalkColumns: no column " + name + " in log.csv or joints.csv");
  }
}

std::vector<double> WalkColumns::values(const WalkSample& sample) const {
  // One row of each file by the writers of the files themselves (the values are the files'), into
  // a row of numbers as Table holds them (an integer cell as its double): no header per sample.
  RowNumbers log, joints;
  log_row(log, sample);
  joints_row(joints, sample, k_estimation_);
  std::vector<double> out;
  out.reserve(where_.size());
  for (const auto& [in_joints, column] : where_) out.push_back((in_joints ? joints : log).numbers.at(column));
  return out;
}

std::string walk_log_csv(const WalkResult& r) {
  return walk_log_rows<CsvWriter>(r).str();
}
std::string walk_joints_csv(const WalkResult& r) {
  return walk_joints_rows<CsvWriter>(r).str();
}
Table walk_log_table(const WalkResult& r) {
  return walk_log_rows<Table>(r);
}
Table walk_joints_table(const WalkResult& r) {
  return walk_joints_rows<Table>(r);
}

std::string walk_footsteps_csv(const WalkResult& r) {
  CsvWriter csv({"kind", "step", "side", "x", "y", "yaw", "landed_x", "landed_y", "landed_yaw", "error"});
  for (int side = 0; side < 2; ++side) {
    const auto& f = r.plan.initial[side];
    csv.cell("initial").cell(-1LL).cell(side == 0 ? "left" : "right").cell(f.x).cell(f.y).cell(f.yaw);
    csv.cell(f.x).cell(f.y).cell(f.yaw).cell(0.0).end_row();
  }
  for (std::size_t i = 0; i < r.plan.steps.size(); ++i) {
    const auto& s = r.plan.steps[i];
    csv.cell("step").cell(static_cast<long long>(i)).cell(s.swing == 0 ? "left" : "right").cell(s.to.x).cell(s.to.y);
    csv.cell(s.to.yaw);
    if (i < r.landings.size()) {
      const auto& l = r.landings[i];
      csv.cell(l.actual_x).cell(l.actual_y).cell(l.actual_yaw).cell(l.error);
    } else {
      csv.cell("").cell("").cell("").cell("");
    }
    csv.end_row();
  }
  return csv.str();
}

nlohmann::ordered_json walk_summary(const WalkResult& r) {
  nlohmann::ordered_json j = record_json(r.metrics);
  if (r.k_estimation) {
    // The identified joints' final estimates (the leg roll and pitch joints) and their mean
    // (docs/guide/compensation.md).
    // With each one's confidence, its relative standard deviation (the compensators use it once at most
    // control.k_estimation_confidence).
    nlohmann::ordered_json k = nlohmann::ordered_json::object(), std = nlohmann::ordered_json::object();
    double sum = 0;
    int n = 0;
    for (int i = 0; i < humanoid::kJoints; ++i)
      if (r.k_identified[i]) {
        k[std::string(humanoid::kJointNames[i])] = r.k_estimate[i];
        std[std::string(humanoid::kJointNames[i])] = r.k_relative_std[i];
        sum += r.k_estimate[i];
        ++n;
      }
    j["k_estimate"] = k;
    j["k_estimate_mean"] = n > 0 ? sum / n : 0.0;
    j["k_estimate_relative_std"] = std;
  }
  return j;
}

std::string walk_summary_json(const WalkResult& r) {
  return json_file_text(walk_summary(r));
}

nlohmann::ordered_json walk_timing(const WalkResult& r) {
  nlohmann::ordered_json j;
  j["simulated_time"] = r.metrics.simulated_time;
  j["wall_time"] = r.metrics.wall_time;
  j["real_time_factor"] = r.metrics.real_time_factor;
  return j;
}

std::string walk_timing_json(const WalkResult& r) {
  return json_file_text(walk_timing(r));
}

WalkLogWriter::WalkLogWriter(const RunDirectory& dir, const std::string& sub, bool k_estimation)
    : log_(make_parent(dir.path() / sub) / "log.csv"),
      joints_(dir.path() / sub / "joints.csv"),
      log_csv_(log_header()),
      joints_csv_(joints_header(k_estimation)),
      k_estimation_(k_estimation) {}

std::filesystem::path WalkLogWriter::make_parent(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  return dir;
}

void WalkLogWriter::add(const WalkSample& w) {
  log_row(log_csv_, w);
  joints_row(joints_csv_, w, k_estimation_);
  if (++pending_ >= kRowsPerWrite) flush();
}

void WalkLogWriter::flush() {
  log_.append(log_csv_.str());
  joints_.append(joints_csv_.str());
  log_csv_.clear();
  joints_csv_.clear();
  pending_ = 0;
}

void WalkLogWriter::commit() {
  flush();
  log_.commit();
  joints_.commit();
}

nlohmann::ordered_json write_walk(const RunDirectory& dir, const std::string& sub, const WalkResult& r) {
  if (!sub.empty()) std::filesystem::create_directories(dir.path() / sub);
  if (!r.log_streamed) {
    dir.write(sub + "log.csv", walk_log_csv(r));
    dir.write(sub + "joints.csv", walk_joints_csv(r));
  }
  dir.write(sub + "footsteps.csv", walk_footsteps_csv(r));
  nlohmann::ordered_json summary = walk_summary(r);
  dir.write(sub + "summary.json", json_file_text(summary));
  dir.write(sub + "timing.json", walk_timing_json(r));
  return summary;
}

}  // namespace flexgait::experiments
