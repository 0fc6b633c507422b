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

/// The gait at μ = μ_s = μ_k: the fixed point's label, or the transient's when there is none.
std::string gait_at_friction(const Config& base, double mu, Section section);

/// Thresholds between behaviours from a μ sweep's rows (value, gait), each refined by bisection
/// to `tolerance`; a behaviour met inside a bracket splits it. CSV: mu_low, mu_high (the final
/// bracket), gait_below, gait_above, threshold.
std::string friction_thresholds_csv(const Config& base, const std::vector<std::pair<double, std::string>>& points,
                                    Section section, double tolerance);

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
