// The flexible wheel's flow and guards (rimless/flow.hpp) on hand-built states: the energy balance
// dE/dt = -(Ẇ_damp + Ẇ_fric) that the spec's ledger rests on holds for the flow's own dissipation
// rates in every mode, the free legs relax as K δ + C δ̇ = 0, and each guard slot holds the value
// the header's table names.
#include "flexgait/rimless/flow.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "flexgait/rimless/energy.hpp"
#include "test_support.hpp"
#include "wheel_states.hpp"

namespace flexgait::rimless {
namespace {

using testing::measured_wheel;
using testing::wheel_state;

struct Case {
  const char* name;
  testing::WheelState s;
};

std::vector<Case> cases(const WheelParams& w) {
  const double a = w.alpha();
  const double h1 = 0.99 * std::cos(0.1), h2 = 0.995 * std::cos(a);
  return {
      {"flight", wheel_state(w, 0.05, 1.2, 0.4, 0.3, -1.0, {})},
      {"stick", wheel_state(w, 0.1, h1, 0.3, -0.1, -0.8, {{0, FootMode::Stick}})},
      {"slip forward", wheel_state(w, 0.1, h1, 2.0, -0.1, -0.8, {{0, FootMode::SlipForward}})},
      {"slip backward", wheel_state(w, 0.1, h1, -1.0, -0.1, 0.8, {{0, FootMode::SlipBackward}})},
      {"two sticking", wheel_state(w, -a, h2, 0.3, -0.05, -0.5, {{0, FootMode::Stick}, {1, FootMode::Stick}})},
      {"stick and slip", wheel_state(w, -a, h2, 0.3, -0.05, -0.5, {{0, FootMode::Stick}, {1, FootMode::SlipForward}})},
  };
}

// dE/dt along the flow, by a central difference of E along ẏ, against -(Ẇ_damp + Ẇ_fric) of the
// flow itself: exact for every state of the mode, not only on solutions (spec rimless.md, "Energy").
TEST(Flow, EnergyBalanceHoldsInEveryModeAndFrictionLaw) {
  for (Friction law : {Friction::Coulomb, Friction::Stribeck}) {
    WheelParams w = measured_wheel(0.6);
    w.friction = law;
    w.mu_k = 0.4;  // Stribeck: μ(ċ) between μ_k and μ_s
    for (const Case& k : cases(w)) {
      SCOPED_TRACE(std::string(k.name) + ", " + std::string(name_of(law)));
      std::vector<double> yd(k.s.y.size());
      ASSERT_TRUE(flow_derivative(w, k.s.contacts, k.s.y, yd));
      const double h = 1e-6;
      auto energy_at = [&](double sign) {
        std::vector<double> y = k.s.y;
        for (std::size_t i = 0; i < y.size(); ++i) y[i] += sign * h * yd[i];
        return mechanical_energy(w, k.s.contacts, y).total();
      };
      const double dEdt = (energy_at(+1) - energy_at(-1)) / (2 * h);
      const double dissipated = yd[StateIndex::w_damp] + yd[StateIndex::w_fric];
      EXPECT_GE(yd[StateIndex::w_damp], 0.0);
      // Central difference, h = 1e-6 s: truncation h²·E''' ≲ 1e-9 W, rounding ε·|E|/h ≈ 1e-9 W;
      // the powers are O(1..10) W. Bound 1e-6 W.
      EXPECT_NEAR(dEdt, -dissipated, 1e-6);
      if (k.s.contacts.count > 0 && k.s.contacts.mode[k.s.contacts.count - 1] != FootMode::Stick) {
        EXPECT_GT(yd[StateIndex::w_fric], 0.0);  // a slipping foot dissipates
      }
    }
  }
}

TEST(Flow, KinematicRowsAndFreeLegsRelaxing) {
  const WheelParams w = measured_wheel(0.6);
  const Case k = cases(w)[1];  // one sticking foot on leg 0
  std::vector<double> yd(k.s.y.size());
  Dynamics d;
  ASSERT_TRUE(flow_derivative(w, k.s.contacts, k.s.y, yd, d));
  EXPECT_EQ(yd[StateIndex::x], k.s.y[StateIndex::xd]);
  EXPECT_EQ(yd[StateIndex::y], k.s.y[StateIndex::yd]);
  EXPECT_EQ(yd[StateIndex::theta], k.s.y[StateIndex::thetad]);
  EXPECT_EQ(yd[StateIndex::xd], d.qdd[0]);
  EXPECT_EQ(yd[StateIndex::thetad], d.qdd[2]);
  EXPECT_EQ(yd[StateIndex::free_delta], 0.0);  // leg 0 is on the ground: its slot stays
  for (int j = 1; j < w.legs; ++j) {
    const auto i = static_cast<std::size_t>(StateIndex::free_delta + j);
    EXPECT_NEAR(yd[i], -w.K / w.C * k.s.y[i], 1e-15) << j;
  }
}

TEST(Flow, GuardSlotsHoldTheValuesOfTheirTable) {
  WheelParams w = measured_wheel(0.6);
  w.mu_k = 0.5;
  const auto all = cases(w);
  for (const Case* k : {&all[1], &all[2], &all[5]}) {
    SCOPED_TRACE(k->name);
    const Dynamics d = contact_dynamics(w, k->s.contacts, k->s.y);
    std::vector<double> g(static_cast<std::size_t>(guard_count(w)));
    guard_values(w, k->s.contacts, k->s.y, g);
    for (int leg = 0; leg < w.legs; ++leg) {
      const double* slot = &g[static_cast<std::size_t>(kGuardsPerLeg * leg)];
      const int i = k->s.contacts.find(leg);
      if (i < 0) {
        // Angle addition against cos(θ + 2αk): within a few ulp of the leg length.
        EXPECT_NEAR(slot[0], foot_height(w, leg, k->s.y), 1e-15) << leg;
        for (int j = 1; j < kGuardsPerLeg; ++j) EXPECT_EQ(slot[j], 1.0) << leg;
        continue;
      }
      EXPECT_EQ(slot[0], d.force[i].N);
      EXPECT_EQ(slot[2], d.leg[i].cb);
      const int s = slip_sign(k->s.contacts.mode[i]);
      if (s == 0) {
        EXPECT_EQ(slot[1], w.mu_s - std::abs(d.force[i].T) / d.force[i].N);
        EXPECT_EQ(slot[3], 1.0);
      } else {
        EXPECT_EQ(slot[1], s * d.leg[i].cdot);
        EXPECT_NEAR(slot[3], d.leg[i].cb - w.mu_k * s * d.leg[i].sb, 1e-15);
      }
    }
  }
}

TEST(Flow, GuardSlotsNameTheirEvents) {
  EXPECT_EQ(guard_event(0, false, FootMode::Stick), EventKind::Touchdown);
  EXPECT_EQ(guard_event(0, true, FootMode::Stick), EventKind::LiftOff);
  EXPECT_EQ(guard_event(1, true, FootMode::Stick), EventKind::StickToSlip);
  EXPECT_EQ(guard_event(1, true, FootMode::SlipBackward), EventKind::SlipToStick);
  EXPECT_EQ(guard_event(2, true, FootMode::SlipForward), EventKind::FallOver);
  EXPECT_EQ(guard_event(3, true, FootMode::SlipForward), EventKind::SlipJam);
}

TEST(Flow, AJammedModeHasNoDerivative) {
  const WheelParams w = measured_wheel(0.6);
  const auto s = wheel_state(w, -1.2, 0.98 * std::cos(1.2), 0.0, 0.0, 0.0, {{0, FootMode::SlipBackward}});
  std::vector<double> yd(s.y.size());
  EXPECT_FALSE(flow_derivative(w, s.contacts, s.y, yd));
}

}  // namespace
}  // namespace flexgait::rimless
