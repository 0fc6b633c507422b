#include "flexgait/rimless/flow.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "flexgait/numerics/ode_system.hpp"
#include "flexgait/rimless/dynamics.hpp"

namespace flexgait::rimless {

namespace {

// Free legs relax, K δ + C δ̇ = 0 (rate = K/C), into yd's free-leg slots; a leg on the ground keeps
// its slot (δ̇ = 0). Returns damp + every leg's C δ̇² added in k's order, the ground legs' exactly
// +0 (the sum of the free legs' alone), in one pass over the runs of free legs between the
// ground legs (no test per leg, and δ̇ kept in a register for the sum).
double relax_free_legs(const WheelParams& w, const ContactSet& contacts, double rate, std::span<const double> y,
                       std::span<double> yd, double damp) {
  using S = StateIndex;
  std::array<int, kMaxContacts> ground = contacts.leg;  // the first contacts.count, ascending
  for (int i = 1; i < contacts.count; ++i)
    for (int j = i; j > 0 && ground[static_cast<std::size_t>(j - 1)] > ground[static_cast<std::size_t>(j)]; --j)
      std::swap(ground[static_cast<std::size_t>(j - 1)], ground[static_cast<std::size_t>(j)]);
  int k = 0;
  const auto relax_until = [&](int end) {
    for (; k < end; ++k) {
      const double dk = -rate * y[static_cast<std::size_t>(S::free_delta + k)];
      yd[static_cast<std::size_t>(S::free_delta + k)] = dk;
      damp += w.C * dk * dk;  // C δ̇²
    }
  };
  for (int i = 0; i < contacts.count; ++i) {
    relax_until(ground[static_cast<std::size_t>(i)]);
    constexpr double dk = 0.0;  // on the ground
    yd[static_cast<std::size_t>(S::free_delta + k)] = dk;
    damp += w.C * dk * dk;
    ++k;
  }
  relax_until(w.legs);
  return damp;
}

}  // namespace

bool flow_derivative(const WheelParams& w, const ContactSet& contacts, std::span<const double> y,
                     std::span<double> yd) {
  Dynamics d;
  return flow_derivative(w, contacts, y, yd, d);
}

bool flow_derivative(const WheelParams& w, const ContactSet& contacts, std::span<const double> y, std::span<double> yd,
                     Dynamics& d) {
  using S = StateIndex;
  // The flow needs q̈ and T; N_k = (f_k - T_k sin β_k) / cos β_k (docs/theory/rimless.md,
  // "Equations of motion"), a division per foot, is left to the guards unless the mode fails.
  const bool complete = contact_accelerations(w, contacts, y, d);
  if (d.failure) {
    if (complete) normal_forces(contacts, d);
    return false;
  }
  yd[S::x] = y[S::xd];
  yd[S::y] = y[S::yd];
  yd[S::theta] = d.thetad;  // the state's θ̇ unless the torque balance fixes it (I = 0)
  yd[S::xd] = d.qdd[0];
  yd[S::yd] = d.qdd[1];
  yd[S::thetad] = d.qdd[2];
  double damp = 0, fric = 0;
  for (int i = 0; i < contacts.count; ++i) {
    damp += w.C * d.leg[i].delta_dot * d.leg[i].delta_dot;
    fric -= d.force[i].T * d.leg[i].cdot;  // power of the tangential force, >= 0 in slip
  }
  damp = relax_free_legs(w, contacts, d.constants.relax_rate, y, yd, damp);  // K/C remembered
  yd[S::w_damp] = damp;
  yd[S::w_fric] = fric;
  return true;
}

LegOffsets leg_offsets(const WheelParams& w) {
  LegOffsets o;
  o.cos.resize(static_cast<std::size_t>(w.legs));
  o.sin.resize(static_cast<std::size_t>(w.legs));
  for (int k = 0; k < w.legs; ++k) {
    const double offset = 2.0 * w.alpha() * k;
    o.cos[static_cast<std::size_t>(k)] = std::cos(offset);
    o.sin[static_cast<std::size_t>(k)] = std::sin(offset);
  }
  return o;
}

void guard_values(const WheelParams& w, const ContactSet& contacts, std::span<const double> y, std::span<double> g) {
  guard_values(w, contacts, contact_dynamics(w, contacts, y), y, g);
}

void guard_values(const WheelParams& w, const ContactSet& contacts, const Dynamics& d, std::span<const double> y,
                  std::span<double> g) {
  guard_values(w, leg_offsets(w), contacts, d, y, g);
}

void guard_values(const WheelParams& w, const LegOffsets& offsets, const ContactSet& contacts, const Dynamics& d,
                  std::span<const double> y, std::span<double> g) {
  std::fill(g.begin(), g.end(), 1.0);
  const double cos_theta = std::cos(y[StateIndex::theta]), sin_theta = std::sin(y[StateIndex::theta]);
  // Every leg's foot height first (no search of the contact set per leg), then the feet on the
  // ground write their own guards over theirs.
  for (int k = 0; k < w.legs; ++k)
    g[static_cast<std::size_t>(kGuardsPerLeg * k)] = free_foot_height(w, offsets, k, cos_theta, sin_theta, y);
  for (int i = 0; i < contacts.count; ++i) {
    double* slot = &g[static_cast<std::size_t>(kGuardsPerLeg * contacts.leg[i])];
    const ContactForce& cf = d.force[i];
    const LegKinematics& leg = d.leg[i];
    slot[0] = cf.N;
    slot[2] = leg.cb;
    const int s = slip_sign(contacts.mode[i]);
    if (s == 0) {
      slot[1] = cf.N > 0 ? w.mu_s - std::abs(cf.T) / cf.N : -1.0;
    } else {
      slot[1] = s * leg.cdot;
      slot[3] = slip_denominator(w, leg, s);
    }
  }
}

void guard_directions(const WheelParams& w, const ContactSet& contacts, std::span<int> directions) {
  for (int k = 0; k < w.legs; ++k) {
    int* slot = &directions[static_cast<std::size_t>(kGuardsPerLeg * k)];
    const int i = contacts.find(k);
    const int used = i < 0 ? 1 : slip_sign(contacts.mode[i]) == 0 ? 3 : 4;  // as guard_values writes them
    for (int j = 0; j < kGuardsPerLeg; ++j) slot[j] = j < used ? -1 : numerics::kNoGuard;
  }
}

EventKind guard_event(int slot, bool on_ground, FootMode mode) {
  switch (slot) {
    case 0:
      return on_ground ? EventKind::LiftOff : EventKind::Touchdown;
    case 1:
      return mode == FootMode::Stick ? EventKind::StickToSlip : EventKind::SlipToStick;
    case 2:
      return EventKind::FallOver;
    default:
      return EventKind::SlipJam;
  }
}

}  // namespace flexgait::rimless
