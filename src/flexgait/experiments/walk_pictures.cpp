#include "flexgait/experiments/walk_pictures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "flexgait/core/enum_names.hpp"

namespace flexgait::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kCaptureX = "capture_point_x";
constexpr const char* kCaptureY = "capture_point_y";
constexpr std::string_view kMinus = " - ";

struct Line {
  std::string name, label;  ///< a column, "a - b" or a capture point; its legend
};
struct Plot {
  const char *panel, *title, *unit;
  std::vector<Line> lines;
};

/// A (left, right) pair of lines of a joint's column (field "torque_true", or "encoder - link").
std::vector<Line> both_legs(const char* joint, const char* field, const char* minus = nullptr) {
  std::vector<Line> lines;
  for (const char* side : {"l", "r"}) {
    std::string name = fmt::format("{}_{}_{}", side, joint, field);
    if (minus != nullptr) name += fmt::format("{}{}_{}_{}", kMinus, side, joint, minus);
    lines.push_back({name, side == std::string_view("l") ? "left" : "right"});
  }
  return lines;
}

}  // namespace

std::vector<replay::Signal> WalkPictures::replay_signals(const WalkRunParams& params, bool pushed) {
  const bool dcm = params.balance.mode == walking::BalanceMode::kDcm;
  std::vector<Line> forward{{"com_ref_x", "planned COM"}, {"com_x", "COM"}, {kCaptureX, "capture point"}};
  std::vector<Line> lateral{{"com_ref_y", "planned COM"}, {"com_y", "COM"}, {kCaptureY, "capture point"}};
  if (dcm) {
    forward.insert(forward.end(), {{"dcm_ref_x", "planned DCM"}, {"dcm_x", "controller's DCM"}});
    lateral.insert(lateral.end(), {{"dcm_ref_y", "planned DCM"}, {"dcm_y", "controller's DCM"}});
  }
  std::vector<Plot> plots{
      {"ZMP",
       "ZMP x",
       "m",
       {{"zmp_ref_x", "planned"}, {"zmp_ft_x", "measured (F/T)"}, {"zmp_true_x", "true (contact forces)"}}},
      {"ZMP",
       "ZMP y",
       "m",
       {{"zmp_ref_y", "planned"}, {"zmp_ft_y", "measured (F/T)"}, {"zmp_true_y", "true (contact forces)"}}},
      {"ZMP", "ZMP error (true − planned)", "m", {{"zmp_true_x - zmp_ref_x", "x"}, {"zmp_true_y - zmp_ref_y", "y"}}},
      {"ZMP", "support margin (true ZMP to the soles' edge)", "m", {{"support_margin", "margin"}}},
      {"COM, capture point", "lateral: COM and capture point y", "m", lateral},
      {"COM, capture point", "forward: COM and capture point x", "m", forward},
      {"COM, capture point",
       "COM error (true − planned)",
       "m",
       {{"com_x - com_ref_x", "x"}, {"com_y - com_ref_y", "y"}}},
      {"pelvis",
       "pelvis roll (error from level)",
       "rad",
       {{"roll_true", "true"}, {"imu_roll", "estimated (IMU)"}, {"roll_correction", "balance correction"}}},
      {"pelvis",
       "pelvis pitch (error from level)",
       "rad",
       {{"pitch_true", "true"}, {"imu_pitch", "estimated (IMU)"}, {"pitch_correction", "balance correction"}}},
      {"pelvis", "pelvis height", "m", {{"pelvis_z", "true"}}},
      {"gears", "hip roll gear torque", "N m", both_legs("hip_roll", "torque_true")},
      {"gears", "ankle roll gear torque", "N m", both_legs("ankle_roll", "torque_true")},
      {"gears", "hip roll deflection (encoder − link)", "rad", both_legs("hip_roll", "encoder", "link")},
      {"gears", "ankle roll deflection (encoder − link)", "rad", both_legs("ankle_roll", "encoder", "link")},
      {"feet", "F/T normal force", "N", {{"l_ft_fz", "left"}, {"r_ft_fz", "right"}}},
      {"feet", "sole height", "m", {{"l_sole_z", "left"}, {"r_sole_z", "right"}}}};
  if (pushed)
    plots.push_back({"feet", "push force", "N", {{"push_force_x", "x"}, {"push_force_y", "y"}, {"push_force_z", "z"}}});
  std::vector<replay::Signal> signals;
  for (const Plot& p : plots)
    for (const Line& l : p.lines) signals.push_back({l.name, p.unit, {}, p.panel, p.title, l.label});
  return signals;
}

WalkPictures::WalkPictures(const WalkRunParams& params, WalkLoop& walk, const WalkPictureOptions& options,
                           std::function<void(const std::vector<unsigned char>&, int)> frame)
    : controller_(walk.control->controller()),
      options_(options),
      frame_(std::move(frame)),
      markers_(params, walk.control->controller(), walk.loop->truth()),
      log_every_(std::max(1L, std::lround(params.log_period / params.plant.control_period))) {
  if (options_.render) renderer_ = std::make_unique<twin::Renderer>(walk.loop->plant(), *options_.render);
  if (!options_.replay) return;
  std::vector<replay::Signal> signals = replay_signals(params, !walk.pushes.empty());
  std::vector<std::string> names;  // the log's columns the signals read
  auto column = [&](const std::string& name) {
    const auto at = std::find(names.begin(), names.end(), name);
    if (at != names.end()) return static_cast<std::size_t>(at - names.begin());
    names.push_back(name);
    return names.size() - 1;
  };
  for (const replay::Signal& sig : signals) {
    const std::size_t minus = sig.name.find(kMinus);
    if (sig.name == kCaptureX || sig.name == kCaptureY)
      columns_.push_back({.capture = sig.name == kCaptureX ? 0 : 1});
    else if (minus == std::string::npos)
      columns_.push_back({.column = column(sig.name)});
    else
      columns_.push_back(
          {.column = column(sig.name.substr(0, minus)), .minus = column(sig.name.substr(minus + kMinus.size()))});
  }
  log_columns_ = std::make_unique<WalkColumns>(names, params.control.k_estimation != compensation::KEstimation::kOff);
  const walking::WalkPlan& plan = controller_.plan();
  replay_ = std::make_unique<twin::ReplayRecorder>(
      walk.loop->plant(),
      fmt::format("humanoid walk: {} steps, compensation {}", plan.steps.size(), name_of(params.control.mode)),
      std::move(signals), options_.replay_frame_dt, options_.replay_max_frames);
  replay_->set_planned_footprints(markers_.planned(walk.loop->plant().terrain()));
}

void WalkPictures::observe(const loop::LoopStep& step) {
  if (step.failure) return;
  markers_.observe(step);
  if (renderer_ && step.k % options_.render_every == 0) {
    if (frame_) frame_(renderer_->render(step.plant, markers_.markers()), frames_);
    ++frames_;
  }
  // (at the log's samples, as WalkScorer logs them: a frame's time is a row's of log.csv)
  if (replay_ && step.k % log_every_ == 0) {
    const twin::GroundTruth& g = step.after;
    const Eigen::Vector2d& o = markers_.offset();
    const bool logged = sample_t_ == g.t;  // (the same double: this period's sample)
    const auto& xi = markers_.markers().capture_point;
    std::vector<double> values;
    values.reserve(columns_.size());
    for (const ColumnSignal& c : columns_) {
      if (c.capture >= 0)  // the capture point marker, in the plan's frame
        values.push_back(!xi ? kNaN : (*xi)[static_cast<std::size_t>(c.capture)] - o[c.capture]);
      else if (!logged)
        values.push_back(kNaN);
      else
        values.push_back(sample_values_[c.column] - (c.minus == std::string::npos ? 0.0 : sample_values_[c.minus]));
    }
    replay_->record(step.plant, g.t, markers_.markers(), values);
  }
}

void WalkPictures::log_sample(const WalkSample& sample) {
  if (!log_columns_) return;
  sample_values_ = log_columns_->values(sample);
  sample_t_ = sample.t;
}

}  // namespace flexgait::experiments
