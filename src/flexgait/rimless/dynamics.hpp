#pragma once
/// \file dynamics.hpp
/// Accelerations and contact forces of the flexible wheel in a given contact mode
/// (docs/theory/rimless.md, "Equations of motion"; Lagrange equations of the first kind):
///
///   diag(m, m, I) q̈ = m g (sin φ, -cos φ, 0) + Σ_k [ f_k ∂L_k/∂q + A_kᵀ T_k ]
///   stick:  A_k q̈ = -Ȧ_k q̇ - 2ω_b ċ_k - ω_b² (c_k - anchor_k)      (T_k is the multiplier)
///   slip:   T_k = -s_k μ f_k / (cos β_k - μ s_k sin β_k)
///   N_k = (f_k - T_k sin β_k) / cos β_k
/// with the slip law T = -s μ N (contact.hpp, SlipLaw): μ = μ_k for Coulomb friction,
/// μ = μ(ċ_k) for Stribeck friction (derivation in dynamics.cpp).
///
/// ω_b (kStickStabilization) is a Baumgarte term that holds a sticking foot on its anchor
/// against integration drift; it vanishes on the exact solution.
///
/// Point mass (I = 0): the θ row is the torque balance 0 = Q_θ. With a sticking foot it fixes
/// the multipliers and θ̇ follows from ċ = 0. With two or more feet all slipping no force is free,
/// and Q_θ, affine in θ̇ through the dampers, fixes θ̇ itself (an index-1 DAE: the I -> 0 limit of
/// the fast rotation); Dynamics::thetad then differs from the state's θ̇. A single slipping foot
/// has no consistent motion with I = 0 (docs/theory/rimless.md) and is reported.
#include <array>
#include <limits>
#include <optional>
#include <span>

#include "flexgait/rimless/contact.hpp"
#include "flexgait/rimless/outcome.hpp"

namespace flexgait::rimless {

/// Baumgarte rate ω_b for sticking feet [1/s].
inline constexpr double kStickStabilization = 10.0;

struct ContactForce {
  double f = 0;  ///< axial leg force [N]
  double T = 0;  ///< tangential ground force on the foot, +x [N]
  double N = 0;  ///< normal ground force [N]
  double D = 1;  ///< slip denominator cos β - μ(ċ) s sin β (1 for stick)
};

struct Dynamics {
  /// Empty when the mode has a consistent motion; otherwise why not (a slip jam D <= 0,
  /// or a singular constrained system, which happens only for I = 0).
  std::optional<FailureReason> failure;
  bool jammed = false;          ///< a slipping foot has D <= 0 (the failure is then the Painlevé jam)
  std::array<double, 3> qdd{};  ///< (ẍ, ÿ, θ̈)
  std::array<ContactForce, kMaxContacts> force{};
  std::array<LegKinematics, kMaxContacts> leg{};
  /// Per foot (slot i of the contact set): the turns its leg angle's wrap removes (AngleWrap),
  /// kept from one evaluation to the next.
  std::array<AngleWrap, kMaxContacts> wraps{};
  double thetad = 0;              ///< the wheel's angular velocity in force [rad/s]
  bool algebraic_thetad = false;  ///< θ̇ fixed by the torque balance (I = 0, all feet slipping)
  /// The wheel's constants that every right-hand side needs, remembered for the parameters this
  /// workspace last used (they change only between runs): each the same number as computing it
  /// again, without its sine, cosine or division.
  struct WheelConstants {
    double slope = std::numeric_limits<double>::quiet_NaN(), m = 0, I = 0, K = 0, C = 0;  ///< of these
    int legs = 0;                                                                         ///< parameters
    double sin_slope = 0, cos_slope = 1;                                                  ///< sin φ, cos φ
    std::array<double, 3> minv{};  ///< M⁻¹ = diag(1/m, 1/m, 1/I) (I > 0)
    double leg_spacing = 0;        ///< 2α = 2π/N, leg k's offset 2αk from leg 0 [rad]
    double relax_rate = 0;         ///< K/C, a free leg's relaxation rate (0 for C = 0) [1/s]
  } constants;
};

/// Dynamics of the contact set `contacts` at state y (dim state_size(w)); they depend on y's
/// configuration and velocities (x, y, θ, ẋ, ẏ, θ̇) alone.
Dynamics contact_dynamics(const WheelParams& w, const ContactSet& contacts, std::span<const double> y);
/// The same written into d, the right-hand side's hot path (no zeroing, no copy): every field
/// but force[i] and leg[i] for i >= contacts.count, which keep what they held.
void contact_dynamics(const WheelParams& w, const ContactSet& contacts, std::span<const double> y, Dynamics& d);
/// contact_dynamics without the normal forces N (force[i].N keep what they held): the flow needs
/// q̈ and T alone, the guards N as well (normal_forces completes them). False where
/// contact_dynamics leaves N unset too (a point mass's singular system).
bool contact_accelerations(const WheelParams& w, const ContactSet& contacts, std::span<const double> y, Dynamics& d);
/// N_k = (f_k - T_k sin β_k) / cos β_k for the feet of d = contact_accelerations(w, contacts, ·),
/// written into d.force[i].N (the same numbers as contact_dynamics).
void normal_forces(const ContactSet& contacts, Dynamics& d);

/// Solves the constrained system [M -Aᵀ; A 0] [a; λ] = [F; b] with M = diag(m, m, I) and
/// `rows` constraint rows A (each ∂c/∂q). Works for I = 0 when the system is nonsingular.
/// \return false if singular (then a and lambda are unspecified).
bool solve_constrained(const WheelParams& w, int rows, const std::array<std::array<double, 3>, kMaxContacts>& A,
                       const std::array<double, 3>& F, const std::array<double, kMaxContacts>& b,
                       std::array<double, 3>& a, std::array<double, kMaxContacts>& lambda);

}  // namespace flexgait::rimless
