#include "flexgait/walking/preview_control.hpp"

#include <cmath>
#include <stdexcept>

#include "flexgait/numerics/riccati.hpp"
#include "flexgait/walking/robot_model.hpp"

namespace flexgait::walking {

PreviewGains preview_gains(double T, double z_c, double g0, double horizon, double q, double r) {
  if (!(T > 0) || !(z_c > 0) || !(g0 > 0) || !(horizon >= T) || !(q > 0) || !(r > 0))
    throw std::invalid_argument("preview_gains: period, COM height, gravity, horizon and weights must be positive");
  PreviewGains g;
  g.period = T;
  g.com_height = z_c;
  g.A << 1, T, T * T / 2, 0, 1, T, 0, 0, 1;
  g.B << T * T * T / 6, T * T / 2, T;
  g.C << 1, 0, -z_c / g0;
  Eigen::Matrix4d At = Eigen::Matrix4d::Zero();
  At(0, 0) = 1;
  At.block<1, 3>(0, 1) = g.C * g.A;
  At.block<3, 3>(1, 1) = g.A;
  Eigen::Vector4d Bt;
  Bt(0) = g.C * g.B;
  Bt.tail<3>() = g.B;
  const Eigen::Vector4d It(1, 0, 0, 0);
  Eigen::Matrix<double, 4, 3> Ft;
  Ft.row(0) = g.C * g.A;
  Ft.bottomRows<3>() = g.A;
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  Q(0, 0) = q;
  const Eigen::Matrix<double, 1, 1> R = Eigen::Matrix<double, 1, 1>::Constant(r);
  const numerics::DareResult dare = numerics::solve_dare(At, Bt, Q, R);
  g.P = dare.P;
  g.riccati_residual = dare.residual;
  const double s = 1.0 / (r + Bt.dot(g.P * Bt));
  g.G_i = s * Bt.dot(g.P * It);
  g.G_x = s * Bt.transpose() * g.P * Ft;
  const Eigen::Matrix4d Ac = At - s * Bt * (Bt.transpose() * g.P * At);
  const int N = static_cast<int>(std::lround(horizon / T));
  g.G_p.resize(N);
  g.G_p[0] = -g.G_i;
  Eigen::Vector4d X = -Ac.transpose() * g.P * It;
  for (int j = 1; j < N; ++j) {
    g.G_p[j] = s * Bt.dot(X);
    X = Ac.transpose() * X;
  }
  return g;
}

double preview_step(const PreviewGains& g, CartTable& cart, const double* p_ref) {
  cart.error_sum += g.C * cart.x - p_ref[0];
  double u = -g.G_i * cart.error_sum - g.G_x * cart.x;
  // The preview's sum Σ G_p(j) p_ref(k + j) (Katayama et al. 1985) as Eigen's dot product: its independent partial
  // sums (vector lanes, unrolled) run in parallel where a running sum waits on each add.
  const auto N = static_cast<Eigen::Index>(g.G_p.size());
  u -= Eigen::Map<const Eigen::VectorXd>(g.G_p.data(), N).dot(Eigen::Map<const Eigen::VectorXd>(p_ref + 1, N));
  cart.x = g.A * cart.x + g.B * u;
  return u;
}

}  // namespace flexgait::walking
