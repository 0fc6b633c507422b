#include "flexgait/rimless/mode_selection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string_view>
#include <vector>

#include "flexgait/rimless/dynamics.hpp"
#include "flexgait/rimless/energy.hpp"

namespace flexgait::rimless {
namespace {

enum class Option : std::uint8_t { Stick, SlipForward, SlipBackward, Leave };

// A list of options (each at most once: at most four), in order of preference; no allocation
// at an event.
class Options {
 public:
  Options() = default;
  Options(std::initializer_list<Option> list) {
    for (Option o : list) push_back(o);
  }
  void push_back(Option o) { list_[static_cast<std::size_t>(count_++)] = o; }
  const Option* begin() const { return list_.data(); }
  const Option* end() const { return list_.data() + count_; }
  Option operator[](int i) const { return list_[static_cast<std::size_t>(i)]; }
  int size() const { return count_; }
  bool empty() const { return count_ == 0; }

 private:
  std::array<Option, 4> list_{};
  int count_ = 0;
};

struct Foot {
  int leg = 0;
  bool was_on_ground = false;
  FootMode previous = FootMode::Stick;
  double anchor = 0;
  Options options;                    // in order of preference
  const GuardEvent* event = nullptr;  // this foot's own event, if one fired
};

// The foot velocity ċ that the tests may read. A foot whose slip→stick guard (s ċ = 0) fired is
// at rest by the event's definition: what ċ shows there is the root location's error,
// |c̈| × (time tolerance), which with stiff slip exceeds any fixed velocity tolerance and would
// send the foot into reverse slip, only to come to rest again at its own restart point.
double tested_cdot(const Foot& foot, const LegKinematics& g) {
  return foot.event != nullptr && foot.event->kind == EventKind::SlipToStick ? 0.0 : g.cdot;
}

// Whether the slip direction of this foot is decided by its event alone: at stick→slip the
// incipient slip opposes the sticking force, s = -sign(T_stick) (docs/theory/rimless.md); its
// acceleration there is 0 for μ_k = μ_s (the forces are continuous) and its sign is noise.
// Not so for I = 0, where θ̇ jumps with the mode and the test must still see whether the slip
// has a motion at all.
bool direction_decided(const WheelParams& w, const Foot& foot) {
  return w.I > 0 && foot.event != nullptr && foot.event->kind == EventKind::StickToSlip;
}

Option option_of(FootMode m) {
  return m == FootMode::Stick ? Option::Stick : m == FootMode::SlipForward ? Option::SlipForward : Option::SlipBackward;
}
FootMode mode_of(Option o) {
  return o == Option::Stick         ? FootMode::Stick
         : o == Option::SlipForward ? FootMode::SlipForward
                                    : FootMode::SlipBackward;
}
const char* option_name(Option o) {
  return o == Option::Leave ? "leave" : mode_name(mode_of(o));
}

const GuardEvent* event_of(std::span<const GuardEvent> events, int leg) {
  for (const auto& e : events)
    if (e.leg == leg) return &e;
  return nullptr;
}

void add_unique(Options& v, Option o) {
  for (Option x : v)
    if (x == o) return;
  v.push_back(o);
}

// Options allowed by the foot's velocity: a moving foot can only slip with its motion (or leave).
// With I = 0 the wheel's rotation carries no energy and θ̇ is not a state: it jumps to the value
// the new mode fixes (ċ = 0 of a sticking foot, or the torque balance when all feet slip; the
// I -> 0 limit of the fast rotation), so every option is left to the consistency test.
Options velocity_options(double cdot, double tol, bool point_mass) {
  if (point_mass) return {Option::Stick, Option::SlipForward, Option::SlipBackward, Option::Leave};
  if (cdot > tol) return {Option::SlipForward, Option::Leave};
  if (cdot < -tol) return {Option::SlipBackward, Option::Leave};
  return {Option::Stick, Option::SlipForward, Option::SlipBackward, Option::Leave};
}

bool allowed(const Options& v, Option o) {
  for (Option x : v)
    if (x == o) return true;
  return false;
}

// Applies jam impulses: P_k along ∂c_k/∂q for the feet in `jam`, so that their ċ becomes 0.
// Returns false when the impulses are inadmissible (outside the cone or pulling).
bool apply_impulse(const WheelParams& w, const std::vector<int>& jam, std::span<double> y, double& energy_loss) {
  using S = StateIndex;
  std::array<std::array<double, 3>, kMaxContacts> A{};
  std::array<double, kMaxContacts> b{};
  std::array<double, kMaxContacts> P{};
  std::array<double, 3> dv{};
  std::array<LegKinematics, kMaxContacts> legs{};
  const int rows = static_cast<int>(jam.size());
  for (int r = 0; r < rows; ++r) {
    legs[r] = leg_kinematics(w, jam[r], y);
    A[r] = legs[r].A;
    b[r] = -legs[r].cdot;
  }
  if (!solve_constrained(w, rows, A, {0.0, 0.0, 0.0}, b, dv, P)) return false;
  for (int r = 0; r < rows; ++r) {
    // Tangential impulse P with no axial part: normal impulse = -P tan β must push, and
    // |P| <= μ (normal impulse), i.e. the direction perpendicular to the leg is in the cone.
    // While the foot is stopped its speed passes through every value in [0, |ċ|]: the cone is
    // the widest the slip law gives there, max(μ_s, μ(ċ)) (μ(v) falls then rises with a viscous
    // part, so the largest is at an end; Coulomb: μ_s). A jam found by its guard sits at
    // D = cos β - μ s sin β = 0, i.e. on that cone's edge, to the root finder's accuracy: the
    // test allows 1e-9 relative.
    const double normal = -P[r] * legs[r].tb;
    const int s = legs[r].cdot > 0 ? 1 : -1;
    const double mu = std::max(w.mu_s, slip_law(w, s, legs[r].cdot).mu);
    if (normal < 0 || std::abs(P[r]) > mu * normal * (1 + 1e-9)) return false;
  }
  const double before = kinetic_energy(w, y);
  y[S::xd] += dv[0];
  y[S::yd] += dv[1];
  y[S::thetad] += dv[2];
  energy_loss = before - kinetic_energy(w, y);
  y[S::w_fric] += energy_loss;
  return true;
}

// Legs that left keep their compression as free legs, relaxing from here.
void release_legs(const WheelParams& w, const ContactSet& current, std::span<const GuardEvent> events,
                  const ContactSet& after, std::span<double> y) {
  using S = StateIndex;
  auto release = [&](int leg) {
    if (after.find(leg) >= 0) return;
    const double delta = leg_kinematics(w, leg, y).delta;
    y[S::free_delta + leg] = w.C > 0 ? delta : 0.0;
    if (w.C == 0) y[S::w_damp] += 0.5 * w.K * delta * delta;  // an undamped massless leg snaps to rest
  };
  for (int i = 0; i < current.count; ++i) release(current.leg[i]);
  for (const auto& e : events)
    if (e.kind == EventKind::Touchdown && current.find(e.leg) < 0) release(e.leg);
}

// θ̇ that the new mode fixes when I = 0: ċ = 0 of the first sticking foot, or the torque balance.
double point_mass_thetad(const WheelParams& w, const ContactSet& after, std::span<const double> y) {
  using S = StateIndex;
  for (int j = 0; j < after.count; ++j) {
    if (after.mode[j] != FootMode::Stick) continue;
    const LegKinematics g = leg_kinematics(w, after.leg[j], y);
    return (y[S::xd] - y[S::yd] * g.tb) * g.cb * g.cb / y[S::y];
  }
  return contact_dynamics(w, after, y).thetad;
}

}  // namespace

void apply_reset(const WheelParams& w, const ContactSet& current, std::span<const GuardEvent> events,
                 const ModeDecision& decision, std::span<double> y) {
  if (!decision.impulse_legs.empty()) {
    double loss = 0;
    apply_impulse(w, decision.impulse_legs, y, loss);  // admissibility was checked when deciding
  }
  if (w.I == 0) y[StateIndex::thetad] = point_mass_thetad(w, decision.contacts, y);
  release_legs(w, current, events, decision.contacts, y);
}

const char* event_name(EventKind kind) {
  switch (kind) {
    case EventKind::Touchdown:
      return "touchdown";
    case EventKind::LiftOff:
      return "liftoff";
    case EventKind::StickToSlip:
      return "stick_to_slip";
    case EventKind::SlipToStick:
      return "slip_to_stick";
    case EventKind::SlipJam:
      return "slip_jam";
    case EventKind::FallOver:
      return "fall_over";
  }
  return "?";
}

ModeTolerances ModeTolerances::of(const WheelParams& w) {
  return {1e-8 * w.m * w.g, 1e-8 * std::sqrt(w.g * w.L0), 1e-8 * w.g};
}

ModeDecision choose_modes(const WheelParams& w, const ContactSet& current, std::span<const GuardEvent> events,
                          std::span<double> y) {
  using S = StateIndex;
  ModeDecision out;
  const ModeTolerances tol = ModeTolerances::of(w);
  if (w.I == 0) y[S::thetad] = contact_dynamics(w, current, y).thetad;  // θ̇ in force (I = 0 DAE)
  for (const auto& e : events) {
    if (e.kind == EventKind::FallOver) {
      out.failure = FailureReason::Fell;
      out.detail = fmt::format("leg {}", e.leg);
      return out;
    }
  }

  // The feet on the ground: the current ones, then the ones landing now.
  std::vector<Foot> feet;
  for (int i = 0; i < current.count; ++i)
    feet.push_back({current.leg[i], true, current.mode[i], current.anchor[i], {}, event_of(events, current.leg[i])});
  for (const auto& e : events)
    if (e.kind == EventKind::Touchdown && current.find(e.leg) < 0)
      feet.push_back({e.leg, false, FootMode::Stick, 0, {}, &e});
  if (static_cast<int>(feet.size()) > kMaxContacts) {
    out.failure = FailureReason::TooManyFeet;
    out.detail = fmt::format("{} feet; at most {}", feet.size(), kMaxContacts);
    return out;
  }

  // Painlevé jams: a moving foot that cannot slip with its motion (D <= 0 while pressed), or a
  // slipping foot whose denominator reached 0.
  std::vector<int> jam;
  for (const auto& foot : feet) {
    const LegKinematics g = leg_kinematics(w, foot.leg, y);
    const GuardEvent* e = foot.event;
    const bool moving = std::abs(tested_cdot(foot, g)) > tol.velocity;
    const int s = g.cdot > 0 ? 1 : -1;
    const bool jammed = (e != nullptr && e->kind == EventKind::SlipJam) ||
                        (moving && g.f > tol.force && slip_denominator(w, g, s) <= 0);
    if (jammed) jam.push_back(foot.leg);
  }
  if (!jam.empty()) {
    // Prefer keeping sticking feet stuck (they take an impulse too); else stop the jammed ones only.
    std::vector<int> with_stuck = jam;
    for (const auto& foot : feet)
      if (foot.was_on_ground && foot.previous == FootMode::Stick) with_stuck.push_back(foot.leg);
    std::vector<double> saved(y.begin(), y.end());
    double loss = 0;
    bool done = with_stuck.size() > jam.size() && apply_impulse(w, with_stuck, y, loss);
    out.impulse_legs = with_stuck;
    if (!done) {
      std::copy(saved.begin(), saved.end(), y.begin());
      done = apply_impulse(w, jam, y, loss);
      out.impulse_legs = jam;
    }
    if (!done) {
      std::copy(saved.begin(), saved.end(), y.begin());
      out.failure = FailureReason::JamWithoutImpulse;
      out.detail = fmt::format("{} jammed foot(feet), first leg {}", jam.size(), jam.front());
      return out;
    }
    out.jammed_feet = static_cast<int>(jam.size());
    out.impulse_energy = loss;
  }

  // Each foot's options, in order of preference.
  for (auto& foot : feet) {
    const LegKinematics g = leg_kinematics(w, foot.leg, y);
    const Options by_velocity = velocity_options(tested_cdot(foot, g), tol.velocity, w.I == 0);
    const GuardEvent* e = foot.event;
    Options preferred;
    if (foot.was_on_ground && (e == nullptr || e->kind == EventKind::SlipJam)) {
      preferred.push_back(option_of(foot.previous));
    }
    if (e != nullptr && e->kind == EventKind::StickToSlip) {
      // Incipient slip opposes the sticking force: s = -sign(T_stick) (the spec's rule).
      ContactSet before = current;
      const Dynamics d = contact_dynamics(w, before, y);
      const int i = current.find(foot.leg);
      const double T = i >= 0 ? d.force[i].T : 0.0;
      preferred = {T > 0 ? Option::SlipBackward : Option::SlipForward, Option::Leave};
    } else if (e != nullptr && e->kind == EventKind::SlipToStick) {
      // At rest now (ċ = 0): stick, reverse, leave, or — last — slip on the same way from rest,
      // which the acceleration test admits only if another foot's new mode turns c̈ around (two
      // feet coming to rest together: the one that sticks may tip the wheel over the other).
      const int s = slip_sign(foot.previous);
      preferred = {Option::Stick, s > 0 ? Option::SlipBackward : Option::SlipForward, Option::Leave,
                   option_of(foot.previous)};
    } else if (e != nullptr && e->kind == EventKind::LiftOff) {
      preferred = {Option::Leave, Option::Stick, Option::SlipForward, Option::SlipBackward};
    } else {
      for (Option o : {Option::Stick, Option::SlipForward, Option::SlipBackward, Option::Leave})
        add_unique(preferred, o);
    }
    const bool must_change = e != nullptr && e->kind != EventKind::Touchdown && e->kind != EventKind::SlipJam &&
                             e->kind != EventKind::SlipToStick;
    for (Option o : preferred) {
      if (!allowed(by_velocity, o)) continue;
      if (must_change && foot.was_on_ground && o == option_of(foot.previous)) continue;
      // A landing foot may leave at once when its leg does not press (f <= 0: grazing, or a jam
      // impulse turned the leg's motion around); the consistency test checks f.
      foot.options.push_back(o);
    }
  }

  // Enumerate every combination; score = Σ preference rank; keep the best consistent one.
  const int n = static_cast<int>(feet.size());
  std::array<int, kMaxContacts> pick{};
  std::vector<double> trial_state(y.begin(), y.end());
  double best_thetad = y[S::thetad];
  bool jam_blocked = false;  // some combination failed only because a slipping foot has D <= 0
  int best_score = std::numeric_limits<int>::max();
  // The inconsistent combinations tried and why (the failure's report, made only on failure).
  struct Tried {
    std::array<int, kMaxContacts> pick;
    std::string_view why;
  };
  std::array<Tried, 4 * 4 * 4> tried{};  // at most four options for each of at most three feet
  std::size_t tried_count = 0;
  for (bool more = true; more;) {
    bool empty = false;
    for (int i = 0; i < n; ++i) empty = empty || feet[i].options.empty();
    if (empty) break;
    ContactSet trial;
    int score = 0;
    for (int i = 0; i < n; ++i) {
      const Option o = feet[i].options[pick[i]];
      score += pick[i];
      if (o == Option::Leave) continue;
      const int j = trial.count++;
      trial.leg[j] = feet[i].leg;
      trial.mode[j] = mode_of(o);
      const bool keeps_stick = feet[i].was_on_ground && feet[i].previous == FootMode::Stick && o == Option::Stick;
      trial.anchor[j] = keeps_stick ? feet[i].anchor : leg_kinematics(w, feet[i].leg, y).c;
    }
    // I = 0: θ̇ takes the value that makes the first sticking foot's ċ vanish.
    std::vector<double>& yc = trial_state;
    std::copy(y.begin(), y.end(), yc.begin());
    if (w.I == 0) {
      for (int j = 0; j < trial.count; ++j) {
        if (trial.mode[j] != FootMode::Stick) continue;
        const LegKinematics g = leg_kinematics(w, trial.leg[j], yc);
        yc[S::thetad] = (yc[S::xd] - yc[S::yd] * g.tb) * g.cb * g.cb / yc[S::y];
        trial.anchor[j] = g.c;
        break;
      }
    }
    const Dynamics d = contact_dynamics(w, trial, yc);
    std::string_view why = d.failure ? failure_sentence(*d.failure) : std::string_view();
    jam_blocked = jam_blocked || d.jammed;
    for (int i = 0; i < n && why.empty(); ++i) {
      const Option o = feet[i].options[pick[i]];
      if (o == Option::Leave) {
        if (leg_kinematics(w, feet[i].leg, y).f > tol.force) why = "a leaving foot is still pressed (f > 0)";
        continue;
      }
      const int j = trial.find(feet[i].leg);
      const ContactForce& cf = d.force[j];
      const LegKinematics& g = d.leg[j];
      const double cdot = tested_cdot(feet[i], g);
      if (cf.N < -tol.force)
        why = "negative normal force";
      else if (o == Option::Stick && std::abs(cf.T) > w.mu_s * cf.N + tol.force)
        why = "stick outside the friction cone";
      else if (o == Option::Stick && std::abs(cdot) > tol.velocity)
        why = "a sticking foot would move";
      else if (o != Option::Stick && std::abs(cdot) > tol.velocity) {
        if (slip_sign(mode_of(o)) * cdot < 0) why = "friction would not oppose the slip";
      } else if (o != Option::Stick && !direction_decided(w, feet[i])) {
        const double cddot = g.A[0] * d.qdd[0] + g.A[1] * d.qdd[1] + g.A[2] * d.qdd[2] + g.Adot_qdot;
        if (slip_sign(mode_of(o)) * cddot < -tol.acceleration) why = "friction would not oppose the slip";
      }
    }
    if (why.empty()) {
      ++out.consistent;
      if (score < best_score) {
        best_score = score;
        out.contacts = trial;
        best_thetad = d.thetad;
      }
    } else {
      tried[tried_count++] = {pick, why};
    }
    more = false;
    for (int i = n - 1; i >= 0; --i) {  // next combination (odometer, last foot fastest)
      if (++pick[i] < feet[i].options.size()) {
        more = true;
        break;
      }
      pick[i] = 0;
    }
  }
  if (out.consistent == 0) {
    if (w.I == 0) {
      const bool single = n == 1;
      out.failure = current.count == 0 ? FailureReason::PointMassLanding
                    : single           ? FailureReason::PointMassSingleSlip
                                       : FailureReason::PointMassDoubleSupport;
    } else if (jam_blocked) {
      out.failure = FailureReason::PainleveParadox;
    } else {
      out.failure = FailureReason::NoConsistentMode;
    }
    for (std::size_t k = 0; k < tried_count && out.detail.size() < 600; ++k) {
      for (int i = 0; i < n; ++i)
        out.detail += fmt::format("{}{}={}", i ? "," : "", feet[i].leg, option_name(feet[i].options[tried[k].pick[i]]));
      out.detail += fmt::format(": {}; ", tried[k].why);
    }
    return out;
  }

  if (w.I == 0) y[S::thetad] = best_thetad;  // θ̇ jumps to the value the new mode fixes (I = 0)
  release_legs(w, current, events, out.contacts, y);
  return out;
}

}  // namespace flexgait::rimless
