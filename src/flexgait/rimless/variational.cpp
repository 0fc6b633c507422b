#include "flexgait/rimless/variational.hpp"

#include <cmath>
#include <vector>

namespace flexgait::rimless {

Eigen::VectorXd state_steps(const WheelParams& w, std::span<const double> y) {
  // ε^(1/3) relative steps, floored at a physical scale per component kind.
  const double v = std::sqrt(w.g * w.L0);
  Eigen::VectorXd h(static_cast<Eigen::Index>(y.size()));
  for (std::size_t j = 0; j < y.size(); ++j) {
    double scale = w.L0;                                                               // positions, compressions
    if (j == StateIndex::theta) scale = 1.0;                                           // rad
    if (j == StateIndex::xd || j == StateIndex::yd) scale = v;                         // m/s
    if (j == StateIndex::thetad) scale = v / w.L0;                                     // rad/s
    if (j == StateIndex::w_damp || j == StateIndex::w_fric) scale = w.m * w.g * w.L0;  // J
    h(static_cast<Eigen::Index>(j)) = 6e-6 * std::max(std::abs(y[j]), scale);
  }
  return h;
}

Eigen::RowVectorXd gradient(const std::function<double(std::span<const double>)>& g, std::span<const double> y,
                            const Eigen::VectorXd& h) {
  std::vector<double> yp(y.begin(), y.end());
  Eigen::RowVectorXd grad(static_cast<Eigen::Index>(y.size()));
  for (std::size_t j = 0; j < y.size(); ++j) {
    const double hj = h(static_cast<Eigen::Index>(j));
    yp[j] = y[j] + hj;
    const double up = g(yp);
    yp[j] = y[j] - hj;
    const double down = g(yp);
    yp[j] = y[j];
    grad(static_cast<Eigen::Index>(j)) = (up - down) / (2 * hj);
  }
  return grad;
}

std::optional<std::string> jacobian(const std::function<bool(std::span<const double>, std::span<double>)>& R,
                                    std::span<const double> y, const Eigen::VectorXd& h, Eigen::MatrixXd& J) {
  const std::size_t n = y.size();
  J.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  std::vector<double> yp(y.begin(), y.end()), up(n), down(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double hj = h(static_cast<Eigen::Index>(j));
    yp[j] = y[j] + hj;
    const bool ok_up = R(yp, up);
    yp[j] = y[j] - hj;
    const bool ok_down = R(yp, down);
    yp[j] = y[j];
    if (!ok_up || !ok_down)
      return "the reset's mode decision changes under a perturbation of state " + std::to_string(j);
    for (std::size_t i = 0; i < n; ++i)
      J(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = (up[i] - down[i]) / (2 * hj);
  }
  return std::nullopt;
}

Eigen::MatrixXd saltation(const Eigen::MatrixXd& R_y, const Eigen::VectorXd& f_minus, const Eigen::VectorXd& f_plus,
                          const Eigen::RowVectorXd& g_y) {
  const double rate = g_y.dot(f_minus);  // ġ at the crossing: nonzero for a transversal crossing
  return R_y + (f_plus - R_y * f_minus) * g_y / rate;
}

}  // namespace flexgait::rimless
