// choose_modes() on hand-built states (spec rimless.md, "Contact modes are chosen, not guessed",
// slip→stick / stick→slip, Painlevé jams, the tie rule). Every state is built so that the answer
// follows from a closed form written out next to it; the test also checks that closed form
// against the library (contact_dynamics), so the hand derivation itself is under test.
//
// Tolerances. Forces here are O(1..100) N and come out of a 3x3 solve of well-conditioned
// systems, so round-off is ~1e-15 relative; the invariants are checked to kForceTol = 1e-12·m g
// (four orders above round-off, four below choose_modes' own 1e-8·m g, so a decision that only
// passes thanks to choose_modes' tolerance fails here). Velocities: kVelocityTol = 1e-12·sqrt(g L0).
// Closed forms against the library: 1e-12 relative.
#include "flexgait/rimless/mode_selection.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "flexgait/rimless/dynamics.hpp"
#include "flexgait/rimless/energy.hpp"

namespace flexgait::rimless {
namespace {

using S = StateIndex;

// How ModeDecision reports a failure: a reason (outcome.hpp) and its detail.
bool ok(const ModeDecision& d) {
  return !d.failure.has_value();
}
std::string failure_text(const ModeDecision& d) {
  return ok(d) ? std::string() : std::string(name_of(*d.failure)) + ": " + d.detail;
}

double force_tol(const WheelParams& w) {
  return 1e-12 * w.m * w.g;
}  // [N]
double velocity_tol(const WheelParams& w) {
  return 1e-12 * std::sqrt(w.g * w.L0);
}  // [m/s]

std::vector<double> rest_state(const WheelParams& w) {
  return std::vector<double>(state_size(w), 0.0);
}

ContactSet contacts_of(const WheelParams& w, std::span<const double> y,
                       std::initializer_list<std::pair<int, FootMode>> feet) {
  ContactSet c;
  for (const auto& [leg, mode] : feet) {
    c.leg[c.count] = leg;
    c.mode[c.count] = mode;
    c.anchor[c.count] = leg_kinematics(w, leg, y).c;  // a sticking foot sits on its anchor
    ++c.count;
  }
  return c;
}

ModeDecision decide(const WheelParams& w, const ContactSet& current, std::vector<GuardEvent> events,
                    std::vector<double>& y) {
  return choose_modes(w, current, events, y);
}

FootMode mode_of_leg(const ModeDecision& d, int leg) {
  return d.contacts.mode[d.contacts.find(leg)];
}

// The spec's consistency conditions for the decided modes at the state after the event, with the
// library's own forces (dynamics.hpp): N >= 0 on every foot kept; stick: ċ = 0 and |T| <= μ_s N;
// slip s: T = -μ_k s N (the code's T = -μ_k s f / D with N = f / D) and friction opposing the
// motion (s ċ >= 0); every foot that left: its leg no longer pushes (f <= 0).
void expect_invariants(const WheelParams& w, const ContactSet& before, const ModeDecision& d,
                       std::span<const double> y) {
  const Dynamics dyn = contact_dynamics(w, d.contacts, y);
  ASSERT_FALSE(dyn.failure.has_value()) << name_of(*dyn.failure);
  for (int i = 0; i < d.contacts.count; ++i) {
    const ContactForce& cf = dyn.force[i];
    const LegKinematics& g = dyn.leg[i];
    const int s = slip_sign(d.contacts.mode[i]);
    SCOPED_TRACE("leg " + std::to_string(d.contacts.leg[i]) + " " + mode_name(d.contacts.mode[i]));
    EXPECT_GE(cf.N, -force_tol(w));
    if (s == 0) {
      EXPECT_NEAR(g.cdot, 0.0, velocity_tol(w));
      EXPECT_LE(std::abs(cf.T), w.mu_s * cf.N + force_tol(w));
    } else {
      EXPECT_NEAR(cf.T, -w.mu_k * s * cf.N, force_tol(w));
      EXPECT_GE(s * g.cdot, -velocity_tol(w));
    }
  }
  for (int i = 0; i < before.count; ++i) {
    if (d.contacts.find(before.leg[i]) < 0) {
      EXPECT_LE(leg_kinematics(w, before.leg[i], y).f, force_tol(w));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// (a) Double support where keeping both feet stuck demands N < 0 at one of them.
//
// Flat ground (φ = 0), ten legs, leg 0 leading at β = -α and leg 1 trailing at β = +α, hub at
// height y (both legs L = y / cos α, same compression δ). The wheel rolls forward with ẏ = 0 and
// ẋ = y sec²α θ̇, so both feet have ċ = 0 (contact.hpp: ċ = ẋ - ẏ tan β - y θ̇ sec²β). The leading
// leg compresses and the trailing one extends at the rate v = y tan α θ̇ / cos α, so
// f_lead = Kδ + Cv and f_trail = Kδ - Cv; θ̇ is set so that f_trail takes a chosen value.
// Both feet stuck (A_k q̈ = -Ȧ_k q̇ = ∓2 y tan α sec²α θ̇²), with r = y sec²α:
//   ÿ = -2 r θ̇²,  ẍ = r θ̈,  θ̈ = -L tan α (f_lead - f_trail) / (I + m r²),
//   T_lead + T_trail = m r θ̈,  T_lead - T_trail = (m (g - 2 r θ̇²) - (f_lead + f_trail)/cos α) / tan α,
//   N_trail = (f_trail - T_trail sin α) / cos α,
// which for the numbers below is about -6.7 N: the trailing foot cannot stay stuck. The leading
// foot had been slipping forward and its ċ just reached 0 (SlipToStick).
//   f_trail = +1 N: the foot is pressed, so it cannot leave; it must slip. With the leading foot
//     stuck, c̈_trail grows with T_trail and vanishes at the stick multiplier T* > 0 (above); slip
//     backward has T = +μ_k f/D < T*, so c̈ < 0 agrees with s = -1, while slip forward (T < 0)
//     would also give c̈ < 0 against s = +1. Expected: leading stick, trailing slip backward.
//   f_trail = -1 N: the leg pulls, so slipping would give N = f/D < 0 too; the foot leaves, and
//     the leading foot sticks alone (|T|/N ≈ 0.3 < μ_s = 0.6).
// A greedy choice (keep both stuck) fails the N >= 0 invariant; letting a pressed foot leave, or
// slipping the wrong way, fails the expected modes.
struct DoubleSupportCase {
  const char* name;
  double f_trail;  // [N]
  bool trail_leaves;
  FootMode trail_mode;  // when it stays
};

void PrintTo(const DoubleSupportCase& c, std::ostream* os) {
  *os << c.name;
}

class DoubleSupportNeedsNegativeN : public ::testing::TestWithParam<DoubleSupportCase> {};

TEST_P(DoubleSupportNeedsNegativeN, AnotherCombinationIsChosen) {
  const DoubleSupportCase& c = GetParam();
  WheelParams w;  // m = 1, I = 0.3, N = 10, L0 = 1, K = 1000, C = 30, μ = 0.6
  w.slope = 0.0;
  const double a = w.alpha(), ca = std::cos(a), ta = std::tan(a);
  const double h = 0.94, L = h / ca, delta = w.L0 - L, r = h / (ca * ca);
  const double v_per_thetad = h * ta / ca;
  const double thetad = (w.K * delta - c.f_trail) / (w.C * v_per_thetad);
  std::vector<double> y = rest_state(w);
  y[S::y] = h;
  y[S::theta] = -a;  // leg 0 at -α, leg 1 at +α
  y[S::thetad] = thetad;
  y[S::xd] = r * thetad;
  const LegKinematics lead = leg_kinematics(w, 0, y), trail = leg_kinematics(w, 1, y);
  ASSERT_NEAR(lead.cdot, 0.0, velocity_tol(w));
  ASSERT_NEAR(trail.cdot, 0.0, velocity_tol(w));
  ASSERT_NEAR(trail.f, c.f_trail, 1e-12 * w.m * w.g);

  // The premise, by hand and by the library: both stuck would need N_trail < 0.
  const double thetadd = -L * ta * (lead.f - trail.f) / (w.I + w.m * r * r);
  const double sum = w.m * r * thetadd;
  const double diff = (w.m * (w.g - 2 * r * thetad * thetad) - (lead.f + trail.f) / ca) / ta;
  const double N_trail_by_hand = (trail.f - 0.5 * (sum - diff) * std::sin(a)) / ca;
  const ContactSet both_stuck = contacts_of(w, y, {{1, FootMode::Stick}, {0, FootMode::Stick}});
  const Dynamics greedy = contact_dynamics(w, both_stuck, y);
  ASSERT_FALSE(greedy.failure.has_value());
  EXPECT_NEAR(greedy.force[0].N, N_trail_by_hand, 1e-12 * std::abs(N_trail_by_hand));
  ASSERT_LT(greedy.force[0].N, -1.0) << "the case must exercise a negative normal force";

  const ContactSet current = contacts_of(w, y, {{1, FootMode::Stick}, {0, FootMode::SlipForward}});
  const ModeDecision d = decide(w, current, {{0, EventKind::SlipToStick}}, y);
  ASSERT_TRUE(ok(d)) << failure_text(d);
  EXPECT_EQ(d.consistent, 1);
  EXPECT_EQ(d.jammed_feet, 0);
  ASSERT_GE(d.contacts.find(0), 0);
  EXPECT_EQ(mode_of_leg(d, 0), FootMode::Stick);
  if (c.trail_leaves) {
    EXPECT_EQ(d.contacts.count, 1);
    EXPECT_LT(d.contacts.find(1), 0);
    // A foot that leaves keeps its compression as a free leg (mode_selection.hpp).
    EXPECT_DOUBLE_EQ(y[S::free_delta + 1], trail.delta);
  } else {
    ASSERT_EQ(d.contacts.count, 2);
    ASSERT_GE(d.contacts.find(1), 0);
    EXPECT_EQ(mode_of_leg(d, 1), c.trail_mode);
  }
  expect_invariants(w, current, d, y);
}

INSTANTIATE_TEST_SUITE_P(
    Table, DoubleSupportNeedsNegativeN,
    ::testing::Values(DoubleSupportCase{"pressed_trailing_foot_slips_back", 1.0, false, FootMode::SlipBackward},
                      DoubleSupportCase{"pulling_trailing_foot_leaves", -1.0, true, FootMode::Stick}),
    [](const auto& info) { return std::string(info.param.name); });

// ---------------------------------------------------------------------------------------------
// (b) Slip reversal and (d) the stick→slip direction, in single support on a vertical-to-slope
// leg (β = 0, leg 0, θ = 0), the foot at ċ = ẋ - y θ̇ = 0. With β = 0: ∂L/∂q = (0, 1, 0),
// A = (1, 0, -y), Ȧq̇ = -2 ẏ θ̇, N = f = K δ - C ẏ, and the stick multiplier solves
//   ẍ = g sin φ + T/m,  θ̈ = -y T / I,  ẍ - y θ̈ = 2 ẏ θ̇   ⇒   T* = (2 ẏ θ̇ - g sin φ) / (1/m + y²/I).
// With the foot stuck on a slope (φ = 0.1, at rest) T* < 0: the ground holds the foot back, it
// tends downhill. On flat ground rolling with ẏ θ̇ > 0, T* > 0. μ_s = μ_k = factor·|T*|/N:
//   factor < 1: the cone cannot hold the foot. It slips with s = -sign T* (spec: "slips with
//     s = -sign(T_stick)"), and the slip friction T = -μ_k s N keeps the sign of T*. A foot that was
//     slipping the other way (SlipToStick at ċ = 0) reverses; one that was stuck (StickToSlip)
//     starts slipping the same way.
//   factor > 1 after SlipToStick: the foot sticks.
// Slip in the other direction gives c̈ = (T - T*)(1/m + y²/I) of the wrong sign, so a broken
// direction rule is caught by the expected mode and by the slip invariant s ċ >= 0 one step later
// (here by the consistency test s c̈ >= 0 that choose_modes applies).
struct SingleSupportCase {
  const char* name;
  double slope;       // φ [rad]
  double yd, thetad;  // ẏ [m/s], θ̇ [rad/s]; ẋ = y θ̇ so that ċ = 0
  FootMode previous;
  EventKind event;
  double mu_factor;  // μ = factor · |T*| / N
  FootMode expected;
};

void PrintTo(const SingleSupportCase& c, std::ostream* os) {
  *os << c.name;
}

class SingleSupportEvent : public ::testing::TestWithParam<SingleSupportCase> {};

TEST_P(SingleSupportEvent, ModeFollowsTheStickMultiplier) {
  const SingleSupportCase& c = GetParam();
  WheelParams w;
  w.slope = c.slope;
  const double h = 0.99;  // δ = 0.01 m, K δ = 10 N
  std::vector<double> y = rest_state(w);
  y[S::y] = h;
  y[S::yd] = c.yd;
  y[S::thetad] = c.thetad;
  y[S::xd] = h * c.thetad;
  const double T_star = (2 * c.yd * c.thetad - w.g * std::sin(w.slope)) / (1 / w.m + h * h / w.I);
  const double N = w.K * (w.L0 - h) - w.C * c.yd;
  w.mu_s = w.mu_k = c.mu_factor * std::abs(T_star) / N;

  // The closed form against the library's stick multiplier.
  const Dynamics stuck = contact_dynamics(w, contacts_of(w, y, {{0, FootMode::Stick}}), y);
  ASSERT_FALSE(stuck.failure.has_value());
  EXPECT_NEAR(stuck.force[0].T, T_star, 1e-12 * std::abs(T_star));
  EXPECT_NEAR(stuck.force[0].N, N, 1e-12 * N);

  const ContactSet current = contacts_of(w, y, {{0, c.previous}});
  const ModeDecision d = decide(w, current, {{0, c.event}}, y);
  ASSERT_TRUE(ok(d)) << failure_text(d);
  ASSERT_EQ(d.contacts.count, 1);
  EXPECT_EQ(d.contacts.mode[0], c.expected) << mode_name(d.contacts.mode[0]);
  EXPECT_EQ(d.consistent, 1);
  const int s = slip_sign(d.contacts.mode[0]);
  if (s != 0) {
    EXPECT_EQ(s, T_star > 0 ? -1 : 1) << "s = -sign T_stick";
    const Dynamics slipping = contact_dynamics(w, d.contacts, y);
    EXPECT_GT(slipping.force[0].T * T_star, 0.0) << "friction keeps the direction of the stick force";
  }
  expect_invariants(w, current, d, y);
}

INSTANTIATE_TEST_SUITE_P(Table, SingleSupportEvent,
                         ::testing::Values(
                             // (b) slip reversal: the foot was slipping, ċ reached 0, the cone cannot hold it.
                             SingleSupportCase{"uphill_slip_reverses_downhill", 0.1, 0.0, 0.0, FootMode::SlipBackward,
                                               EventKind::SlipToStick, 0.9, FootMode::SlipForward},
                             SingleSupportCase{"uphill_slip_stops_in_the_cone", 0.1, 0.0, 0.0, FootMode::SlipBackward,
                                               EventKind::SlipToStick, 1.1, FootMode::Stick},
                             SingleSupportCase{"forward_slip_reverses_backward", 0.0, 0.1, 1.0, FootMode::SlipForward,
                                               EventKind::SlipToStick, 0.9, FootMode::SlipBackward},
                             SingleSupportCase{"forward_slip_stops_in_the_cone", 0.0, 0.1, 1.0, FootMode::SlipForward,
                                               EventKind::SlipToStick, 1.1, FootMode::Stick},
                             // (d) stick→slip: the foot slips against the friction force it had, s = -sign T.
                             SingleSupportCase{"stuck_on_slope_slips_downhill", 0.1, 0.0, 0.0, FootMode::Stick,
                                               EventKind::StickToSlip, 0.9, FootMode::SlipForward},
                             SingleSupportCase{"stuck_rolling_slips_backward", 0.0, 0.1, 1.0, FootMode::Stick,
                                               EventKind::StickToSlip, 0.9, FootMode::SlipBackward}),
                         [](const auto& info) { return std::string(info.param.name); });

// ---------------------------------------------------------------------------------------------
// (c) Painlevé jam. Single support, leg 0 at β = 0.4 rad (θ = 0.4), δ = 0.01 m, hub moving
// forward (ẋ = 0.2 m/s, ẏ = θ̇ = 0): ċ = ẋ = 0.2 m/s, the foot slips forward (s = +1), f = K δ.
// The slip denominator D = cos β - μ_k sin β is <= 0 once μ_k >= cot β = 2.365.
// The jam impulse P along ∂c/∂q = A = (1, -tan β, -y sec²β) stops the foot (A Δq̇ = -ċ):
//   P = -ċ / (A M⁻¹ Aᵀ),  A M⁻¹ Aᵀ = (1 + tan²β)/m + y² sec⁴β / I,
//   kinetic-energy loss = ċ² / (2 A M⁻¹ Aᵀ)  (a plastic impulse along one constraint),
// a ground impulse (P, -P tan β): perpendicular to the leg, in the friction cone exactly when
// μ_s tan β >= 1, i.e. when D <= 0 (μ_s = μ_k). With μ = 2.5 (D = -0.05) it is admissible; with
// μ = 2.0 (D = +0.14) a SlipJam event cannot be honoured: the impulse is outside the cone.
struct JamState {
  WheelParams w;
  std::vector<double> y;
};

JamState jam_state(double mu) {
  JamState j;
  j.w.mu_s = j.w.mu_k = mu;
  const double beta = 0.4;
  j.y = rest_state(j.w);
  j.y[S::theta] = beta;
  j.y[S::y] = (j.w.L0 - 0.01) * std::cos(beta);
  j.y[S::xd] = 0.2;
  return j;
}

TEST(PainleveJam, InsideTheConeTheFootIsStoppedAndTheLossBooked) {
  for (const bool with_event : {true, false}) {  // the event, or a moving foot found with D <= 0
    SCOPED_TRACE(with_event ? "SlipJam event" : "no event");
    JamState j = jam_state(2.5);
    const WheelParams& w = j.w;
    const LegKinematics g = leg_kinematics(w, 0, j.y);
    ASSERT_NEAR(g.cdot, 0.2, 1e-15);
    ASSERT_LT(slip_denominator(w, g, +1), 0.0);
    const double AMA = (1 + g.tb * g.tb) / w.m + std::pow(j.y[S::y] / (g.cb * g.cb), 2) / w.I;
    const double loss_by_hand = g.cdot * g.cdot / (2 * AMA);
    const double P = -g.cdot / AMA;
    const std::vector<double> before = j.y;
    const ContactSet current = contacts_of(w, j.y, {{0, FootMode::SlipForward}});
    std::vector<GuardEvent> events;
    if (with_event) events.push_back({0, EventKind::SlipJam});
    const ModeDecision d = decide(w, current, events, j.y);
    ASSERT_TRUE(ok(d)) << failure_text(d);
    EXPECT_EQ(d.jammed_feet, 1);
    EXPECT_EQ(d.impulse_legs, std::vector<int>{0});
    // Booked: the loss by hand, the kinetic-energy drop, and W_fric's increase agree.
    EXPECT_GT(d.impulse_energy, 0.0);
    EXPECT_NEAR(d.impulse_energy, loss_by_hand, 1e-12 * loss_by_hand);
    EXPECT_NEAR(d.impulse_energy, kinetic_energy(w, before) - kinetic_energy(w, j.y), 1e-12 * loss_by_hand);
    EXPECT_NEAR(j.y[S::w_fric] - before[S::w_fric], d.impulse_energy, 1e-15);
    // The foot is stopped, by an impulse M Δq̇ = Aᵀ P (no axial part through the massless leg).
    EXPECT_NEAR(leg_kinematics(w, 0, j.y).cdot, 0.0, velocity_tol(w));
    EXPECT_NEAR(w.m * (j.y[S::xd] - before[S::xd]), P, 1e-12 * std::abs(P));
    EXPECT_NEAR(w.m * (j.y[S::yd] - before[S::yd]), -g.tb * P, 1e-12 * std::abs(P));
    EXPECT_NEAR(w.I * (j.y[S::thetad] - before[S::thetad]), -j.y[S::y] / (g.cb * g.cb) * P, 1e-12 * std::abs(P));
    const double normal_impulse = -P * g.tb;
    EXPECT_GT(normal_impulse, 0.0);
    EXPECT_LE(std::abs(P), w.mu_s * normal_impulse);
    // It cannot slip on in the jammed direction (D < 0 there).
    ASSERT_EQ(d.contacts.count, 1);
    EXPECT_NE(d.contacts.mode[0], FootMode::SlipForward);
    expect_invariants(w, current, d, j.y);
  }
}

// Outside the cone (SlipJam fired, but μ_s tan β < 1): choose_modes reports the failure by name
// and leaves y as it was (no impulse, no friction work). A moving foot with D > 0 and no event
// is no jam: it keeps slipping, nothing is booked.
TEST(PainleveJam, OutsideTheConeIsReportedAndTheStateKept) {
  JamState j = jam_state(2.0);
  const WheelParams& w = j.w;
  ASSERT_GT(slip_denominator(w, leg_kinematics(w, 0, j.y), +1), 0.1);
  const std::vector<double> before = j.y;
  const ContactSet current = contacts_of(w, j.y, {{0, FootMode::SlipForward}});
  const ModeDecision d = decide(w, current, {{0, EventKind::SlipJam}}, j.y);
  ASSERT_FALSE(ok(d));
  EXPECT_EQ(d.failure, FailureReason::JamWithoutImpulse) << failure_text(d);
  EXPECT_EQ(j.y, before);
  EXPECT_EQ(d.impulse_energy, 0.0);

  const ModeDecision no_event = decide(w, current, {}, j.y);
  ASSERT_TRUE(ok(no_event)) << failure_text(no_event);
  EXPECT_EQ(no_event.jammed_feet, 0);
  EXPECT_EQ(no_event.impulse_energy, 0.0);
  ASSERT_EQ(no_event.contacts.count, 1);
  EXPECT_EQ(no_event.contacts.mode[0], FootMode::SlipForward);
  EXPECT_EQ(j.y, before);
  expect_invariants(w, current, no_event, j.y);
}

// ---------------------------------------------------------------------------------------------
// (e) The tie rule. Flat ground, at rest, leg 0 vertical (β = 0) carrying the weight: K δ = m g
// with δ = L0 (1 - cos 2α), i.e. K = m g / (L0 (1 - cos 2α)); the hub at y = L0 cos 2α, so legs 1
// and 9 (β = ±2α) touch the ground exactly at rest length (f = 0). The body is in equilibrium on
// leg 0 alone: every sticking foot has T = 0 and q̈ = 0, so any foot with f = 0 may stick (T = 0
// <= μ_s·0), slip either way (zero force, c̈ = 0) or, if it was on the ground, leave (f <= 0).
// Leg 0 can only stick (slip would be braked by friction against its own direction; leaving
// needs f <= 0). With μ = 0.6 < cot 2α a foot at ±2α cannot take a tangential force, so no
// other combination appears. Leg 9 touches down with f = 0, so it may also leave at once:
//   {0}       + 9 lands: 1 x 4 consistent combinations;  leg 1 on the ground too: 1 x 4 x 4.
// The rule: keep each foot's previous mode (leg 1's), then stick over slip over leave. A rule
// that ignores previous modes, prefers slip or leave, or counts wrongly fails a row.
struct TieCase {
  const char* name;
  bool leg1_on_ground;
  FootMode leg1_previous;
  int consistent;
};

void PrintTo(const TieCase& c, std::ostream* os) {
  *os << c.name;
}

class TieRule : public ::testing::TestWithParam<TieCase> {};

TEST_P(TieRule, KeepsPreviousModesThenPrefersStick) {
  const TieCase& c = GetParam();
  WheelParams w;
  w.slope = 0.0;
  const double c2a = std::cos(2 * w.alpha());
  w.K = w.m * w.g / (w.L0 * (1 - c2a));
  std::vector<double> y = rest_state(w);
  y[S::y] = w.L0 * c2a;
  ASSERT_NEAR(leg_kinematics(w, 0, y).f, w.m * w.g, force_tol(w));
  ASSERT_NEAR(leg_kinematics(w, 1, y).f, 0.0, force_tol(w));
  ASSERT_NEAR(foot_height(w, 9, y), 0.0, 1e-15);

  const ContactSet current = c.leg1_on_ground ? contacts_of(w, y, {{0, FootMode::Stick}, {1, c.leg1_previous}})
                                              : contacts_of(w, y, {{0, FootMode::Stick}});
  const ModeDecision d = decide(w, current, {{9, EventKind::Touchdown}}, y);
  ASSERT_TRUE(ok(d)) << failure_text(d);
  EXPECT_EQ(d.consistent, c.consistent);
  EXPECT_GT(d.consistent, 1);
  ASSERT_EQ(d.contacts.count, current.count + 1);
  EXPECT_EQ(mode_of_leg(d, 0), FootMode::Stick);
  EXPECT_EQ(mode_of_leg(d, 9), FootMode::Stick);
  if (c.leg1_on_ground) {
    ASSERT_GE(d.contacts.find(1), 0) << "stick or slip over leave";
    EXPECT_EQ(mode_of_leg(d, 1), c.leg1_previous) << "previous mode kept";
  }
  expect_invariants(w, current, d, y);
}

INSTANTIATE_TEST_SUITE_P(Table, TieRule,
                         ::testing::Values(TieCase{"landing_foot_sticks_rather_than_slips", false, FootMode::Stick, 4},
                                           TieCase{"stuck_foot_stays_stuck_rather_than_leave", true, FootMode::Stick,
                                                   16},
                                           TieCase{"backward_slip_is_kept", true, FootMode::SlipBackward, 16},
                                           TieCase{"forward_slip_is_kept", true, FootMode::SlipForward, 16}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace flexgait::rimless
