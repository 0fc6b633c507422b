// The flexible wheel's constrained dynamics (rimless/dynamics.hpp) on hand-built states: the
// Lagrange equations it states hold for the accelerations and forces it returns, a sticking foot's
// constraint row holds, a slipping foot obeys its friction law, the pendulum about a sticking foot
// has its closed form, and the Painlevé jam is reported.
#include "flexgait/rimless/dynamics.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "wheel_states.hpp"

namespace flexgait::rimless {
namespace {

using testing::measured_wheel;
using testing::wheel_state;

// The residual of diag(m, m, I) q̈ = m g (sin φ, -cos φ, 0) + Σ_k [f_k ∂L_k/∂q + A_kᵀ T_k] per row,
// and the largest force term, for a relative bound.
void expect_lagrange_equations_hold(const WheelParams& w, const ContactSet& c, const Dynamics& d) {
  const std::array<double, 3> mass{w.m, w.m, w.I};
  std::array<double, 3> Q{w.m * w.g * std::sin(w.slope), -w.m * w.g * std::cos(w.slope), 0.0};
  double scale = w.m * w.g;
  for (int i = 0; i < c.count; ++i)
    for (int j = 0; j < 3; ++j) {
      Q[j] += d.force[i].f * d.leg[i].gradL[j] + d.leg[i].A[j] * d.force[i].T;
      scale = std::max({scale, std::abs(d.force[i].f), std::abs(d.force[i].T)});
    }
  // The solve is a 3×3 (plus ≤ 3 rows) system of condition ~1e2: residuals within 1e-12 of the forces.
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(mass[j] * d.qdd[j], Q[j], 1e-12 * scale) << "row " << j;
}

TEST(Dynamics, LagrangeEquationsAndContactLawsHoldInEveryMode) {
  const WheelParams w = measured_wheel(0.6);
  const double a = w.alpha();
  const double h1 = 0.99 * std::cos(0.1);  // one foot at β = 0.1, leg 1 % short
  const double h2 = 0.995 * std::cos(a);   // two feet at β = ∓α, legs 0.5 % short
  struct Case {
    const char* name;
    testing::WheelState s;
  };
  const Case cases[] = {
      {"stick", wheel_state(w, 0.1, h1, 0.3, -0.1, -0.8, {{0, FootMode::Stick}})},
      // forward slip: ċ = ẋ - tan β ẏ - y θ̇ / cos² β > 0 with ẋ large
      {"slip forward", wheel_state(w, 0.1, h1, 2.0, -0.1, -0.8, {{0, FootMode::SlipForward}})},
      {"slip backward", wheel_state(w, 0.1, h1, -1.0, -0.1, 0.8, {{0, FootMode::SlipBackward}})},
      {"two sticking", wheel_state(w, -a, h2, 0.3, -0.05, -0.5, {{0, FootMode::Stick}, {1, FootMode::Stick}})},
      {"stick and slip", wheel_state(w, -a, h2, 0.3, -0.05, -0.5, {{0, FootMode::Stick}, {1, FootMode::SlipForward}})},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    const Dynamics d = contact_dynamics(w, k.s.contacts, k.s.y);
    ASSERT_FALSE(d.failure.has_value());
    expect_lagrange_equations_hold(w, k.s.contacts, d);
    for (int i = 0; i < k.s.contacts.count; ++i) {
      const ContactForce& f = d.force[i];
      const LegKinematics& leg = d.leg[i];
      // N = (f - T sin β) / cos β, to rounding.
      EXPECT_NEAR(f.N, (f.f - f.T * leg.sb) / leg.cb, 1e-12 * std::abs(f.f));
      const int s = slip_sign(k.s.contacts.mode[i]);
      if (s == 0) {
        // A q̈ = -Ȧ q̇ - 2 ω_b ċ - ω_b² (c - anchor); the anchor is where the foot is, so the last term is 0.
        double Aq = 0;
        for (int j = 0; j < 3; ++j) Aq += leg.A[j] * d.qdd[j];
        EXPECT_NEAR(Aq, -leg.Adot_qdot - 2 * kStickStabilization * leg.cdot, 1e-10);
        EXPECT_EQ(f.D, 1.0);
      } else {
        EXPECT_NEAR(f.T, -s * w.mu_k * f.N, 1e-12 * std::abs(f.N));  // Coulomb
        EXPECT_NEAR(f.D, leg.cb - w.mu_k * s * leg.sb, 1e-15);
      }
    }
  }
}

// One sticking foot straight below the hub (β = 0), at rest, the leg at its static compression
// m g cos φ / K: a pendulum about the foot. Torque m g y sin φ about the foot over I + m y² gives
// θ̈; the foot holds T = -m g sin φ · I / (I + m y²) and N = m g cos φ; ÿ = 0.
TEST(Dynamics, PendulumAboutAStickingFootHasItsClosedForm) {
  for (double I : {0.3, 0.05}) {
    WheelParams w = measured_wheel(0.6);
    w.I = I;
    const double y = w.L0 - w.m * w.g * std::cos(w.slope) / w.K;
    const auto s = wheel_state(w, 0.0, y, 0.0, 0.0, 0.0, {{0, FootMode::Stick}});
    const Dynamics d = contact_dynamics(w, s.contacts, s.y);
    ASSERT_FALSE(d.failure.has_value());
    const double J = I + w.m * y * y;
    const double sp = std::sin(w.slope), cp = std::cos(w.slope);
    // Closed forms against a 3×3 solve: 1e-12 relative.
    EXPECT_NEAR(d.qdd[2], w.m * w.g * y * sp / J, 1e-12);
    EXPECT_NEAR(d.qdd[0], y * d.qdd[2], 1e-12);
    EXPECT_NEAR(d.qdd[1], 0.0, 1e-12);
    EXPECT_NEAR(d.force[0].T, -w.m * w.g * sp * I / J, 1e-12);
    EXPECT_NEAR(d.force[0].N, w.m * w.g * cp, 1e-12);
  }
}

TEST(Dynamics, SlipWithNonPositiveDenominatorIsAPainleveJam) {
  // β = -1.2: D = cos β - μ s sin β = 0.362 + 0.559 s; backward slip (s = -1) gives D = -0.197,
  // a jam; forward slip D = 0.92.
  const WheelParams w = measured_wheel(0.6);
  const double beta = -1.2;
  const double h = 0.98 * std::cos(beta);
  const auto backward = wheel_state(w, beta, h, 0.0, 0.0, 0.0, {{0, FootMode::SlipBackward}});
  const Dynamics jam = contact_dynamics(w, backward.contacts, backward.y);
  EXPECT_TRUE(jam.jammed);
  EXPECT_TRUE(jam.failure.has_value());
  EXPECT_LE(std::cos(beta) + w.mu_k * std::sin(beta), 0.0);  // the case is a jam by the formula
  const auto forward = wheel_state(w, beta, h, 0.0, 0.0, 0.0, {{0, FootMode::SlipForward}});
  const Dynamics ok = contact_dynamics(w, forward.contacts, forward.y);
  EXPECT_FALSE(ok.jammed);
  EXPECT_FALSE(ok.failure.has_value());
}

TEST(Dynamics, SolveConstrainedSatisfiesBothBlockRows) {
  // [M -Aᵀ; A 0] [a; λ] = [F; b]: M a - Aᵀ λ = F and A a = b, for 0–3 rows, I > 0 and I = 0.
  const std::array<std::array<double, 3>, kMaxContacts> A{{{1.0, -0.3, -0.9}, {1.0, 0.4, -1.1}, {0.2, 1.0, 0.5}}};
  const std::array<double, 3> F{2.0, -9.0, 0.7};
  const std::array<double, kMaxContacts> b{0.5, -0.2, 0.1};
  for (double I : {0.3, 0.0}) {
    WheelParams w;
    w.I = I;
    const std::array<double, 3> mass{w.m, w.m, w.I};
    for (int rows = 0; rows <= 3; ++rows) {
      std::array<double, 3> a{};
      std::array<double, kMaxContacts> lambda{};
      const bool solved = solve_constrained(w, rows, A, F, b, a, lambda);
      if (I == 0.0 && rows == 0) {  // the θ row 0 = F_θ ≠ 0 has no solution
        EXPECT_FALSE(solved);
        continue;
      }
      ASSERT_TRUE(solved) << "I " << I << ", rows " << rows;
      for (int j = 0; j < 3; ++j) {
        double r = mass[j] * a[j] - F[j];
        for (int i = 0; i < rows; ++i) r -= A[i][j] * lambda[i];
        EXPECT_NEAR(r, 0.0, 1e-12) << "I " << I << ", rows " << rows << ", row " << j;
      }
      for (int i = 0; i < rows; ++i) {
        double r = -b[i];
        for (int j = 0; j < 3; ++j) r += A[i][j] * a[j];
        EXPECT_NEAR(r, 0.0, 1e-12) << "I " << I << ", rows " << rows << ", constraint " << i;
      }
    }
  }
}

TEST(Dynamics, DependentConstraintRowsAreReportedSingular) {
  const std::array<std::array<double, 3>, kMaxContacts> A{{{1.0, -0.3, -0.9}, {2.0, -0.6, -1.8}, {0, 0, 0}}};
  std::array<double, 3> a{};
  std::array<double, kMaxContacts> lambda{};
  EXPECT_FALSE(solve_constrained(WheelParams{}, 2, A, {1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, a, lambda));
}

}  // namespace
}  // namespace flexgait::rimless
