#include "flexgait/rimless/simulation.hpp"

#include <fmt/format.h>

#include <cmath>

namespace flexgait::rimless {

// RunEvent begins with EventKind's values, in its order.
static_assert(static_cast<int>(RunEvent::Touchdown) == static_cast<int>(EventKind::Touchdown));
static_assert(static_cast<int>(RunEvent::LiftOff) == static_cast<int>(EventKind::LiftOff));
static_assert(static_cast<int>(RunEvent::StickToSlip) == static_cast<int>(EventKind::StickToSlip));
static_assert(static_cast<int>(RunEvent::SlipToStick) == static_cast<int>(EventKind::SlipToStick));
static_assert(static_cast<int>(RunEvent::SlipJam) == static_cast<int>(EventKind::SlipJam));
static_assert(static_cast<int>(RunEvent::FallOver) == static_cast<int>(EventKind::FallOver));

const char* run_event_name(RunEvent kind) {
  switch (kind) {
    case RunEvent::Start:
      return "start";
    case RunEvent::Jam:
      return "jam";
    case RunEvent::Section:
      return "section";
    case RunEvent::Failure:
      return "failure";
    default:
      return event_name(static_cast<EventKind>(kind));
  }
}

std::string describe_contacts(const ContactSet& c) {
  if (c.count == 0) return "flight";
  std::string s;
  for (int i = 0; i < c.count; ++i) s += fmt::format("{}{}:{}", i ? " " : "", c.leg[i], mode_name(c.mode[i]));
  return s;
}

void RunCollector::on_sample(const LogSample& sample) {
  result_.samples.push_back(sample);
}
void RunCollector::on_event(const EventRecord& event) {
  result_.events.push_back(event);
}
void RunCollector::on_step(const StepRecord& step) {
  result_.steps.push_back(step);
}

bool balanced_at_vertical(const WheelParams& w, double beta, double omega) {
  return std::abs(beta + w.slope) <= 1e-3 && std::abs(omega) <= 1e-3 * std::sqrt(w.g / w.L0);
}

}  // namespace flexgait::rimless
