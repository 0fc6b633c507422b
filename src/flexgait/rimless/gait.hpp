#pragma once
/// \file gait.hpp
/// Gait classification (docs/theory/rimless.md, "Poincaré map, fixed points, stability"): a step runs from the
/// touchdown of its
/// stance leg to the touchdown of the next leg; its label is the sequence of the stance foot's
/// phases during single support (and `flight` while no foot is down), consecutive repeats merged:
///
///   `stick`            sticks all through single support (the landing slip ended in double support)
///   `slip-stick`       the landing slip runs into single support, then the foot sticks
///   `stick-slip`       sticks, then slips before the next leg lands
///   `slip`             slips all through single support (sliding gait)
///   `slip-stick-slip`  both
///   `double`           no single support at all
///
/// A label that starts with `slip` gets the prefix `touchdown-stick ` when the stance foot stuck
/// in the double support after its own landing and slipped again before single support began: its
/// whole contact runs slip, stick, slip, ... rather than one landing slip (on the measured wheel the
/// window 0.2805 < μ < 0.3273 of the `slip-stick` gait: slip−, stick, slip+, stick, slip+).
///
/// These are the paper's four behaviours (and their combination). The full sequence of the
/// stance foot over its whole contact, double support included, is kept as `contact_phases`.
#include <span>
#include <string>
#include <vector>

#include "flexgait/rimless/contact.hpp"

namespace flexgait::rimless {

enum class Phase : std::uint8_t { Stick, Slip, Flight };
const char* phase_name(Phase p);
/// "slip-stick" style label; "double" for an empty sequence.
std::string gait_label(const std::vector<Phase>& phases);
struct StepRecord;
/// A step's gait: gait_label(single_support), with the prefix "touchdown-stick " when the stance
/// foot stuck in the double support after its landing and single support begins in slip (the
/// header). `single_support` may be a longer sequence that starts with the step's (joined cycles).
std::string step_gait(const StepRecord& step, const std::vector<Phase>& single_support);
std::string step_gait(const StepRecord& step);

struct StepRecord {
  int index = 0;  ///< 1-based; step 1 starts at the initial state
  int stance_leg = 0;
  double t_start = 0, t_end = 0;      ///< [s]
  double x_start = 0, x_end = 0;      ///< hub position [m]
  double energy_start = 0;            ///< mechanical energy at the start [J]
  std::vector<Phase> single_support;  ///< stance-foot phases while it is the only foot down
  std::vector<Phase> contact;         ///< stance-foot phases over its whole contact
  /// The stance foot stuck in the double support after its landing (before single support).
  bool landing_stick = false;
  bool complete = false;  ///< ended by the next touchdown
};

/// Follows the steps of a run. It holds the last two steps only once the caller takes the final
/// ones (final_steps(), drop_final_steps()), so a run of any length keeps O(1) step records; the
/// gait labels of the completed steps are kept (gaits()).
class StepTracker {
 public:
  /// Starts step 1 with `stance_leg` as stance foot (-1: the oldest foot on the ground) on a
  /// wheel of `legs` legs.
  void start(double t, double x, double energy, const ContactSet& contacts, int legs, int stance_leg = -1);
  /// Records the modes in force after an event.
  void observe(const ContactSet& contacts);
  /// Closes the current step at the touchdown of `leg` and opens the next.
  void touchdown(double t, double x, double energy, int leg, const ContactSet& contacts);
  /// At the end of the run at hub position x [m]: the open step ends at time t [s].
  void finish(double t, double x);
  int stance_leg() const { return steps_.empty() ? -1 : steps_.back().stance_leg; }
  /// Whether a touchdown of `leg` starts a new step: the leg lies ahead of the stance leg in the
  /// direction of walking (legs k-1, k-2, … of stance leg k, fewer than half the wheel ahead).
  /// The stance leg itself or a leg behind it landing again (the wheel rocked back, a foot
  /// bounced) is a re-landing within the current step, not a step.
  bool is_new_leg(int leg) const;
  /// The steps held, oldest first (all of them after finish()).
  const std::vector<StepRecord>& steps() const { return steps_; }
  /// The held steps whose records can no longer change: all but the last two (the previous
  /// stance foot may still be on the ground and add to its contact phases).
  std::span<const StepRecord> final_steps() const;
  /// Forgets the final steps (after the caller has taken them).
  void drop_final_steps();
  /// The latest completed step, or nullptr.
  const StepRecord* last_complete() const;
  /// gait_label(single_support) of every completed step, in order.
  const std::vector<std::string>& gaits() const { return gaits_; }

 private:
  std::vector<StepRecord> steps_;
  std::vector<std::string> gaits_;
  int legs_ = 0;
};

}  // namespace flexgait::rimless
