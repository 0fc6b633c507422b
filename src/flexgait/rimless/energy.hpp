#pragma once
/// \file energy.hpp
/// Mechanical energy of the flexible wheel (docs/theory/rimless.md, "Energy"):
///   E = ½ m (ẋ² + ẏ²) + ½ I θ̇² + m g (y cos φ - x sin φ) + Σ_k ½ K δ_k²
/// over every leg (a relaxing free leg included). Along a solution
///   dE/dt = -Σ C δ̇_k² - Σ_slip μ_k N_k |ċ_k|,
/// so E(t) + W_damp(t) + W_fric(t) = E(0), with W_damp and W_fric carried in the state.
#include <span>

#include "flexgait/rimless/contact.hpp"

namespace flexgait::rimless {

struct EnergyTerms {
  double kinetic = 0;  ///< [J]
  double gravity = 0;  ///< m g (y cos φ - x sin φ) [J]
  double spring = 0;   ///< Σ ½ K δ² over all legs [J]
  double total() const { return kinetic + gravity + spring; }
};

EnergyTerms mechanical_energy(const WheelParams& w, const ContactSet& contacts, std::span<const double> y);

/// Kinetic energy ½ q̇ᵀ M q̇ [J].
double kinetic_energy(const WheelParams& w, std::span<const double> y);

}  // namespace flexgait::rimless
