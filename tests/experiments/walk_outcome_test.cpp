// The humanoid walk's outcome reasons (walk_outcome.hpp): one name table each, and the text of
// summary.json made from the reason.
#include "flexgait/experiments/walk_outcome.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "../support/enum_table.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/experiments/walk_experiment.hpp"

// GCC 12 with the sanitizers' flags warns that the payload of a default WalkMetrics' disengaged std::optional "may be
// used uninitialized" where fall_text() tests it (GCC bug 80635, a false positive); -Werror would stop the build.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace flexgait::experiments {
namespace {

TEST(WalkOutcome, NamesAreUniqueAndRoundTrip) {
  flexgait::testing::expect_enum_table_round_trips<FallReason>();
  flexgait::testing::expect_enum_table_round_trips<SimulationFailure>();
  std::set<std::string_view> sentences;
  for (const auto& e : enum_names(FallReason{})) EXPECT_TRUE(sentences.insert(fall_sentence(e.value)).second);
}

TEST(WalkOutcome, SummaryTextComesFromTheReason) {
  WalkMetrics m;
  EXPECT_EQ(m.fall_text(), "");
  EXPECT_EQ(m.failure_text(), "");
  m.fell = true;
  m.fall_reason = FallReason::kPelvisTilted;
  m.failure = WalkFailure{SimulationFailure::kMuJoCoWarning, "Nan, Inf or huge value in QACC at DOF 3"};
  const auto j = record_json(m);
  EXPECT_EQ(j["fall_reason"], "pelvis tilted beyond the limit");
  EXPECT_EQ(j["failure"], "MuJoCo: Nan, Inf or huge value in QACC at DOF 3");
  EXPECT_TRUE(j.contains("failure_time"));
  EXPECT_EQ((WalkFailure{SimulationFailure::kDiverged, {}}).text(), "the simulation diverged: a non-finite state");
}

// summary.json's safe_stop_reason is made from the sensor, its fault and the cut plan.
TEST(WalkOutcome, SafeStopTextComesFromTheReason) {
  WalkMetrics m;
  EXPECT_EQ(record_json(m)["safe_stop_reason"], "");
  m.safe_stop = true;
  m.safe_stop_reason = SafeStopReason{humanoid::kFtRight, walking::SignalFault::kNan, 0.3, 3, 10};
  EXPECT_EQ(record_json(m)["safe_stop_reason"],
            "sensor ft_right nan for longer than health.hold_time = 0.3 s; walk cut to 3 of 10 steps");
  m.safe_stop_reason = SafeStopReason{humanoid::kGyro, walking::SignalFault::kStale, 0.05, 0, 4};
  EXPECT_EQ(m.safe_stop_text(),
            "sensor gyro stale for longer than health.hold_time = 0.05 s; walk cut to 0 of 4 steps");
}

}  // namespace
}  // namespace flexgait::experiments
