#pragma once
/// \file contact.hpp
/// State layout, foot modes and the kinematics of one leg (docs/theory/rimless.md, "Equations of motion").
///
/// Slope frame: x down the slope, y along the slope normal. Leg k makes the angle
/// β_k = θ + 2αk with the slope normal; the hub sits at foot + L_k (sin β_k, cos β_k).
#include <array>
#include <cstdint>
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

/// Leg angle β_k = θ + 2αk wrapped to (-π, π] [rad].
double leg_angle(const WheelParams& w, int k, double theta);

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
/// The same written into g (the right-hand side's hot path: no temporary to copy).
void leg_kinematics(const WheelParams& w, int k, std::span<const double> y, LegKinematics& g);

/// Height of free leg k's foot above the slope: y - (L0 - δ_k) cos β_k [m] (touchdown guard).
double foot_height(const WheelParams& w, int k, std::span<const double> y);

/// The friction law of a foot slipping with sign s at foot velocity ċ (parameters.hpp, Friction):
/// T = -s μ(ċ) N.
struct SlipLaw {
  /// μ(ċ): μ_k (Coulomb), or μ_k + (μ_s - μ_k) exp(-(|ċ|/v_s)^δ) + σ s ċ (Stribeck; σ s ċ is
  /// σ |ċ| on a slip arc, where s ċ >= 0, and smooth through ċ = 0)
  double mu = 0;
};
SlipLaw slip_law(const WheelParams& w, int s, double cdot);

/// Slip friction denominator D = cos β - μ s sin β for the coefficient μ; D <= 0 is a Painlevé jam.
inline double slip_denominator(const LegKinematics& leg, int s, double mu) {
  return leg.cb - mu * s * leg.sb;
}
/// D with the slip law's coefficient at the leg's own foot velocity, μ(ċ).
inline double slip_denominator(const WheelParams& w, const LegKinematics& leg, int s) {
  return slip_denominator(leg, s, slip_law(w, s, leg.cdot).mu);
}

}  // namespace flexgait::rimless
