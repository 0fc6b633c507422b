#pragma once
/// \file field_baselines.hpp
/// The field's hip compensations, as `control.compensation` choices beside the thesis's (docs/guide/compensation.md):
///  - robotis: ROBOTIS's THORMANG3 walking module — a fixed feed-forward on the stance hip roll,
///    δ = ±δ_peak · sin(π s), s ∈ [0, 1] the phase of single support (0 at lift-off, peak at mid
///    single support, 0 at touchdown), with the sign that lifts the swing side (against the sag);
///    nothing else: its joint feedback reads the motor-side encoder, so it never sees the
///    deflection (no output compensator).
///  - talos: PAL's TALOS hip flexibility compensation — on each stance hip roll
///    δ = sat(LP(τ_hip_roll) / K, ±δ_max), τ_hip_roll the modelled torque of that joint while its
///    leg stands (0 while it swings), LP a first-order low-pass at f_c (discrete:
///    y ← y + (1 − e^{−2π f_c T}) (u − y)).
/// Both add δ to the hip roll command θ_d; allocation-free.
#include <algorithm>
#include <cmath>

namespace flexgait::compensation {

/// ROBOTIS's feed-forward on the stance hip roll [rad]. \param phase s of single support [-] (<0 or
/// >1: not in single support → 0); \param peak δ_peak [rad]; \param against_sag +1 or −1, the
/// direction of the hip roll that lifts the swing side.
inline double robotis_hip_roll(double phase, double peak, double against_sag) {
  if (!(phase >= 0 && phase <= 1)) return 0.0;
  return against_sag * peak * std::sin(M_PI * phase);
}

/// TALOS's low-passed hip roll torque over the stiffness, saturated.
class TalosHipRoll {
 public:
  /// \param cutoff f_c [Hz]; \param limit δ_max [rad]; \param period T [s]
  TalosHipRoll(double cutoff, double limit, double period)
      : gain_(1.0 - std::exp(-2.0 * M_PI * cutoff * period)), limit_(limit) {}
  /// One period: \param torque τ_hip_roll while the leg stands, 0 while it swings [Nm];
  /// \param stiffness K [Nm/rad]; \return δ [rad]
  double update(double torque, double stiffness) {
    filtered_ += gain_ * (torque - filtered_);
    return std::clamp(filtered_ / stiffness, -limit_, limit_);
  }
  double filtered_torque() const { return filtered_; }  ///< LP(τ) [Nm]

 private:
  double gain_, limit_;
  double filtered_ = 0;
};

}  // namespace flexgait::compensation
