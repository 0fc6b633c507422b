#pragma once
/// \file preview_control.hpp
/// COM by ZMP preview control (Kajita et al., ICRA 2003; docs/theory/humanoid.md, "The walking
/// controller"). Cart-table model per horizontal axis, sampled at the control period T:
///
///   x = (c, ċ, c̈),  x⁺ = A x + B u (u: COM jerk),  p = C x = c − (z_c / g) c̈   (the ZMP)
///
/// with integral action (Katayama et al. 1985): the augmented system in increments
/// Ã = [1, CA; 0, A], B̃ = [CB; B], weights Q on the integrated ZMP error and R on Δu. Its DARE
/// solution P̃ gives
///
///   G_I = (R + B̃ᵀP̃B̃)⁻¹ B̃ᵀP̃ Ĩ,  G_x = (R + B̃ᵀP̃B̃)⁻¹ B̃ᵀP̃ F̃  (Ĩ = [1; 0], F̃ = [CA; A]),
///   G_p(1) = −G_I,  G_p(j) = (R + B̃ᵀP̃B̃)⁻¹ B̃ᵀ X̃(j−1),  X̃(1) = −Ãcᵀ P̃ Ĩ,  X̃(j) = Ãcᵀ X̃(j−1),
///
/// Ãc = Ã − B̃ (R + B̃ᵀP̃B̃)⁻¹ B̃ᵀP̃Ã, and the control
///
///   u(k) = −G_I Σ_{i≤k} (C x(i) − p_ref(i)) − G_x x(k) − Σ_{j=1..N} G_p(j) p_ref(k + j).
#include <Eigen/Dense>

#include <vector>

namespace flexgait::walking {

struct PreviewGains {
  double period = 0;            ///< T [s]
  double com_height = 0;        ///< z_c [m]
  Eigen::Matrix3d A;            ///< cart-table transition
  Eigen::Vector3d B;            ///< jerk input
  Eigen::RowVector3d C;         ///< ZMP output
  double G_i = 0;               ///< integral gain [1/(m s^3)... per sample]
  Eigen::RowVector3d G_x;       ///< state gain
  std::vector<double> G_p;      ///< preview gains G_p(1..N), index j−1
  Eigen::Matrix4d P;            ///< DARE solution of the augmented system
  double riccati_residual = 0;  ///< max-norm residual of P in its DARE
};

/// Gains for period T [s], COM height z_c [m], gravity g [m/s^2] (C = [1 0 −z_c/g]), horizon [s] (N = round(horizon /
/// T) samples), weights q (ZMP error) and r (jerk increment). Throws on a bad argument.
PreviewGains preview_gains(double period, double com_height, double gravity, double horizon, double q, double r);

/// One axis of the cart-table under preview control.
struct CartTable {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  ///< (c, ċ, c̈) [m, m/s, m/s^2]
  double error_sum = 0;                         ///< Σ (C x − p_ref) [m]
};

/// Advances one period: u(k) from the state and the reference p_ref[0..N] (p_ref[0] = p_ref(k)),
/// then x ← A x + B u. Returns u [m/s^3]. Reads `gains.G_p.size() + 1` reference samples.
double preview_step(const PreviewGains& gains, CartTable& cart, const double* p_ref);

/// The ZMP of the cart-table state, C x [m].
inline double cart_zmp(const PreviewGains& g, const CartTable& cart) {
  return g.C * cart.x;
}

}  // namespace flexgait::walking
