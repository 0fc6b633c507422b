// Pictures of a real walk (walk_pictures.hpp, walk_markers.hpp): the side camera's first and last
// frames differ (the robot walked through the fixed view), the markers are drawn (their colours'
// pixels appear over the bare picture of the same state). What the markers hold is tested in
// walk_markers_test.cpp. Small frames (320 × 180), few of them: fast.
#include "flexgait/experiments/walk_pictures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace flexgait::experiments {
namespace {

/// Pixels of a marker colour: strongly saturated red, yellow, magenta, green or blue (the floor is
/// grey, the sky pale blue-grey, the robot grey and dark).
long marker_pixels(const std::vector<unsigned char>& rgb) {
  long n = 0;
  for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) {
    const int r = rgb[i], g = rgb[i + 1], b = rgb[i + 2];
    const int hi = std::max({r, g, b}), lo = std::min({r, g, b});
    n += hi > 110 && hi - lo > 90;
  }
  return n;
}

long differing(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
  long n = 0;
  for (std::size_t i = 0; i + 2 < a.size(); i += 3)
    n += std::abs(a[i] - b[i]) + std::abs(a[i + 1] - b[i + 1]) + std::abs(a[i + 2] - b[i + 2]) > 30;
  return n;
}

TEST(WalkPictures, TheSideCameraSeesTheRobotWalkWithItsMarkers) {
  WalkRunParams p;
  p.walk.steps = 2;
  const walking::WalkPlan plan = walking::plan_footsteps(p.walk);
  twin::RenderView view{320, 180, twin::CameraView::kSide, plan.initial[0].x, plan.final[0].x};
  WalkPictureOptions options;
  options.render = view;
  // Two frames: at the start and at 5.4 s, standing after the steps (the walk ends at 5.5 s).
  options.render_every = std::lround(5.4 / p.plant.control_period);
  std::vector<std::vector<unsigned char>> frames, bare;
  std::unique_ptr<WalkPictures> pictures;
  struct Bare final : loop::LoopObserver {
    std::function<void(const loop::LoopStep&)> f;
    void observe(const loop::LoopStep& step) override { f(step); }
  } bare_frames;
  bare_frames.f = [&](const loop::LoopStep& step) {
    // (the same renderer and state without the markers)
    if (step.k % options.render_every == 0) bare.push_back(pictures->renderer()->render(step.plant));
  };
  const WalkResult r = run_walk(p, {}, [&](WalkLoop& w) {
    pictures = std::make_unique<WalkPictures>(p, w, options, [&](const std::vector<unsigned char>& rgb, int index) {
      EXPECT_EQ(index, static_cast<int>(frames.size()));
      frames.push_back(rgb);
    });
    w.loop->attach(*pictures);
    w.loop->attach(bare_frames);
  });
  ASSERT_TRUE(r.metrics.completed()) << r.metrics.outcome();
  ASSERT_EQ(frames.size(), 2u);
  ASSERT_EQ(frames.size(), bare.size());
  ASSERT_EQ(frames.front().size(), 320u * 180u * 3u);

  // The robot moved 0.2 m (two steps of 0.1 m) in a view 2.5 m high from 3 m (~72 pixels a metre):
  // ~14 pixels along its ~70-pixel height: over a thousand pixels change (1600 measured).
  const long moved = differing(bare.front(), bare.back());
  ::testing::Test::RecordProperty("pixels_moved", std::to_string(moved));
  EXPECT_GT(moved, 300) << moved;
  // The markers: their saturated colours appear in every frame over the bare picture of the same
  // state (footprints ~0.22 m long, balls ~5 cm wide: 62 and 80 pixels more measured).
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const long added = marker_pixels(frames[i]) - marker_pixels(bare[i]);
    ::testing::Test::RecordProperty("marker_pixels_" + std::to_string(i), std::to_string(added));
    EXPECT_GT(added, 30) << "frame " << i;
  }

  // The markers hold the walk's landings (walk_markers_test.cpp); here they are the pictures' own.
  EXPECT_EQ(pictures->markers().markers().actual.size(), 2 + plan.steps.size());
}

// The replay's plotted signals are the log's: at each frame (a logged sample's time) every signal
// named by a column (or "a - b") holds float32 of that column's value (the difference) in the
// sample run_walk logged then; the capture point is the marker's, in the plan's frame.
TEST(WalkPictures, TheReplaysSignalsAreTheLogsColumns) {
  WalkRunParams p;
  p.walk.steps = 1;
  WalkPictureOptions options;
  options.replay = true;
  std::unique_ptr<WalkPictures> pictures;
  std::vector<WalkSample> samples;
  const WalkResult r = run_walk(
      p, {},
      [&](WalkLoop& w) {
        pictures = std::make_unique<WalkPictures>(p, w, options);
        w.loop->attach(*pictures);
      },
      [&](const WalkSample& w) {
        samples.push_back(w);
        pictures->log_sample(w);
      });
  ASSERT_TRUE(r.metrics.completed()) << r.metrics.outcome();
  const replay::Scene& s = pictures->replay()->scene();
  ASSERT_GT(s.frames(), 50);
  ASSERT_EQ(s.signals.size(), 36u);  // (pd balance, no push: no DCM, no push force)
  // Each signal's columns: a, or a and b of "a - b" (2k and 2k + 1; b = a for a single column).
  std::vector<std::string> names;
  for (const replay::Signal& signal : s.signals) {
    const std::size_t minus = signal.name.find(" - ");
    names.push_back(signal.name.substr(0, minus));
    names.push_back(minus == std::string::npos ? signal.name : signal.name.substr(minus + 3));
  }
  for (std::string& name : names)
    if (name.rfind("capture_point_", 0) == 0) name = "t";  // (not a column: checked apart)
  const WalkColumns columns(names);
  std::size_t row = 0;
  int checked = 0;
  for (int f = 0; f < s.frames(); ++f) {
    while (row < samples.size() && samples[row].t != s.time[static_cast<std::size_t>(f)]) ++row;
    ASSERT_LT(row, samples.size()) << "frame " << f << " is no logged sample";
    const std::vector<double> v = columns.values(samples[row]);
    for (std::size_t k = 0; k < s.signals.size(); ++k) {
      const replay::Signal& signal = s.signals[k];
      const float shown = signal.data[static_cast<std::size_t>(f)];
      if (signal.name.rfind("capture_point_", 0) == 0) {
        EXPECT_TRUE(std::isfinite(shown)) << signal.name;
        continue;
      }
      const double want = signal.name.find(" - ") == std::string::npos ? v[2 * k] : v[2 * k] - v[2 * k + 1];
      EXPECT_TRUE(shown == static_cast<float>(want) || (std::isnan(shown) && std::isnan(want)))
          << signal.name << " at frame " << f << ": " << shown << " vs " << want;
      ++checked;
    }
  }
  EXPECT_EQ(checked, s.frames() * 34);
  // The panels: ZMP, COM and capture point, pelvis, gears, feet, each signal with a unit.
  std::vector<std::string> panels;
  for (const replay::Signal& signal : s.signals) {
    if (panels.empty() || panels.back() != signal.panel) panels.push_back(signal.panel);
    EXPECT_FALSE(signal.unit.empty()) << signal.name;
  }
  EXPECT_EQ(panels, (std::vector<std::string>{"ZMP", "COM, capture point", "pelvis", "gears", "feet"}));
  p.balance.mode = walking::BalanceMode::kDcm;  // the DCM's columns; a push's force
  EXPECT_EQ(WalkPictures::replay_signals(p, true).size(), 36u + 4 + 3);
}

}  // namespace
}  // namespace flexgait::experiments
