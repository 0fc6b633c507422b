#include "flexgait/rimless/gait.hpp"

namespace flexgait::rimless {
namespace {

void append(std::vector<Phase>& v, Phase p) {
  if (v.empty() || v.back() != p) v.push_back(p);
}

Phase phase_of(FootMode m) {
  return m == FootMode::Stick ? Phase::Stick : Phase::Slip;
}

}  // namespace

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::Stick:
      return "stick";
    case Phase::Slip:
      return "slip";
    case Phase::Flight:
      return "flight";
  }
  return "?";
}

std::string gait_label(const std::vector<Phase>& phases) {
  if (phases.empty()) return "double";
  std::string s;
  for (std::size_t i = 0; i < phases.size(); ++i) s += (i ? "-" : "") + std::string(phase_name(phases[i]));
  return s;
}

std::string step_gait(const StepRecord& step, const std::vector<Phase>& single_support) {
  const bool touchdown_stick = step.landing_stick && !single_support.empty() && single_support.front() == Phase::Slip;
  return (touchdown_stick ? "touchdown-stick " : "") + gait_label(single_support);
}
std::string step_gait(const StepRecord& step) {
  return step_gait(step, step.single_support);
}

void StepTracker::start(double t, double x, double energy, const ContactSet& contacts, int legs, int stance_leg) {
  steps_.clear();
  gaits_.clear();
  legs_ = legs;
  StepRecord r;
  r.index = 1;
  r.stance_leg = stance_leg >= 0 ? stance_leg : contacts.count > 0 ? contacts.leg[0] : -1;
  r.t_start = r.t_end = t;
  r.x_start = r.x_end = x;
  r.energy_start = energy;
  steps_.push_back(r);
  observe(contacts);
}

void StepTracker::observe(const ContactSet& contacts) {
  if (steps_.empty()) return;
  StepRecord& cur = steps_.back();
  if (contacts.count == 0) append(cur.single_support, Phase::Flight);
  if (contacts.count == 1 && contacts.leg[0] == cur.stance_leg) append(cur.single_support, phase_of(contacts.mode[0]));
  if (contacts.count > 1 && cur.single_support.empty()) {  // the double support after the landing
    const int i = contacts.find(cur.stance_leg);
    if (i >= 0 && contacts.mode[i] == FootMode::Stick) cur.landing_stick = true;
  }
  // Whole-contact phases: the current stance foot, and the previous one while it is still down.
  for (std::size_t back = 0; back < 2 && back < steps_.size(); ++back) {
    StepRecord& r = steps_[steps_.size() - 1 - back];
    const int i = contacts.find(r.stance_leg);
    if (i >= 0) append(r.contact, phase_of(contacts.mode[i]));
  }
}

bool StepTracker::is_new_leg(int leg) const {
  const int stance = stance_leg();
  if (stance < 0) return true;  // the first landing after a start in flight
  // Walking forward θ grows and leg k-1 (β_{k-1} = β_k - 2α) is the next to land.
  const int ahead = ((stance - leg) % legs_ + legs_) % legs_;
  return ahead >= 1 && 2 * ahead < legs_;
}

void StepTracker::touchdown(double t, double x, double energy, int leg, const ContactSet& contacts) {
  StepRecord& cur = steps_.back();
  cur.t_end = t;
  cur.x_end = x;
  cur.complete = true;
  gaits_.push_back(step_gait(cur));
  StepRecord next;
  next.index = cur.index + 1;
  next.stance_leg = leg;
  next.t_start = next.t_end = t;
  next.x_start = next.x_end = x;
  next.energy_start = energy;
  steps_.push_back(next);
  observe(contacts);
}

void StepTracker::finish(double t, double x) {
  if (steps_.empty() || steps_.back().complete) return;
  steps_.back().t_end = t;
  steps_.back().x_end = x;
}

std::span<const StepRecord> StepTracker::final_steps() const {
  return std::span<const StepRecord>(steps_).first(steps_.size() > 2 ? steps_.size() - 2 : 0);
}

void StepTracker::drop_final_steps() {
  steps_.erase(steps_.begin(), steps_.begin() + static_cast<std::ptrdiff_t>(final_steps().size()));
}

const StepRecord* StepTracker::last_complete() const {
  for (auto it = steps_.rbegin(); it != steps_.rend(); ++it)
    if (it->complete) return &*it;
  return nullptr;
}

}  // namespace flexgait::rimless
