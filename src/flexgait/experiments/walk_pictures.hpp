#pragma once
/// \file walk_pictures.hpp
/// Pictures of a walk as an observer of its closed loop (loop/closed_loop.hpp): the walk's
/// markers (walk_markers.hpp) drawn over the twin by the offscreen renderer (twin/renderer.hpp)
/// at a frame rate, and a replay scene (twin/replay_recorder.hpp) recorded at the log's samples
/// for `replay.html`. Evaluation and presentation only: it changes nothing of the walk.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/experiments/walk_markers.hpp"
#include "flexgait/experiments/walk_output.hpp"
#include "flexgait/twin/renderer.hpp"
#include "flexgait/twin/replay_recorder.hpp"

namespace flexgait::experiments {

struct WalkPictureOptions {
  /// Draw frames from this view (none: no frames), one every `render_every` control periods,
  /// from the first period on.
  std::optional<twin::RenderView> render;
  long render_every = 1;
  /// Record the replay scene: a frame at the log's samples (WalkRunParams::log_period) every
  /// `replay_frame_dt` [s] of simulated time (25 frames per second: every other 0.02 s sample),
  /// at most `replay_max_frames` (then every other frame is dropped; ReplayRecorder).
  bool replay = false;
  double replay_frame_dt = 0.04;
  int replay_max_frames = 6000;
};

class WalkPictures final : public loop::LoopObserver {
 public:
  /// The replay's plotted signals for this run, in panels (ZMP, COM and capture point, pelvis,
  /// gears, feet): log.csv's and joints.csv's columns (named by the column, or "a - b" for a
  /// difference of two), the plan's frame; and the true capture point (the page's marker, named
  /// capture_point_x/y, not a column). The DCM's columns only in balance mode dcm, the push's only
  /// with a push.
  static std::vector<replay::Signal> replay_signals(const WalkRunParams& params, bool pushed);

  /// `walk`: the loop made by make_walk_loop, before its first period. `frame(rgb, index)` takes
  /// each drawn frame (RGB rows top to bottom, view width × height × 3 bytes).
  WalkPictures(const WalkRunParams& params, WalkLoop& walk, const WalkPictureOptions& options,
               std::function<void(const std::vector<unsigned char>& rgb, int index)> frame = {});

  void observe(const loop::LoopStep& step) override;
  /// The log's sample of this period (run_walk's `record`): the replay's frame at this time plots
  /// its columns. WalkScorer logs a period's sample before this observer sees the period (run_walk
  /// attaches it first); a frame without its sample plots nothing (NaN).
  void log_sample(const WalkSample& sample);

  /// The frames drawn so far.
  int frames() const { return frames_; }
  const WalkMarkers& markers() const { return markers_; }
  /// The renderer of the frames (null unless options.render), e.g. to draw a state without markers.
  twin::Renderer* renderer() { return renderer_.get(); }
  /// The replay scene recorded (null unless options.replay).
  const twin::ReplayRecorder* replay() const { return replay_.get(); }

 private:
  const walking::WalkingController& controller_;
  WalkPictureOptions options_;
  std::function<void(const std::vector<unsigned char>&, int)> frame_;
  WalkMarkers markers_;
  std::unique_ptr<twin::Renderer> renderer_;
  std::unique_ptr<twin::ReplayRecorder> replay_;
  long log_every_ = 1;
  int frames_ = 0;
  struct ColumnSignal {
    std::size_t column = 0, minus = std::string::npos;  ///< value = column − minus (minus: none when npos)
    int capture = -1;                                   ///< 0, 1: the capture point's x, y instead
  };
  std::vector<ColumnSignal> columns_;  ///< where each of the replay's signals comes from
  std::unique_ptr<WalkColumns> log_columns_;
  std::vector<double> sample_values_;  ///< log_columns_'s values of the last logged sample
  double sample_t_ = -1;               ///< its time [s]
};

}  // namespace flexgait::experiments
