// The linearisation across events (rimless/variational.hpp): the saltation matrix of a bouncing
// ball composed with the flow's Jacobians equals finite differences of its closed-form hybrid map;
// the saltation matrix maps f⁻ to f⁺ and the section's correction removes the guard's direction;
// the central-difference gradient and Jacobian are exact on quadratics.
#include "flexgait/rimless/variational.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "flexgait/rimless/contact.hpp"

namespace flexgait::rimless {
namespace {

// A ball under gravity G from height h0 > 0 with velocity v0, bouncing once with restitution e:
// its state (h, v) at time T (after the impact at t*).
constexpr double G = 9.81, e = 0.7;
double impact_time(double h0, double v0) {
  return (v0 + std::sqrt(v0 * v0 + 2 * G * h0)) / G;
}
std::array<double, 2> ball_at(double h0, double v0, double T) {
  const double ts = impact_time(h0, v0);
  const double vplus = -e * (v0 - G * ts);
  const double s = T - ts;
  return {vplus * s - 0.5 * G * s * s, vplus - G * s};
}

TEST(Variational, SaltationOfABouncingBallMatchesFiniteDifferencesOfItsMap) {
  const double h0 = 1.0, v0 = 0.5, T = 0.9;
  const double ts = impact_time(h0, v0);
  ASSERT_LT(ts, T);
  // Flow Jacobian of free fall over τ: [[1, τ], [0, 1]]; at the impact f⁻ = (v⁻, -G), the reset
  // R(h, v) = (h, -e v), f⁺ = (-e v⁻, -G), the guard g = h.
  auto flow = [](double tau) {
    Eigen::Matrix2d P;
    P << 1, tau, 0, 1;
    return P;
  };
  const double vminus = v0 - G * ts;
  Eigen::Matrix2d Ry;
  Ry << 1, 0, 0, -e;
  const Eigen::MatrixXd S =
      saltation(Ry, Eigen::Vector2d(vminus, -G), Eigen::Vector2d(-e * vminus, -G), Eigen::RowVector2d(1, 0));
  const Eigen::Matrix2d J = flow(T - ts) * S * flow(ts);
  // Central differences of the closed form, step 1e-6: truncation ~1e-12·|∂³|, rounding
  // ~1e-16/1e-6 = 1e-10. Bound 1e-8.
  const double step = 1e-6;
  for (int j = 0; j < 2; ++j) {
    const double dh = j == 0 ? step : 0, dv = j == 1 ? step : 0;
    const auto up = ball_at(h0 + dh, v0 + dv, T), down = ball_at(h0 - dh, v0 - dv, T);
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(J(i, j), (up[static_cast<std::size_t>(i)] - down[static_cast<std::size_t>(i)]) / (2 * step), 1e-8)
          << i << ", " << j;
  }
  // The ball's saltation matrix in closed form (v⁻ < 0): S = [[-e, 0], [-(1 + e) G / v⁻, -e]].
  EXPECT_NEAR(S(0, 0), -e, 1e-15);
  EXPECT_NEAR(S(0, 1), 0.0, 1e-15);
  EXPECT_NEAR(S(1, 0), -(1 + e) * G / vminus, 1e-13);
  EXPECT_NEAR(S(1, 1), -e, 1e-15);
}

TEST(Variational, SaltationMapsTheOldVectorFieldToTheNewAndTheSectionProjects) {
  Eigen::MatrixXd Ry(3, 3);
  Ry << 1.0, 0.2, -0.1, 0.0, 0.9, 0.3, 0.4, 0.0, 1.1;
  const Eigen::Vector3d fm(0.3, -1.2, 0.7), fp(-0.5, 0.8, 0.2);
  const Eigen::RowVector3d gy(0.6, 1.0, -0.4);
  // S f⁻ = R_y f⁻ + (f⁺ - R_y f⁻) (g_y f⁻)/(g_y f⁻) = f⁺, to rounding.
  EXPECT_LT((saltation(Ry, fm, fp, gy) * fm - fp).norm(), 1e-14);
  // The section's correction I - f g_y/(g_y f) (no reset, f⁺ = 0): g_y S = 0 and S f = 0.
  const Eigen::MatrixXd P = saltation(Eigen::Matrix3d::Identity(), fm, Eigen::Vector3d::Zero(), gy);
  EXPECT_LT((gy * P).norm(), 1e-14);
  EXPECT_LT((P * fm).norm(), 1e-14);
  // Without a change of vector field or a reset the crossing changes nothing: S = I.
  EXPECT_LT((saltation(Eigen::Matrix3d::Identity(), fm, fm, gy) - Eigen::Matrix3d::Identity()).norm(), 1e-15);
}

TEST(Variational, CentralDifferencesAreExactOnQuadratics) {
  const std::vector<double> y{0.4, -1.3, 2.0};
  const Eigen::VectorXd h = Eigen::Vector3d(1e-3, 2e-3, 5e-4);
  // g = y₀² + 3 y₀ y₁ - y₂² + 2 y₂: ∇g = (2 y₀ + 3 y₁, 3 y₀, -2 y₂ + 2).
  const Eigen::RowVectorXd grad =
      gradient([](std::span<const double> v) { return v[0] * v[0] + 3 * v[0] * v[1] - v[2] * v[2] + 2 * v[2]; }, y, h);
  // Exact up to rounding of g (|g| ~ 5) over 2h (1e-3): 1e-11.
  EXPECT_NEAR(grad(0), 2 * 0.4 + 3 * -1.3, 1e-11);
  EXPECT_NEAR(grad(1), 3 * 0.4, 1e-11);
  EXPECT_NEAR(grad(2), -2 * 2.0 + 2, 1e-11);
  Eigen::MatrixXd J;
  const auto why = jacobian(
      [](std::span<const double> v, std::span<double> out) {
        out[0] = v[0] * v[1];
        out[1] = v[2] * v[2];
        out[2] = v[0] - v[2];
        return true;
      },
      y, h, J);
  ASSERT_FALSE(why.has_value());
  Eigen::Matrix3d exact;
  exact << -1.3, 0.4, 0, 0, 0, 4.0, 1, 0, -1;
  EXPECT_LT((J - exact).norm(), 1e-11);
}

TEST(Variational, AMapWhoseDecisionChangesIsReportedWithItsState) {
  const std::vector<double> y{0.0, 1.0};
  Eigen::MatrixXd J;
  const auto why = jacobian(
      [](std::span<const double> v, std::span<double> out) {
        out[0] = v[0];
        out[1] = v[1];
        return v[1] <= 1.0;  // a decision that flips above y₁ = 1
      },
      y, Eigen::Vector2d(1e-6, 1e-6), J);
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("state 1"), std::string::npos) << *why;
}

TEST(Variational, StateStepsAreRelativeWithAPhysicalFloor) {
  WheelParams w;
  std::vector<double> y(static_cast<std::size_t>(state_size(w)), 0.0);
  y[StateIndex::x] = 100.0;  // large: relative
  const Eigen::VectorXd h = state_steps(w, y);
  ASSERT_EQ(h.size(), state_size(w));
  const double v = std::sqrt(w.g * w.L0);
  EXPECT_DOUBLE_EQ(h(StateIndex::x), 6e-6 * 100.0);
  EXPECT_DOUBLE_EQ(h(StateIndex::y), 6e-6 * w.L0);
  EXPECT_DOUBLE_EQ(h(StateIndex::theta), 6e-6);
  EXPECT_DOUBLE_EQ(h(StateIndex::xd), 6e-6 * v);
  EXPECT_DOUBLE_EQ(h(StateIndex::thetad), 6e-6 * v / w.L0);
  EXPECT_DOUBLE_EQ(h(StateIndex::w_fric), 6e-6 * w.m * w.g * w.L0);
  EXPECT_DOUBLE_EQ(h(StateIndex::free_delta), 6e-6 * w.L0);
}

}  // namespace
}  // namespace flexgait::rimless
