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
///   the side where the guard has crossed; every guard that has crossed by then fires, and every
///   guard whose own root lies within that tolerance of it (a tie, whatever the round-off).
/// One rule beyond CVODE's, for integrators whose first step after a restart is long (DOP853): a
/// guard that starts at 0 or on its crossed side and ends the first step on its crossed side may
/// have been on the other side in between (a foot that starts to slip and reverses within the
/// step). It is probed on the interpolant at t + h 2^-k, k = 1…kProbeLevels; where it is found on
/// the other side, its bracket starts there. (CVODE's first steps after a restart are short
/// enough that its step ends see such a hump.)
///
/// And one rule for every step, against a guard that crosses and returns within it (both ends on
/// the side before the crossing, so CVODE's end-point rule sees nothing): every guard is sampled
/// on the interpolant at kSamples - 1 evenly spaced interior points, and each sample is treated
/// like a step end (a crossing there brackets the root, a sample on the side before a crossing
/// starts the bracket). Between two samples a and b on one side of 0 the guard can reach 0 only
/// if its curvature allows it: for |g''| <= M,
///   |g(s)| >= min(|g(a)|, |g(b)|) - M (b - a)^2 / 8   on [a, b]
/// (the error bound of linear interpolation). M is taken as twice the largest |g''| the samples' second divided
/// differences show (each is g'' at some point of its two intervals); where the bound does not
/// exclude 0 the interval is bisected, to kRefineDepth levels and kRefineBudget evaluations per
/// step, until a sample crosses or the bound excludes a root. A dip shorter than the spacing
/// and shallower than its curvature shows is the one crossing this can still miss.
///
/// The midpoint is sampled first. Where, for every guard, the step's ends and the midpoint lie on
/// one side of 0 and the same bound over the two halves, with M = 2x the |g''| their one second
/// difference shows and kCoarseMargin = 4 times more margin,
///   min |g| > 4 M (h/2)^2 / 8,
/// excludes a root, the other samples are not taken. Within one mode a guard is a smooth function
/// of the state, and the integrator's step resolves the state (for DOP853's 8th order at rtol
/// 1e-10, h is a few tenths of the state's time scale or less; CVODE's steps are shorter), so g''
/// varies over a step by far less than the factor 8 this margin allows. That is every step of a
/// guard far from 0 (CVODE's short steps almost always); a guard near 0 for its curvature, or a
/// step with a crossing, still gets all the samples, with the same brackets and roots as if
/// sampled at once.
///
/// Before the midpoint, a step that follows a step of the same segment (no crossing, no restart
/// since; every guard watched from that step's start, none activated or probed later) is first bounded without any
/// evaluation, from the guards' values at the three step ends it already has: the previous step's start a, this step's
/// start b and its end c. Where, for every guard, a, b and c lie on one side of 0, the previous step is at most
/// kPreviousStepRatio times as long as this one, and the same bound over the step [b, c], with M = 2x the |g''| the
/// second divided difference g[a, b, c] shows and kCoarseMargin times more margin,
///   min(|g(b)|, |g(c)|) > kCoarseMargin M (c - b)^2 / 8,
/// excludes a root, the step takes no sample and the integrator's dense output is not prepared.
/// This is the midpoint rule's assumption, that g'' over the step stays within 8x (the factor 2 in
/// M times the margin) of what one second difference shows, taken over a window of two steps
/// (at most (1 + kPreviousStepRatio) h) instead of one: the window is still a fraction of the
/// state's time scale, which the step resolves. A step that shrank more than that against its
/// predecessor (the controller meeting faster dynamics) takes the samples. For the same measured
/// curvature the bound asks 4x more distance from 0 than the midpoint rule's (one part of length
/// h instead of two of h/2). What either rule can miss is a dip whose curvature shows at none of
/// its points: for this one, a feature that arises within the step and is absent at its ends and
/// at the previous step's start.
///
/// A slot with direction kNoGuard (ode_system.hpp) holds no guard in this mode: none of the rules
/// above looks at it and it never fires. Its constant value would pass every one of them (no
/// crossing, every difference 0), so the crossings found are those of watching it, at the cost
/// of the mode's own guards alone.
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "flexgait/numerics/ode_system.hpp"

namespace flexgait::numerics {

/// The root of g in [a, b] (g(a) = ga and g(b) = gb of opposite signs, or gb = 0) by TOMS 748
/// until the bracket is shorter than tol: the end of that bracket on b's side (b if gb = 0).
double locate_root(const std::function<double(double)>& g, double a, double b, double ga, double gb, double tol);

class GuardCrossings {
 public:
  /// g(t, out): every guard's value at t within the last step, from the interpolant (dim count()).
  using Values = std::function<void(double t, std::span<double> g)>;
  /// g_i(t): guard i's value at t within the last step (the same number Values gives for it).
  using Value = std::function<double(double t, int i)>;

  /// Starts watching at t with the guards' values g there and their crossing directions (+1, -1,
  /// 0, or kNoGuard: not watched).
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
  /// The interior samples of the step to t1 (above): per guard, the bracket of its first crossing
  /// in the step, if any (lo_t_, lo_g_, hi_t_, hi_g_; hi_t_ = t1 and hi_g_ = g1 where the samples
  /// show none). False: the coarse bound excludes every crossing (the brackets are not set).
  bool sample_interior(double t1, std::span<const double> g1, const Values& g_at);
  struct Point {
    double t, g;
  };
  /// Whether the midpoint sample (samples_ row mid, at t_mid) and the step's ends exclude a root
  /// of every guard by the coarse bound (above).
  bool coarse_excludes(double t1, std::span<const double> g1, double t_mid, std::size_t mid) const;
  /// Whether the previous step's start, this step's start and its end t1 (g1) exclude a root of
  /// every guard in the step by the two-step bound (above).
  bool previous_step_excludes(double t1, std::span<const double> g1) const;
  /// Between a and b (no crossing from a to b): bisects while the curvature bound (above) does not
  /// exclude a root; true with the bracket in `lo`, `hi` where a sample crosses.
  bool refine(std::size_t i, Point a, Point b, int depth, const Values& g_at, Point& lo, Point& hi);

 public:
  static constexpr int kSamples = 4;        ///< a step is sampled as this many equal parts
  static constexpr int kRefineDepth = 6;    ///< bisections of one part, at most (to h / 256)
  static constexpr int kRefineBudget = 24;  ///< extra evaluations of the guards per step, at most
  /// The coarse bound's margin over the curvature its one second difference shows (above).
  static constexpr double kCoarseMargin = 4.0;
  /// The two-step bound (above) needs the previous step no longer than this many times this one.
  static constexpr double kPreviousStepRatio = 1.5;
  /// The guards' evaluations of the interior samples so far (the cost of the rule above).
  long long interior_evaluations() const { return interior_evaluations_; }

 private:
  static constexpr int kProbeLevels = 12;  // probes down to h / 4096
  bool first_step_ = false;                // the next check() is the first step after (re)arming

  double t_ = 0.0;                    // where watching (re)started: the last step's end or crossing [s]
  std::vector<int> directions_;       // per guard: +1, -1, 0 or kNoGuard
  std::vector<std::size_t> watched_;  // the guards whose direction is not kNoGuard, ascending
  std::vector<double> g_lo_;          // per guard: its value where its bracket starts
  std::vector<double> t_lo_;          // per guard: where its bracket starts (t_, or later if it was 0 there)
  std::vector<char> active_;          // per guard: 0 while it has stayed exactly 0 since t_
  std::size_t inactive_ = 0;          // guards with active_ 0
  std::vector<int> fired_;            // per guard: the last crossing's direction, or 0
  std::vector<double> scratch_;       // guard values at one time
  std::vector<double> samples_;       // (kSamples - 1) × count(): the guards at the interior samples
  std::vector<double> lo_t_, lo_g_, hi_t_, hi_g_;  // per guard: its bracket in the current step
  std::vector<double> curvature_;                  // per guard: M of the bound above, for the current step
  std::vector<double> roots_;                      // per guard: its root in the current step (infinity: none)
  bool lo_at_start_ = false;                       // every guard is active and its bracket starts at t_ (t_lo_ = t_)
  bool has_prev_ = false;       // the previous step is in this segment, every guard watched from its start
  double prev_t_ = 0.0;         // the previous step's start [s]
  std::vector<double> prev_g_;  // per guard: its value there
  int budget_ = 0;              // refinement evaluations left in the current step
  long long interior_evaluations_ = 0;
};

}  // namespace flexgait::numerics
