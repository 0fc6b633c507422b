#pragma once
/// \file contact.hpp
/// State layout, foot modes and the kinematics of one leg (docs/theory/rimless.md, "Equations of motion").
///
/// Slope frame: x down the slope, y along the slope normal. Leg k makes the angle
/// β_k = θ + 2αk with the slope normal; the hub sits at foot + L_k (sin β_k, cos β_k).
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>

#include "flexgait/rimless/parameters.hpp"

namespace flexgait::rimless {

/// Layout of the flexible wheel's state vector y (dim kStateBase + N).
struct StateIndex {
  static constexpr int x = 0;           ///< hub position down the slope [m]
  static constexpr int y = 1;           ///< hub height above the slope [m]
  static constexpr int theta = 2;       ///< wheel angle [rad]
  static constexpr int xd = 3;          ///< [m/s]
  static constexpr int yd = 4;          ///< [m/s]
  static constexpr int thetad = 5;      ///< [rad/s]
  static constexpr int w_damp = 6;      ///< work dissipated by the leg dampers since t = 0 [J]
  static constexpr int w_fric = 7;      ///< work dissipated by friction (and jam impulses) [J]
  static constexpr int free_delta = 8;  ///< + k: compression of free leg k, relaxing as Kδ + Cδ̇ = 0 [m]
};
inline constexpr int kStateBase = 8;
inline int state_size(const WheelParams& w) {
  return kStateBase + w.legs;
}

/// The contact mode of a foot on the ground. Slip directions are signs of ċ (foot velocity
/// along the slope): forward = +x (down the slope).
enum class FootMode : std::uint8_t { Stick, SlipForward, SlipBackward };
inline int slip_sign(FootMode m) {
  return m == FootMode::SlipForward ? 1 : m == FootMode::SlipBackward ? -1 : 0;
}
const char* mode_name(FootMode m);

/// At most this many feet on the ground at once (two in the paper; three for many soft legs).
inline constexpr int kMaxContacts = 3;

/// The feet on the ground, oldest first, and their modes.
struct ContactSet {
  int count = 0;
  std::array<int, kMaxContacts> leg{};  ///< leg index k in [0, N)
  std::array<FootMode, kMaxContacts> mode{};
  std::array<double, kMaxContacts> anchor{};  ///< c_k where the foot started sticking [m]

  int find(int k) const {
    for (int i = 0; i < count; ++i)
      if (leg[i] == k) return i;
    return -1;
  }
};

/// x / 2π rounded to the nearest integer, by adding and removing 1.5·2^52 (wrap_angle's n).
inline double turns(double x) {
  constexpr double kRound = 0x1.8p52;
  constexpr double kInvP = 1.0 / (2.0 * std::numbers::pi);
  return (x * kInvP + kRound) - kRound;
}
/// x wrapped to (-π, π] [rad] (inline: the first step of every right-hand side).
inline double wrap_angle(double x) {
  // remainder(x, P) = x - n P with n the integer nearest x / P, exact in floating point (libm's
  // remainder is a slow path of the right-hand side). The candidate n, turns(x), gives
  // r = x - n P exactly by one fused multiply-add (the exact r is representable); where
  // |r| < P/2 that r is the remainder (the only representative below P/2), else (a quotient
  // near a half-integer, or huge, or r = 0) libm decides.
  constexpr double P = 2.0 * std::numbers::pi;
  const double n = turns(x);
  const double r = std::fma(-n, P, x);
  // (r = 0: libm gives it x's sign, the multiply-add +0.)
  return std::abs(r) < 0.5 * P && r != 0.0 ? r : std::remainder(x, P);
}
/// wrap_angle for an angle that moves by far less than a turn from one call to the next (a
/// foot's leg angle over the right-hand sides of a run): the multiple n 2π that wrap_angle removed
/// last time is kept as hi + lo (hi = n 2π rounded, lo its rounding error: their sum is n 2π
/// exactly) and removed again by two subtractions, r = (x - hi) - lo. Where that leaves
/// |r| < 3 (below π with a margin far beyond the rounding of x / 2π), turns(x) is that n, x - hi
/// is exact (Sterbenz: x lies within a factor 1.5 of hi, or hi = 0) and r is x - n 2π rounded
/// once: wrap_angle's number, without its rounding of x / 2π and its call of fma. Elsewhere (a
/// new turn, or the first call) wrap_angle itself, its n kept.
class AngleWrap {
 public:
  double operator()(double x) {
    const double r = (x - hi_) - lo_;
    return std::abs(r) < 3.0 && r != 0.0 ? r : rewrap(x);
  }

 private:
  double rewrap(double x) {
    constexpr double P = 2.0 * std::numbers::pi;
    const double n = turns(x);
    const bool usable = std::abs(n) < 0x1p30;  // x / 2π rounded far below the margin
    hi_ = usable ? n * P : std::numeric_limits<double>::quiet_NaN();
    lo_ = usable ? std::fma(n, P, -hi_) : hi_;  // the product's rounding error, exact
    return wrap_angle(x);
  }
  double hi_ = 0.0, lo_ = 0.0;  // n 2π = hi_ + lo_ (n = 0 at first)
};
/// Leg angle β_k = θ + 2αk wrapped to (-π, π] [rad].
inline double leg_angle(const WheelParams& w, int k, double theta) {
  return wrap_angle(theta + 2.0 * w.alpha() * k);
}

/// Kinematics of leg k with its foot on the ground (L_k = y / cos β_k).
struct LegKinematics {
  double beta = 0, cb = 1, sb = 0, tb = 0;  ///< β, cos β, sin β, tan β
  double L = 0;                             ///< leg length y / cos β [m]
  double delta = 0;                         ///< compression L0 - L [m]
  double delta_dot = 0;                     ///< compression rate -L̇ [m/s]
  double f = 0;                             ///< axial force K δ + C δ̇, compressive positive [N]
  double c = 0;                             ///< foot position c = x - y tan β [m]
  double cdot = 0;                          ///< foot velocity ċ = A q̇ [m/s]
  std::array<double, 3> gradL{};            ///< ∂L/∂q = (0, 1/cos β, L tan β)
  std::array<double, 3> A{};                ///< ∂c/∂q = (1, -tan β, -y / cos² β)
  double Adot_qdot = 0;                     ///< Ȧ q̇ = -2 ẏ θ̇ / cos² β - 2 y tan β θ̇² / cos² β [m/s²]
};
LegKinematics leg_kinematics(const WheelParams& w, int k, std::span<const double> y);
/// The same written into g for the leg at angle beta = leg_angle(w, k, θ) (the right-hand side's
/// hot path: no temporary to copy, and inline, so that the contact dynamics compile it into their
/// loop over the feet).
inline void leg_kinematics_at(const WheelParams& w, double beta, std::span<const double> s, LegKinematics& g) {
  using S = StateIndex;
  const double y = s[S::y], yd = s[S::yd], td = s[S::thetad];
  g.beta = beta;
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
/// The same for leg k, written into g.
inline void leg_kinematics(const WheelParams& w, int k, std::span<const double> s, LegKinematics& g) {
  leg_kinematics_at(w, leg_angle(w, k, s[StateIndex::theta]), s, g);
}

/// Height of free leg k's foot above the slope: y - (L0 - δ_k) cos β_k [m] (touchdown guard).
double foot_height(const WheelParams& w, int k, std::span<const double> y);

/// The friction law of a foot slipping with sign s at foot velocity ċ (parameters.hpp, Friction):
/// T = -s μ(ċ) N.
struct SlipLaw {
  /// μ(ċ): μ_k (Coulomb), or μ_k + (μ_s - μ_k) exp(-(|ċ|/v_s)^δ) + σ s ċ (Stribeck; σ s ċ is
  /// σ |ċ| on a slip arc, where s ċ >= 0, and smooth through ċ = 0)
  double mu = 0;
};
inline SlipLaw slip_law(const WheelParams& w, int s, double cdot) {
  if (w.friction == Friction::Coulomb) return {w.mu_k};
  const double decay = std::exp(-std::pow(std::abs(cdot) / w.stribeck_velocity, w.stribeck_exponent));
  return {w.mu_k + (w.mu_s - w.mu_k) * decay + w.viscous * s * cdot};
}

/// Slip friction denominator D = cos β - μ s sin β for the coefficient μ; D <= 0 is a Painlevé jam.
inline double slip_denominator(const LegKinematics& leg, int s, double mu) {
  return leg.cb - mu * s * leg.sb;
}
/// D with the slip law's coefficient at the leg's own foot velocity, μ(ċ).
inline double slip_denominator(const WheelParams& w, const LegKinematics& leg, int s) {
  return slip_denominator(leg, s, slip_law(w, s, leg.cdot).mu);
}

}  // namespace flexgait::rimless
