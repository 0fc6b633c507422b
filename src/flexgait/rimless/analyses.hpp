#pragma once
/// \file analyses.hpp
/// The paper's analyses (Bao, Zhang, Zhou 2024; spec rimless.md, "What the paper does"), each
/// producing CSV text. The command line writes them with a PNG each.
///   1. gait behaviour against the friction coefficient, with the thresholds between behaviours;
///   2. energy during single support, sticking against slipping;
///   3. a fixed point and its multipliers for each of the four behaviours;
///   4. robustness of the sliding gait: the largest perturbation of the fixed point that returns;
///   5. the stagnation interval (paper Fig. 12) has its own file, stagnation.hpp.
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/rimless/fixed_point.hpp"

namespace flexgait::rimless {

/// The periodic gait at μ = μ_s = μ_k, found as robustly as the map allows.
struct FrictionGait {
  double mu = 0;
  bool converged = false;      ///< a fixed point was found
  bool stable = false;         ///< ... with every multiplier inside the unit circle
  double max_multiplier = 0;   ///< its largest |multiplier|
  std::string gait;            ///< the fixed point's label ("(unstable)" appended when unstable), else the
                               ///< transient's with " (no fixed point)", else "none"
  std::string source;          ///< how it was found: "start", "start, N transient steps", "continued from mu = …"
  SectionState point;          ///< the fixed point (when converged)
};

/// The gait at μ: Newton from the configured start after analysis.transient_steps, then after
/// 3 and 9 times as many while the transient's mode is still changing (Newton keeps the section's
/// mode); failing that, natural-parameter continuation from the first converged neighbour in
/// `neighbours` (in 1, 4 or 16 equal steps of μ). "(no fixed point)" only when all of these fail.
FrictionGait friction_gait(const Config& base, double mu, Section section,
                           const std::vector<const FrictionGait*>& neighbours = {});

/// friction_gait at every μ of `mus` (ascending), then once more, continued from the nearest
/// converged neighbour, at every point that found no fixed point.
std::vector<FrictionGait> friction_gaits(const Config& base, const std::vector<double>& mus, Section section);

/// CSV: mu, gait, converged, stable, max_multiplier, source.
std::string friction_gaits_csv(const std::vector<FrictionGait>& gaits);

/// Thresholds between behaviours along `gaits`, each refined by bisection to `tolerance` (the
/// midpoints continued from the bracket's fixed points); a behaviour met inside a bracket splits
/// it. CSV: mu_low, mu_high (the final bracket), gait_below, gait_above, threshold.
std::string friction_thresholds_csv(const Config& base, const std::vector<FrictionGait>& gaits, Section section,
                                    double tolerance);

/// Analysis 2: one periodic step on the fixed point at each μ, logged. CSV: mu, gait, phase
/// (stick/slip of the stance foot), t (since the step's start), beta (stance leg), E_kinetic,
/// E_total_minus_start (mechanical energy minus its value at the step's start), in single support.
std::string single_support_energy_csv(const Config& base, const std::vector<double>& mus);

/// Analysis 3: CSV: mu, gait, converged, mode, state, |multiplier| (largest), multipliers (re:im;...),
/// stable, period, speed, dissipated_per_cycle.
std::string behaviour_fixed_points_csv(const Config& base, const std::vector<double>& mus, Section section);

/// Analysis 4: from the fixed point at μ, perturb each reduced-state component by ±ε·scale for
/// ε in `epsilons`, iterate the map up to `max_steps`; "returned" when within 1e-6·scale.
/// CSV: mu, component, sign, epsilon, returned, steps, failure.
std::string robustness_csv(const Config& base, double mu, const std::vector<double>& epsilons, int max_steps);

}  // namespace flexgait::rimless
