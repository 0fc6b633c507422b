#include "flexgait/experiments/walk_pictures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "flexgait/core/enum_names.hpp"

namespace flexgait::experiments {

WalkPictures::WalkPictures(const WalkRunParams& params, WalkLoop& walk, const WalkPictureOptions& options,
                           std::function<void(const std::vector<unsigned char>&, int)> frame)
    : controller_(walk.control->controller()),
      options_(options),
      frame_(std::move(frame)),
      markers_(params, walk.control->controller(), walk.loop->truth()),
      log_every_(std::max(1L, std::lround(params.log_period / params.plant.control_period))) {
  if (options_.render) renderer_ = std::make_unique<twin::Renderer>(walk.loop->plant(), *options_.render);
  if (!options_.replay) return;
  std::vector<std::pair<std::string, std::string>> signals;
  for (const char* name : kReplaySignals) signals.emplace_back(name, "m");
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
    const walking::ControllerStatus& st = controller_.status();
    const Eigen::Vector2d& o = markers_.offset();
    const std::array<double, kReplaySignals.size()> values{g.com[0] - o.x(), g.com[1] - o.y(), g.zmp[1] - o.y(),
                                                           st.zmp_ref.y(), g.pelvis_pos[2]};
    replay_->record(step.plant, g.t, markers_.markers(), values);
  }
}

}  // namespace flexgait::experiments
