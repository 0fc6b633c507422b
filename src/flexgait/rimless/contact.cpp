#include "flexgait/rimless/contact.hpp"

#include <cmath>

namespace flexgait::rimless {

const char* mode_name(FootMode m) {
  switch (m) {
    case FootMode::Stick:
      return "stick";
    case FootMode::SlipForward:
      return "slip+";
    case FootMode::SlipBackward:
      return "slip-";
  }
  return "?";
}

double leg_angle(const WheelParams& w, int k, double theta) {
  // remainder(x, P) = x - n P with n the integer nearest x / P, exact in floating point (libm's
  // remainder is a slow path of the right-hand side). The candidate n, x·(1/P) rounded to an
  // integer (adding and removing 1.5·2^52), gives r = x - n P exactly by one fused
  // multiply-add (the exact r is representable); where |r| < P/2 that r is the remainder (the
  // only representative below P/2), else (a quotient near a half-integer, or huge, or r = 0) libm decides.
  constexpr double P = 2.0 * std::numbers::pi;
  constexpr double kRound = 0x1.8p52;
  const double x = theta + 2.0 * w.alpha() * k;
  constexpr double kInvP = 1.0 / P;
  const double n = (x * kInvP + kRound) - kRound;
  const double r = std::fma(-n, P, x);
  // (r = 0: libm gives it x's sign, the multiply-add +0.)
  return std::abs(r) < 0.5 * P && r != 0.0 ? r : std::remainder(x, P);
}

LegKinematics leg_kinematics(const WheelParams& w, int k, std::span<const double> s) {
  LegKinematics g;
  leg_kinematics(w, k, s, g);
  return g;
}

void leg_kinematics(const WheelParams& w, int k, std::span<const double> s, LegKinematics& g) {
  using S = StateIndex;
  const double y = s[S::y], yd = s[S::yd], td = s[S::thetad];
  g.beta = leg_angle(w, k, s[S::theta]);
  g.cb = std::cos(g.beta);
  g.sb = std::sin(g.beta);
  // One division (the right-hand side's hot path; products of 1/cos β are within an ulp or two
  // of the quotients).
  const double sec = 1.0 / g.cb;
  g.tb = g.sb * sec;
  const double sec2 = sec * sec;
  g.L = y * sec;
  const double Ldot = (yd + y * g.tb * td) * sec;
  g.delta = w.L0 - g.L;
  g.delta_dot = -Ldot;
  g.f = w.K * g.delta + w.C * g.delta_dot;
  g.gradL = {0.0, sec, g.L * g.tb};
  g.A = {1.0, -g.tb, -y * sec2};
  g.c = s[S::x] - y * g.tb;
  g.cdot = s[S::xd] - yd * g.tb - y * td * sec2;
  g.Adot_qdot = -2.0 * yd * td * sec2 - 2.0 * y * g.tb * td * td * sec2;
}

SlipLaw slip_law(const WheelParams& w, int s, double cdot) {
  if (w.friction == Friction::Coulomb) return {w.mu_k};
  const double decay = std::exp(-std::pow(std::abs(cdot) / w.stribeck_velocity, w.stribeck_exponent));
  return {w.mu_k + (w.mu_s - w.mu_k) * decay + w.viscous * s * cdot};
}

double foot_height(const WheelParams& w, int k, std::span<const double> s) {
  // cos is 2π-periodic: no need to wrap the angle (a hot path: every free leg, every step).
  const double cb = std::cos(s[StateIndex::theta] + 2.0 * w.alpha() * k);
  return s[StateIndex::y] - (w.L0 - s[StateIndex::free_delta + k]) * cb;
}

}  // namespace flexgait::rimless
