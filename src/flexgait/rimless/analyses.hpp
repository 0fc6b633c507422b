#pragma once
/// \file analyses.hpp
/// The paper's analyses (Bao, Zhang, Zhou 2024; docs/theory/rimless.md), each
/// producing CSV text. The command line writes them with a PNG each.
///   1. gait behaviour against the friction coefficient, with the thresholds between behaviours;
///   2. energy during single support, sticking against slipping;
///   3. a fixed point and its multipliers for each of the four behaviours;
///   4. robustness of the sliding gait: the largest perturbation of the fixed point that returns;
///   5. the stagnation interval (paper Fig. 12) has its own file, stagnation.hpp.
#include <functional>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/rimless/fixed_point.hpp"

namespace flexgait::rimless {

/// What the paper's analyses compute, keys `analysis.<analysis>.*` (`flexgait rimless analysis
/// NAME`; the options --mu, --from, --to and --count set the running analysis's keys). The
/// defaults are the values the analyses always used: the four behaviours at μ = 0.105 (sliding,
/// just above tan φ = 0.1003), 0.13, 0.2 and 0.6 (sticking); the friction sweep over the spec's
/// μ ∈ (0, 1.5).
struct PaperAnalysisOptions {
  double friction_mu_from = 0.1;    ///< gait-vs-friction: first μ of the sweep
  double friction_mu_to = 1.5;      ///< gait-vs-friction: last μ
  int friction_count = 100;         ///< gait-vs-friction: number of values of μ, evenly spaced, ends included
  double threshold_tol = 1e-8;      ///< gait-vs-friction: bisection of a threshold stops at this bracket width in μ
  double continued_bracket = 1e-4;  ///< gait-vs-friction: narrower brackets continue a midpoint from their ends first
  int split_depth = 4;              ///< gait-vs-friction: nested splits of a bracket by a third behaviour, at most
  /// gait-vs-friction: Newton from the start after analysis.transient_steps times each factor, in turn
  std::vector<double> transient_factors{1, 3, 9};
  /// gait-vs-friction: natural-parameter continuation from a neighbour in each number of equal steps of μ, in turn
  std::vector<double> continuation_steps{1, 4, 16};
  std::vector<double> energy_mu{0.6, 0.105};                   ///< energy: μ of each periodic step logged
  std::vector<double> fixed_points_mu{0.105, 0.13, 0.2, 0.6};  ///< fixed-points: μ of each row
  std::vector<double> robustness_mu{0.105, 0.6};               ///< robustness: μ of each fixed point perturbed
  double epsilon_min = 1e-3;  ///< robustness: smallest perturbation, a fraction of the component's scale
  double epsilon_max = 1.0;   ///< robustness: largest perturbation
  int epsilon_count = 13;     ///< robustness: perturbations, log-spaced, ends included (4 per decade)
  int max_steps = 300;        ///< robustness: map iterations allowed to return
  double return_tol = 1e-6;   ///< robustness: returned when every component is within this × its scale

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("analysis.friction.mu_from", s.friction_mu_from,
      {.doc = "gait-vs-friction: first mu = mu_s = mu_k of the sweep (--from)", .bounds = non_negative()});
    v("analysis.friction.mu_to", s.friction_mu_to,
      {.doc = "gait-vs-friction: last mu of the sweep (--to)", .bounds = non_negative()});
    v("analysis.friction.count", s.friction_count,
      {.doc = "gait-vs-friction: number of values of mu, evenly spaced, ends included (--count)",
       .bounds = closed(1, 1000000)});
    v("analysis.friction.threshold_tol", s.threshold_tol,
      {.doc = "gait-vs-friction: bisection of each threshold stops at this bracket width in mu",
       .bounds = closed(1e-15, 1)});
    v("analysis.friction.continued_bracket", s.continued_bracket,
      {.doc = "gait-vs-friction: in a bracket narrower than this (in mu) a midpoint's gait is Newton's from the "
              "bracket's fixed points first, the start's only when neither converges",
       .bounds = non_negative()});
    v("analysis.friction.split_depth", s.split_depth,
      {.doc = "gait-vs-friction: a third behaviour inside a bracket splits it, nested at most this deep",
       .bounds = closed(0, 64)});
    v("analysis.friction.transient_factors", s.transient_factors,
      {.doc = "gait-vs-friction: Newton from the start after analysis.transient_steps times each factor in turn, "
              "while the transient's mode still changes (whole numbers)",
       .bounds = closed(1, 1000)});
    v("analysis.friction.continuation_steps", s.continuation_steps,
      {.doc = "gait-vs-friction: where the start finds no fixed point, continuation in mu from a neighbour's in each "
              "number of equal steps in turn (whole numbers)",
       .bounds = closed(1, 10000)});
    v("analysis.energy.mu", s.energy_mu,
      {.doc = "energy: mu = mu_s = mu_k of each periodic step logged (--mu)", .bounds = non_negative()});
    v("analysis.fixed_points.mu", s.fixed_points_mu,
      {.doc = "fixed-points: mu = mu_s = mu_k of each fixed point (--mu)", .bounds = non_negative()});
    v("analysis.robustness.mu", s.robustness_mu,
      {.doc = "robustness: mu = mu_s = mu_k of each fixed point perturbed (--mu)", .bounds = non_negative()});
    v("analysis.robustness.epsilon_min", s.epsilon_min,
      {.doc = "robustness: smallest perturbation, as a fraction of each component's scale", .bounds = positive()});
    v("analysis.robustness.epsilon_max", s.epsilon_max,
      {.doc = "robustness: largest perturbation (>= epsilon_min)", .bounds = positive()});
    v("analysis.robustness.epsilon_count", s.epsilon_count,
      {.doc = "robustness: number of perturbations, log-spaced from epsilon_min to epsilon_max, ends included",
       .bounds = closed(1, 10000)});
    v("analysis.robustness.max_steps", s.max_steps,
      {.doc = "robustness: map iterations allowed for a perturbed state to return", .bounds = closed(1, 1000000)});
    v("analysis.robustness.return_tol", s.return_tol,
      {.doc = "robustness: returned when every component is within this fraction of its scale of the fixed point",
       .bounds = open(0, 1)});
  }
};
inline Schema paper_analysis_schema() {
  return schema_of<PaperAnalysisOptions>();
}
/// The options of a resolved configuration; throws ConfigError (key named) if epsilon_max < epsilon_min
/// or a factor or step count is not a whole number.
PaperAnalysisOptions paper_analysis_from_config(const Config& config);

/// The robustness perturbations ε_k = ε_min 10^(k log10(ε_max/ε_min)/(n − 1)), k = 0..n−1 (ε_min alone
/// when n = 1); the defaults give 1e-3 · 10^(k/4), k = 0..12.
std::vector<double> robustness_epsilons(const PaperAnalysisOptions& options);

/// The periodic gait at μ = μ_s = μ_k, found as robustly as the map allows.
struct FrictionGait {
  double mu = 0;
  bool converged = false;     ///< a fixed point was found
  bool stable = false;        ///< ... with every multiplier inside the unit circle
  double max_multiplier = 0;  ///< its largest |multiplier|
  std::string gait;           ///< the fixed point's label ("(unstable)" appended when unstable), else the
                              ///< transient's with " (no fixed point)", else "none"
  std::string source;         ///< how it was found: "start", "start, N transient steps", "continued from mu = …"
  SectionState point;         ///< the fixed point (when converged)
};

/// The gait at μ: Newton from the configured start after analysis.transient_steps times each of
/// `options.transient_factors` (1, 3, 9) in turn while the transient's mode is still changing (Newton
/// keeps the section's mode); failing that, natural-parameter continuation from the first converged
/// neighbour in `neighbours` (in each of `options.continuation_steps`, 1, 4 or 16, equal steps of μ).
/// "(no fixed point)" only when all of these fail.
FrictionGait friction_gait(const Config& base, double mu, Section section, const PaperAnalysisOptions& options,
                           const std::vector<const FrictionGait*>& neighbours = {});

/// friction_gait at every μ of `mus` (ascending), then once more, continued from the nearest
/// converged neighbour, at every point that found no fixed point.
std::vector<FrictionGait> friction_gaits(const Config& base, const std::vector<double>& mus, Section section,
                                         const PaperAnalysisOptions& options);

/// CSV: mu, gait, converged, stable, max_multiplier, source.
std::string friction_gaits_csv(const std::vector<FrictionGait>& gaits);

/// Thresholds between behaviours along `gaits`, each refined by bisection to `options.threshold_tol`
/// (the midpoints continued from the bracket's fixed points below `options.continued_bracket`); a
/// behaviour met inside a bracket splits it (`options.split_depth` deep at most).
/// CSV: mu_low, mu_high (the final bracket), gait_below, gait_above, threshold.
std::string friction_thresholds_csv(const Config& base, const std::vector<FrictionGait>& gaits, Section section,
                                    const PaperAnalysisOptions& options);

/// Analysis 2: one periodic step on the fixed point at each μ, logged. CSV: mu, gait, phase
/// (stick/slip of the stance foot), t (since the step's start), beta (stance leg), E_kinetic,
/// E_total_minus_start (mechanical energy minus its value at the step's start), in single support.
std::string single_support_energy_csv(const Config& base, const std::vector<double>& mus);

/// Analysis 3: CSV: mu, gait, converged, mode, state, |multiplier| (largest), multipliers (re:im;...),
/// stable, period, speed, dissipated_per_cycle.
std::string behaviour_fixed_points_csv(const Config& base, const std::vector<double>& mus, Section section);

/// Analysis 4: from the fixed point at μ, perturb each reduced-state component by ±ε·scale for
/// ε in `epsilons`, iterate the map up to `max_steps`; "returned" when within `return_tol`·scale.
/// CSV: mu, component, sign, epsilon, returned, steps, failure.
/// The columns of robustness.csv (robustness_csv writes them; `flexgait schema` lists them).
const std::vector<std::string>& robustness_csv_columns();
/// `progress`, if given, is called after each perturbation with the fraction of them done.
std::string robustness_csv(const Config& base, double mu, const std::vector<double>& epsilons, int max_steps,
                           double return_tol, const std::function<void(double fraction)>& progress = {});

}  // namespace flexgait::rimless
