#pragma once
/// \file replay_recorder.hpp
/// The twin as a replay scene (replay/scene.hpp), for `replay.html`: every body that has a visible
/// geom, its geoms' shapes read once from the model (primitives, meshes, the floor's plane, boxes
/// and height field) and its pose (xpos, xquat) read from the state at each frame; and, per frame,
/// what only the controller knows (the ZMP, the centre of mass's ground projection, the capture
/// point), the push as an arrow, and the caller's signals. Planned footprints are drawn as flat
/// boxes from the start. For evaluation and presentation only.
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "flexgait/replay/scene.hpp"
#include "flexgait/twin/plant.hpp"
#include "flexgait/twin/renderer.hpp"

namespace flexgait::humanoid {

class ReplayRecorder {
 public:
  /// `signals`: (name, unit) of the values record() is given, in that order. A frame every
  /// `frame_dt` [s] of simulated time (calls in between are ignored).
  ReplayRecorder(const HumanoidPlant& plant, std::string title,
                 std::vector<std::pair<std::string, std::string>> signals = {}, double frame_dt = 1.0 / 50.0);

  /// Draws these footprints (the plan's) as flat translucent boxes on the floor, from the start.
  void set_planned_footprints(const std::vector<FootprintMarker>& footprints);

  /// Appends a frame at simulated time t [s] if one is due: every recorded body's pose, the
  /// markers' points (planned and actual footprints and the overlay are not per frame: see
  /// set_planned_footprints), the push arrow (as Renderer draws it) and `values` (one per signal).
  void record(const HumanoidPlant& plant, double t, const RenderMarkers& markers = {},
              std::span<const double> values = {});

  const replay::Scene& scene() const { return scene_; }
  /// The model's body id of each recorded body, in the scene's order.
  const std::vector<int>& body_ids() const { return body_ids_; }

 private:
  replay::Scene scene_;
  std::vector<int> body_ids_;
  double frame_dt_, next_ = 0;
};

}  // namespace flexgait::humanoid
