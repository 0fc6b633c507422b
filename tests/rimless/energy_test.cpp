// The flexible wheel's mechanical energy (rimless/energy.hpp) term by term against the spec's
// formula, E = ½ m (ẋ² + ẏ²) + ½ I θ̇² + m g (y cos φ - x sin φ) + Σ_k ½ K δ_k², on hand-built
// states: a leg on the ground counts with its compression from the kinematics, a free leg with its
// relaxing compression in the state.
#include "flexgait/rimless/energy.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "wheel_states.hpp"

namespace flexgait::rimless {
namespace {

using testing::measured_wheel;
using testing::wheel_state;

TEST(Energy, TermsAreTheSpecsFormula) {
  WheelParams w = measured_wheel(0.6);
  w.slope = 0.2;
  const double beta = 0.1, L = 0.99;
  const auto s = wheel_state(w, beta, L * std::cos(beta), 0.7, -0.2, -1.1, {{0, FootMode::Stick}});
  const EnergyTerms e = mechanical_energy(w, s.contacts, s.y);
  const double x = s.y[StateIndex::x], y = s.y[StateIndex::y];
  // Every term is a few flops from the state: to 1e-14 J.
  EXPECT_NEAR(e.kinetic, 0.5 * w.m * (0.7 * 0.7 + 0.2 * 0.2) + 0.5 * w.I * 1.1 * 1.1, 1e-14);
  EXPECT_NEAR(e.gravity, w.m * w.g * (y * std::cos(w.slope) - x * std::sin(w.slope)), 1e-14);
  // Leg 0 on the ground is 1 % short; legs 1..9 free with δ_k = 1e-3 (k + 1) (its slot holds 1e-3, unused).
  double spring = 0.5 * w.K * (w.L0 - L) * (w.L0 - L);
  for (int k = 1; k < w.legs; ++k) spring += 0.5 * w.K * std::pow(1e-3 * (k + 1), 2);
  EXPECT_NEAR(e.spring, spring, 1e-12);
  EXPECT_EQ(e.total(), e.kinetic + e.gravity + e.spring);
  EXPECT_EQ(kinetic_energy(w, s.y), e.kinetic);
}

TEST(Energy, APointMassHasNoRotationalEnergy) {
  WheelParams w = measured_wheel(0.6);
  w.I = 0.0;
  const auto s = wheel_state(w, 0.0, 0.98, 1.0, 2.0, 50.0, {});
  EXPECT_EQ(kinetic_energy(w, s.y), 0.5 * w.m * 5.0);
}

TEST(Energy, GravityTermIsTheHeightAboveTheHorizontal) {
  // A move of the hub along the world's horizontal, (Δx, Δy) = (cos φ, sin φ) in the slope frame,
  // keeps the potential; a move of 1 m straight up, (-sin φ, cos φ), adds m g.
  WheelParams w = measured_wheel(0.6);
  w.slope = 0.3;
  auto s = wheel_state(w, 0.0, 0.98, 0.0, 0.0, 0.0, {});
  const double g0 = mechanical_energy(w, s.contacts, s.y).gravity;
  auto moved = s.y;
  moved[StateIndex::x] += 2.0 * std::cos(w.slope);
  moved[StateIndex::y] += 2.0 * std::sin(w.slope);
  EXPECT_NEAR(mechanical_energy(w, s.contacts, moved).gravity, g0, 1e-14);
  moved = s.y;
  moved[StateIndex::x] -= std::sin(w.slope);
  moved[StateIndex::y] += std::cos(w.slope);
  EXPECT_NEAR(mechanical_energy(w, s.contacts, moved).gravity, g0 + w.m * w.g, 1e-13);
}

}  // namespace
}  // namespace flexgait::rimless
