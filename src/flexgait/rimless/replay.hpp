#pragma once
/// \file replay.hpp
/// The wheel as a replay scene (replay/scene.hpp), recorded from a run's log samples as they come:
/// the slope, the hub, each leg's spring from the hub to its foot, the feet coloured by contact
/// mode (stick, slip, free) and the ground reaction of each foot on the ground as two arrows
/// (normal N along the slope normal, friction T along the slope).
///
/// Geometry (docs/theory/rimless.md, "Coordinates and legs"): leg k makes the angle
/// β_k = θ + 2αk with the slope normal; a foot on the ground sits at (c_k, 0) in the slope's
/// frame, a free foot at hub − L0 (sin β_k, cos β_k) (drawn at rest length: the free leg's
/// relaxing compression is not in the log). The slope frame (x down the slope, y along its normal)
/// is the world's x–z plane turned by φ about +y: (x, y) ↦ (x cos φ + y sin φ, 0, −x sin φ + y cos φ).
#include <array>
#include <string>
#include <vector>

#include "flexgait/replay/scene.hpp"
#include "flexgait/rimless/parameters.hpp"
#include "flexgait/rimless/simulation.hpp"

namespace flexgait::rimless {

/// A point (x, y) of the slope's frame in the world (z up) [m].
std::array<double, 3> slope_to_world(const WheelParams& w, double x, double y);

/// Records a frame every `frame_dt` of simulated time (the first log sample at or after each
/// frame time: frames are logged samples, bit for bit), at most `max_frames` (the page stays near
/// 10 MB or less: ~0.8 KB a frame for 10 legs; the title then says how much it shows), and hands
/// every callback on to `next`.
class WheelReplay final : public RunSink {
 public:
  /// Palette indices of the feet layer.
  enum Mode : int { kStick = 0, kSlip = 1, kFree = 2 };
  /// Arrow length per newton [m/N]: m g is drawn 0.4 L0 long.
  WheelReplay(const WheelParams& w, RunSink& next, double frame_dt = 1.0 / 60.0, std::string title = "",
              int max_frames = 12000);
  void on_start(double energy_initial) override {
    energy_initial_ = energy_initial;
    next_.on_start(energy_initial);
  }
  void on_sample(const LogSample& sample) override;
  void on_event(const EventRecord& event) override { next_.on_event(event); }
  void on_step(const StepRecord& step) override { next_.on_step(step); }
  void on_restart(double t, std::span<const double> state, const ContactSet& contacts) override {
    next_.on_restart(t, state, contacts);
  }
  /// The scene with its slope sized to the hub's travel (call after the run).
  const replay::Scene& finish();
  double force_scale() const { return force_scale_; }

 private:
  WheelParams w_;
  RunSink& next_;
  double frame_dt_, next_frame_ = 0, force_scale_;
  int max_frames_;
  double energy_initial_ = 0;
  std::vector<std::size_t> columns_;  ///< each signal's column of log.csv (log_values)
  std::vector<int> phase_signals_;    ///< the signals of slot k's phase (a text column)
  bool truncated_ = false;
  double x_min_ = 0, x_max_ = 0;
  replay::Scene scene_;
};

}  // namespace flexgait::rimless
