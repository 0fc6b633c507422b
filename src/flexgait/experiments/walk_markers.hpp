#pragma once
/// \file walk_markers.hpp
/// What a picture of the walk shows beside the robot, as an observer of the closed loop
/// (loop/closed_loop.hpp): the plan's footprints and where the soles really landed, the true ZMP
/// (contact forces) and the controller's reference ZMP, the centre of mass's ground projection, the
/// capture point, and a line of text (time, step, phase, compensation mode). The renderer
/// (twin/renderer.hpp) and the replay recorder (twin/replay_recorder.hpp) draw them; this class
/// only reads the loop and the walking controller. Evaluation code: it changes nothing of the walk.
#include <Eigen/Core>

#include <vector>

#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/loop/closed_loop.hpp"
#include "flexgait/twin/renderer.hpp"

namespace flexgait::experiments {

class WalkMarkers final : public loop::LoopObserver {
 public:
  /// \param controller the walking controller of the loop (its plan and status are read each period)
  /// \param initial the twin's truth at the start (the plan's frame is found from its feet)
  WalkMarkers(const WalkRunParams& params, const walking::WalkingController& controller,
              const twin::GroundTruth& initial);

  void observe(const loop::LoopStep& step) override;

  /// The markers after the last observed period, in the world frame [m].
  const twin::RenderMarkers& markers() const { return markers_; }
  /// The controller's plan's footprints now (the start's two, then each step's landing), in the
  /// world on `terrain`.
  std::vector<twin::FootprintMarker> planned(const twin::Terrain& terrain) const;
  /// The plan's frame in the world: world = plan + offset (x, y) [m].
  const Eigen::Vector2d& offset() const { return offset_; }

 private:
  twin::FootprintMarker footprint(double x, double y, double yaw, const twin::Terrain& terrain) const;

  const WalkRunParams& params_;
  const walking::WalkingController& controller_;
  Eigen::Vector2d offset_ = Eigen::Vector2d::Zero();
  double settle_ = 0;             ///< a landing is taken this long after touchdown (as WalkScorer's) [s]
  std::size_t next_landing_ = 0;  ///< the plan's next step not yet landed
  twin::RenderMarkers markers_;
};

}  // namespace flexgait::experiments
