#pragma once
/// \file guard_crossings.hpp
/// Which guard functions g_i(t, y(t)) cross zero over one integrator step, and where first, by
/// SUNDIALS CVODE's rules (cvRcheck1–3 in cvode.c), for integrators with a continuous interpolant:
/// - a guard crosses when its sign changes over the step or it reaches exactly 0 at the step's end;
///   direction +1 counts rising crossings only, -1 falling only, 0 both;
/// - a guard exactly 0 where a segment starts is inactive until it moves away from 0: it is looked
///   at a tenth of the first step later and, if still 0, at the step's end;
/// - the crossing time is the earliest guard root, located by TOMS 748 (Alefeld, Potra & Shi 1995;
///   Boost.Math's toms748_solve) on the interpolant to CVODE's tolerance 100·u·(|t| + |h|), on
///   the side where the guard has crossed; every guard that has crossed by then fires.
/// One rule beyond CVODE's, for integrators whose first step after a restart is long (DOP853): a
/// guard that starts at 0 or on its crossed side and ends the first step on its crossed side may
/// have been on the other side in between (a foot that starts to slip and reverses within the
/// step). It is probed on the interpolant at t + h 2^-k, k = 1…kProbeLevels; where it is found on
/// the other side, its bracket starts there. (CVODE's first steps after a restart are short
/// enough that its step ends see such a hump.)
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace flexgait::numerics {

class GuardCrossings {
 public:
  /// g(t, out): every guard's value at t within the last step, from the interpolant (dim count()).
  using Values = std::function<void(double t, std::span<double> g)>;
  /// g_i(t): guard i's value at t within the last step (the same number Values gives for it).
  using Value = std::function<double(double t, int i)>;

  /// Starts watching at t with the guards' values g there and their crossing directions.
  void start(double t, std::span<const int> directions, std::span<const double> g);
  /// After a step to t1 with g1 = g(t1) (dim count()): the earliest crossing time in the step if a
  /// guard crossed (fired() says which; watching then restarts there), else nothing (watching
  /// moves on to t1).
  /// The crossing's root is located on guard i alone (g_i_at).
  std::optional<double> check(double t1, std::span<const double> g1, const Values& g_at, const Value& g_i_at);
  /// Per guard, after check() found a crossing: +1 crossed upward, -1 downward, 0 not crossed.
  std::span<const int> fired() const { return fired_; }
  int count() const { return static_cast<int>(directions_.size()); }

 private:
  /// Watching (re)starts at t with the guards' values g: those exactly 0 are inactive.
  void rearm(double t, std::span<const double> g);
  /// The probe of the first step after (re)arming, for guards not armed at either end (above).
  void probe_unarmed(double t1, std::span<const double> g1, const Values& g_at);

  static constexpr int kProbeLevels = 12;  // probes down to h / 4096
  bool first_step_ = false;      // the next check() is the first step after (re)arming

  double t_ = 0.0;               // where watching (re)started: the last step's end or crossing [s]
  std::vector<int> directions_;  // per guard: +1, -1, 0
  std::vector<double> g_lo_;     // per guard: its value where its bracket starts
  std::vector<double> t_lo_;     // per guard: where its bracket starts (t_, or later if it was 0 there)
  std::vector<char> active_;     // per guard: 0 while it has stayed exactly 0 since t_
  std::size_t inactive_ = 0;     // guards with active_ 0
  std::vector<int> fired_;       // per guard: the last crossing's direction, or 0
  std::vector<double> scratch_;  // guard values at one time
};

}  // namespace flexgait::numerics
