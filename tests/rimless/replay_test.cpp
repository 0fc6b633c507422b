// The wheel's replay scene against its run: every frame is a logged sample (its time and hub
// position the log's), the legs' feet on the ground sit at the log's c_k on the slope, a free
// foot is L0 from the hub, the plotted signals are the log's cells, the slope map turns the slope's axes into unit
// vectors φ below and above the horizontal, and every callback reaches the next sink unchanged.
#include "flexgait/rimless/replay.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/output.hpp"

namespace flexgait::rimless {
namespace {

TEST(SlopeToWorld, TurnsTheSlopeFrameByPhiAboutY) {
  WheelParams w;
  w.slope = 0.3;
  const auto ex = slope_to_world(w, 1, 0), ey = slope_to_world(w, 0, 1);
  EXPECT_NEAR(ex[0], std::cos(0.3), 1e-15);  // down the slope: below the horizontal by φ
  EXPECT_NEAR(ex[2], -std::sin(0.3), 1e-15);
  EXPECT_NEAR(ey[0] * ex[0] + ey[2] * ex[2], 0, 1e-15);  // the normal stays normal
  EXPECT_NEAR(std::hypot(ey[0], ey[2]), 1, 1e-15);
}

TEST(WheelReplay, FramesAreLoggedSamples) {
  WheelParams w;
  SimulationOptions o;
  o.steps = 3;
  SimulationResult in_memory = simulate_flexible(w, InitialState{}, o);
  SimulationResult forwarded;
  RunCollector collector(forwarded);
  WheelReplay replay(w, collector, 0.05);
  forwarded.energy_initial = simulate_flexible(w, InitialState{}, o, replay).energy_initial;  // (log.csv's E(0))
  // Every callback reached the next sink: the same samples as the in-memory run.
  ASSERT_EQ(forwarded.samples.size(), in_memory.samples.size());
  EXPECT_EQ(forwarded.events.size(), in_memory.events.size());
  const replay::Scene& s = replay.finish();
  ASSERT_GT(s.frames(), 10);
  const Table log = log_table(forwarded);  // log.csv's cells
  std::size_t row = 0;
  const double alpha = w.alpha();
  for (int f = 0; f < s.frames(); ++f) {
    while (row < forwarded.samples.size() && forwarded.samples[row].t != s.time[f]) ++row;
    ASSERT_LT(row, forwarded.samples.size()) << "frame " << f << " is no logged sample";
    const LogSample& x = forwarded.samples[row];
    if (f > 0) {
      EXPECT_GE(s.time[f] - s.time[f - 1], 0.05 - 2e-3);  // a frame every 0.05 s, on the 1 ms samples
    }
    // The plotted signals are log.csv's columns of their names (float32 of the cells); phaseK is
    // the slot's mode as a number (slip+ 1, stick 0, slip- -1), NaN while the slot is empty. And
    // log_values is the row's numbers, NaN for its text cells.
    const std::vector<double> values = log_values(x, forwarded.energy_initial);
    ASSERT_EQ(values.size(), log.columns().size());
    for (std::size_t c = 0; c < values.size(); ++c) {
      const Table::Column& column = log.columns()[c];
      if (column.kind == Table::Kind::Text)
        EXPECT_TRUE(std::isnan(values[c])) << column.name;
      else
        EXPECT_EQ(values[c], column.numbers[row]) << column.name;
    }
    for (const replay::Signal& signal : s.signals) {
      const float shown = signal.data[static_cast<std::size_t>(f)];
      if (signal.name.rfind("phase", 0) == 0) {
        const ContactSample& slot = x.contact[static_cast<std::size_t>(std::stoi(signal.name.substr(5)) - 1)];
        if (slot.leg < 0)
          EXPECT_TRUE(std::isnan(shown)) << signal.name;
        else
          EXPECT_EQ(shown, static_cast<float>(slip_sign(slot.mode))) << signal.name;
        continue;
      }
      const auto column = std::find_if(log.columns().begin(), log.columns().end(),
                                       [&](const Table::Column& c) { return c.name == signal.name; });
      ASSERT_NE(column, log.columns().end()) << signal.name;
      EXPECT_EQ(shown, static_cast<float>(column->numbers[row])) << signal.name << " at frame " << f;
    }
    const auto hub = slope_to_world(w, x.q[0], x.q[1]);
    const float* p = &s.poses[static_cast<std::size_t>(f) * 7];
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(p[i], hub[i], 1e-6);  // float32 of coordinates below 10 m
    for (int k = 0; k < w.legs; ++k) {
      const float* leg = &s.layers[0].data[(static_cast<std::size_t>(f) * w.legs + k) * 6];
      const unsigned char mode = s.layers[1].color[static_cast<std::size_t>(f) * w.legs + k];
      int slot = -1;
      for (int i = 0; i < kMaxContacts; ++i)
        if (x.contact[i].leg == k) slot = i;
      if (slot >= 0) {
        const auto foot = slope_to_world(w, x.contact[slot].c, 0);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(leg[3 + i], foot[i], 1e-6);
        EXPECT_EQ(mode, x.contact[slot].mode == FootMode::Stick ? WheelReplay::kStick : WheelReplay::kSlip);
      } else {
        EXPECT_NEAR(std::hypot(leg[3] - leg[0], leg[5] - leg[2]), w.L0, 1e-6);
        EXPECT_EQ(mode, WheelReplay::kFree);
        // Leg k points along β_k = θ + 2αk from the slope normal, away from the hub.
        const double beta = x.q[2] + 2 * alpha * k;
        const auto dir = slope_to_world(w, -std::sin(beta), -std::cos(beta));
        EXPECT_NEAR(leg[3] - leg[0], w.L0 * dir[0], 1e-5);
        EXPECT_NEAR(leg[5] - leg[2], w.L0 * dir[2], 1e-5);
      }
    }
  }
}

TEST(WheelReplay, KeepsAtMostMaxFramesAndSaysSo) {
  WheelParams w;
  SimulationOptions o;
  o.steps = 2;
  SimulationResult forwarded;
  RunCollector collector(forwarded);
  WheelReplay replay(w, collector, 0.01, "capped", 5);
  (void)simulate_flexible(w, InitialState{}, o, replay);
  const replay::Scene& s = replay.finish();
  EXPECT_EQ(s.frames(), 5);
  EXPECT_NE(s.title.find("the first 0.0"), std::string::npos) << s.title;
  EXPECT_GT(forwarded.samples.size(), 100u);  // the log itself is whole
}

}  // namespace
}  // namespace flexgait::rimless
