// What a rimless run records (rimless/simulation.hpp): the event names of events.csv (the guard
// events with mode_selection's names, then the run's own marks), the contact description, and the
// in-memory collector keeping everything in order.
#include "flexgait/rimless/simulation.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace flexgait::rimless {
namespace {

TEST(Simulation, RunEventNamesAreTheGuardEventsThenTheRunsMarks) {
  for (EventKind k : {EventKind::Touchdown, EventKind::LiftOff, EventKind::StickToSlip, EventKind::SlipToStick,
                      EventKind::SlipJam, EventKind::FallOver})
    EXPECT_STREQ(run_event_name(run_event(k)), event_name(k));
  EXPECT_STREQ(run_event_name(RunEvent::Start), "start");
  EXPECT_STREQ(run_event_name(RunEvent::Jam), "jam");
  EXPECT_STREQ(run_event_name(RunEvent::Section), "section");
  EXPECT_STREQ(run_event_name(RunEvent::Failure), "failure");
  // Every kind has its own name (events.csv is read back by name).
  std::set<std::string> names;
  for (int k = 0; k <= static_cast<int>(RunEvent::Failure); ++k) names.insert(run_event_name(static_cast<RunEvent>(k)));
  EXPECT_EQ(names.size(), static_cast<std::size_t>(RunEvent::Failure) + 1);
}

TEST(Simulation, ContactsAreDescribedLegByLegOrAsFlight) {
  EXPECT_EQ(describe_contacts(ContactSet{}), "flight");
  ContactSet c;
  c.count = 2;
  c.leg = {3, 4, 0};
  c.mode = {FootMode::Stick, FootMode::SlipBackward, FootMode::Stick};
  EXPECT_EQ(describe_contacts(c),
            std::string("3:") + mode_name(FootMode::Stick) + " 4:" + mode_name(FootMode::SlipBackward));
}

TEST(Simulation, CollectorKeepsSamplesEventsAndStepsInOrder) {
  SimulationResult result;
  RunCollector collector(result);
  RunSink& sink = collector;
  for (int k = 0; k < 3; ++k) {
    LogSample sample;
    sample.t = 0.1 * k;
    sink.on_sample(sample);
    EventRecord event;
    event.t = 0.1 * k;
    event.leg = k;
    sink.on_event(event);
    StepRecord step;
    step.index = k + 1;
    sink.on_step(step);
  }
  ASSERT_EQ(result.samples.size(), 3u);
  ASSERT_EQ(result.events.size(), 3u);
  ASSERT_EQ(result.steps.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(result.samples[static_cast<std::size_t>(k)].t, 0.1 * k);
    EXPECT_EQ(result.events[static_cast<std::size_t>(k)].leg, k);
    EXPECT_EQ(result.steps[static_cast<std::size_t>(k)].index, k + 1);
  }
}

}  // namespace
}  // namespace flexgait::rimless
