#pragma once
/// \file replay_recorder.hpp
/// The twin as a replay scene (replay/scene.hpp), for `replay.html`: every body that has a visible
/// geom, its geoms' shapes read once from the model (primitives, meshes, the floor's plane, boxes
/// and height field) and its pose at each frame: the forward kinematics of the state's positions
/// qpos (MuJoCo's xpos and xquat after mj_step are those of the step's start); and, per frame,
/// the markers of RenderMarkers (the ZMP and the reference ZMP, the centre of mass's ground
/// projection, the capture point, the actual footprints as heel-to-toe bars, in the renderer's
/// colours), the push as an arrow, and the caller's signals. Planned footprints are drawn as flat
/// boxes from the start. Memory is bounded: at most `max_frames` frames; when full, every other
/// frame is dropped and the frame interval doubles. For evaluation and presentation only.
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "flexgait/replay/scene.hpp"
#include "flexgait/twin/plant.hpp"
#include "flexgait/twin/renderer.hpp"

namespace flexgait::twin {

class ReplayRecorder {
 public:
  /// `signals`: the values record() is given, in that order (name, unit and where the page plots
  /// them; their data are ignored). A frame every
  /// `frame_dt` > 0 [s] of simulated time (calls in between are ignored), at most `max_frames` ≥ 2
  /// (then the interval doubles). Throws std::invalid_argument for other values.
  ReplayRecorder(const HumanoidPlant& plant, std::string title, std::vector<replay::Signal> signals = {},
                 double frame_dt = 1.0 / 50.0, int max_frames = 6000);
  ~ReplayRecorder();
  ReplayRecorder(const ReplayRecorder&) = delete;
  ReplayRecorder& operator=(const ReplayRecorder&) = delete;

  /// Draws these footprints (the plan's) as flat translucent boxes on the floor, from the start.
  /// Before the first frame (std::logic_error after it).
  void set_planned_footprints(const std::vector<FootprintMarker>& footprints);

  /// Appends a frame at simulated time t [s] if one is due: every recorded body's pose, the
  /// markers' points and every actual footprint, recovery steps beyond the plan included (the
  /// planned ones and the overlay are not per frame: see set_planned_footprints), the push arrow (as Renderer draws it)
  /// and `values` (one per signal).
  void record(const HumanoidPlant& plant, double t, const RenderMarkers& markers = {},
              std::span<const double> values = {});

  const replay::Scene& scene() const { return scene_; }
  /// The model's body id of each recorded body, in the scene's order.
  const std::vector<int>& body_ids() const { return body_ids_; }
  /// The interval between frames now [s] (frame_dt, doubled each time the frames were thinned).
  double frame_dt() const { return frame_dt_; }

 private:
  struct Kinematics;  ///< a scratch state for the forward kinematics
  std::unique_ptr<Kinematics> kinematics_;
  replay::Scene scene_;
  std::vector<int> body_ids_;
  double frame_dt_, next_ = 0;
  int max_frames_;
};

}  // namespace flexgait::twin
