#pragma once
/// \file link_angle_newton.hpp
/// The output compensator's equation (Kim 2017, eqs. 10-13; docs/theory/humanoid.md): the link angles θ that the
/// encoders θ_enc imply through the deformation model,
///     N(θ) = θ_enc − K⁻¹ τ_g(θ) − θ = 0,
/// solved by Newton's method: N'(θ) = −(I + K⁻¹ G), G = ∂τ_g/∂θ, so each step solves
///     (K + G) Δ = K N(θ),   θ ← θ + Δ.
/// From θ = θ_enc the first step is the one-step form (12), θ_enc − (K + G)⁻¹ τ_g(θ_enc); the
/// "conventional" estimate is θ_enc − K⁻¹ τ_g(θ_enc); the per-joint form of (12), the thesis's
/// scalar one, θ_enc,j − τ_g,j(θ_enc) / (k_j + G_jj), leaves out G's coupling between joints
/// (Fig. 15 per joint). Fixed size, no allocation (it runs in the
/// control loop; the Poincaré machinery's general Newton in numerics/newton allocates).
///
/// Bounded: at most `max_iterations` steps; if the residual does not fall below `tolerance`, the
/// iterate with the smallest residual among the Newton iterates and the conventional estimate is
/// returned and `converged` is false.
#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace flexgait::compensation {

/// How often G is formed: at every iterate (Newton's method, quadratic convergence), or kept
/// while it serves (the chord method with a refresh: a step reuses the last G and its
/// factorisation, converging linearly at the rate ||(K + G)⁻¹ ΔG||, ΔG the change of G since it
/// was formed; G is formed again at the next iterate once a step cut the residual by less than
/// kChordContraction). kReused forms G afresh at the first step of each solve; kKept carries the
/// factorisation from one solve to the next (the caller's LinkAngleFactor: in the control loop G
/// moves little in a period, and the first step of a period then needs no new G) and may start
/// from a prediction (the output compensator's: the deflection extrapolated from the last three periods).
enum class NewtonJacobian { kEachIteration, kReused, kKept };
inline constexpr double kChordContraction = 0.01;
/// kKept's threshold: from the predicted start the residual is already small, and a G kept for many periods is
/// refreshed sooner. In the default walk (instructions per control period of the loop's own work, callgrind; measured
/// with the tolerance at 1e-12 and the start extrapolated from two periods):
/// 1e-2 → 141.3k, 1e-3 → 135.9k, 1e-4 → 136.0k, 1e-6 → 152.6k (forming G and factoring K + G cost about
/// two torque evaluations).
inline constexpr double kKeptChordContraction = 1e-3;
/// kKept's convergence test without the last evaluation (the test of CVODE's and RADAU5's simplified Newton,
/// Hindmarsh et al. 2005 §2.1, Hairer and Wanner 1996 §IV.8): a chord step leaves the residual its contraction rate ρ
/// times the one before, ρ = ‖(K + G̃)⁻¹(G̃ − G)‖ to first order, so a step from ‖N‖ with ρ‖N‖ ≤ tolerance is taken as
/// converged without τ_g at the new iterate. ρ: the largest ratio measured with the kept factor since it was formed
/// (none yet: no step is taken so), and at least kPredictedContraction. A measured ratio is no bound by itself: at a
/// residual of rounding's size it reads ~1e-9 where the rate is 1e-4. At most kMaxPredictedSolves solves in a row
/// end so; the next evaluates its last step, measuring ρ again as G ages.
/// kPredictedContraction: three times the rate a kept factor is held to (kKeptChordContraction; a step contracting
/// less forms G again). The default walk's steps contract by 2.7e-4 (median) to 2.4e-3 (largest of 2776).
inline constexpr double kPredictedContraction = 3 * kKeptChordContraction;
inline constexpr int kMaxPredictedSolves = 4;

struct NewtonSettings {
  int max_iterations = 10;
  /// On ||N(θ)||_inf [rad]. The estimate's error is at most about this (N' = −(I + K⁻¹G), K⁻¹G < I). 1e-9 rad is
  /// 1e-4 of the encoders' count (2π / 501923 = 1.25e-5 rad, the quantisation every reading carries): the solve
  /// adds nothing a sensor could tell (Newton steps per period in the default walk: 1e-12 2.07, 1e-9 1.19).
  double tolerance = 1e-9;
  NewtonJacobian jacobian = NewtonJacobian::kKept;
  /// With kKept: a step whose predicted residual meets the tolerance ends the solve unevaluated
  /// (kMaxPredictedSolves).
  bool predicted_convergence = true;
};

template <int N>
struct LinkAngleEstimate {
  using Vector = Eigen::Matrix<double, N, 1>;
  Vector newton = Vector::Zero();        ///< Newton's solution (or the fallback) [rad]
  Vector one_step = Vector::Zero();      ///< eq. 12 [rad] (with kKept: only if forms were asked for, else NaN)
  Vector per_joint = Vector::Zero();     ///< eq. 12 joint by joint (G's diagonal alone) [rad] (likewise)
  Vector conventional = Vector::Zero();  ///< θ_enc − τ_g(θ_enc)/k [rad] (with a start: likewise)
  int iterations = 0;                    ///< Newton steps taken
  double residual = 0;                   ///< ||N(newton)||_inf [rad] (predicted: ρ times the last evaluated one)
  bool converged = false;
  bool predicted = false;  ///< the last step was not evaluated (NewtonSettings::predicted_convergence)
  /// τ_g(newton) [Nm]: evaluated, or (predicted) the chord's own, K (θ_enc − θ) (= τ_g(θ₀) + G̃ Δ).
  Vector torque = Vector::Zero();
};

/// The LU factorisation of K + G (partial pivoting) and its solve. When G is block diagonal in two halves (each
/// leg's torques depend on its own joints only) each half's block is factored alone: partial pivoting picks the same
/// pivots and makes the same eliminations as on the whole (none across the zero blocks), so the factors, put together,
/// are the whole's, and the whole's triangular solves on them give the same numbers.
template <int N>
class LinkAngleFactor {
 public:
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  void compute(const Matrix& A, bool two_blocks) {
    rate_ = std::numeric_limits<double>::infinity();  // (a new factor's rate is not known yet)
    predicted_solves_ = 0;
    if constexpr (N % 2 == 0) {
      if (two_blocks) {
        constexpr int H = N / 2;
        factor(halves_[0], A.template topLeftCorner<H, H>());
        factor(halves_[1], A.template bottomRightCorner<H, H>());
        lu_.setZero();
        lu_.template topLeftCorner<H, H>() = halves_[0]->matrixLU();
        lu_.template bottomRightCorner<H, H>() = halves_[1]->matrixLU();
        for (int i = 0; i < H; ++i) {
          permutation_.indices()(i) = halves_[0]->permutationP().indices()(i);
          permutation_.indices()(H + i) = H + halves_[1]->permutationP().indices()(i);
        }
        formed_ = true;
        return;
      }
    }
    factor(whole_, A);
    lu_ = whole_->matrixLU();
    permutation_ = whole_->permutationP();
    formed_ = true;
  }
  /// Whether compute has been called since construction or the last forget.
  bool formed() const { return formed_; }
  void forget() { formed_ = false; }
  /// The largest contraction ‖N(θ_{k+1})‖ / ‖N(θ_k)‖ measured on a step with this factor since it was formed
  /// (infinite until one is), and the solves ended on a predicted residual since one was.
  double rate() const { return rate_; }
  int predicted_solves() const { return predicted_solves_; }
  void measured(double ratio) {
    rate_ = rate_ == std::numeric_limits<double>::infinity() ? ratio : std::max(rate_, ratio);
    predicted_solves_ = 0;
  }
  void predicted() { ++predicted_solves_; }
  /// (K + G)⁻¹ b as Eigen's PartialPivLU::solve forms it.
  Vector solve(const Vector& b) const {
    Vector x = permutation_ * b;
    lu_.template triangularView<Eigen::UnitLower>().solveInPlace(x);
    lu_.template triangularView<Eigen::Upper>().solveInPlace(x);
    return x;
  }

 private:
  template <class LU, class Block>
  static void factor(std::optional<LU>& lu, const Block& A) {
    if (lu)
      lu->compute(A);
    else
      lu.emplace(A);
  }
  static constexpr int kHalf = N % 2 == 0 ? N / 2 : 1;
  Matrix lu_ = Matrix::Zero();
  Eigen::PermutationMatrix<N, N> permutation_;
  bool formed_ = false;
  double rate_ = std::numeric_limits<double>::infinity();
  int predicted_solves_ = 0;
  std::optional<Eigen::PartialPivLU<Matrix>> whole_;
  std::array<std::optional<Eigen::PartialPivLU<Eigen::Matrix<double, kHalf, kHalf>>>, 2> halves_;
};

/// `torque(θ, τ)` writes τ_g(θ) [Nm]; `jacobian(θ, τ, G)` writes G = ∂τ_g/∂θ [Nm/rad] given
/// τ = τ_g(θ) (it is only asked for where another step follows). `stiffness`: k per joint [Nm/rad].
/// `two_blocks`: G is block diagonal in its two halves (N even), K + G is factored block by block.
/// With NewtonJacobian::kKept, `kept` is the factorisation carried between solves (the caller forgets
/// it when the form of G changes; a changed K only slows the chord until G is formed again), `start` (if given)
/// Newton's first iterate in θ_enc's place (a prediction from the last solves), and the conventional, one-step and
/// per-joint forms, which need τ_g and G at θ_enc, are formed (apart from Newton's iterates, which they do not change)
/// only with `forms` (else NaN).
template <int N, class Torque, class Jacobian>
LinkAngleEstimate<N> solve_link_angles(const Eigen::Matrix<double, N, 1>& encoder,
                                       const Eigen::Matrix<double, N, 1>& stiffness, Torque&& torque,
                                       Jacobian&& jacobian, const NewtonSettings& settings = {},
                                       bool two_blocks = false, LinkAngleFactor<N>* kept = nullptr, bool forms = true,
                                       const Eigen::Matrix<double, N, 1>* start = nullptr) {
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  LinkAngleEstimate<N> out;
  Vector tau, theta = encoder;
  Matrix G;
  const Vector compliance = stiffness.cwiseInverse();
  const auto factor_of = [&](LinkAngleFactor<N>& lu) {
    Matrix A = G;
    A.diagonal() += stiffness;
    lu.compute(A, two_blocks);
  };
  LinkAngleFactor<N> own;  // formed at the first step (refresh), before any solve
  const bool carried = settings.jacobian == NewtonJacobian::kKept && kept != nullptr;
  LinkAngleFactor<N>& lu = carried ? *kept : own;
  if (!carried) start = nullptr;
  const Vector unformed = Vector::Constant(std::numeric_limits<double>::quiet_NaN());
  out.conventional = out.one_step = out.per_joint = unformed;
  if (!start || forms) {
    torque(theta, tau);
    out.conventional = encoder - compliance.cwiseProduct(tau);
  }
  if (carried && forms) {
    // The forms at θ_enc with their own G; Newton's steps go on with the kept factorisation.
    jacobian(theta, tau, G);
    out.per_joint = encoder - tau.cwiseQuotient(stiffness + G.diagonal());
    LinkAngleFactor<N> at_encoder;
    // (nothing kept and Newton starting at θ_enc: its first factor is this one)
    LinkAngleFactor<N>& f = lu.formed() || start ? at_encoder : lu;
    factor_of(f);
    out.one_step = encoder + f.solve(stiffness.cwiseProduct(out.conventional - encoder));  // (K N(θ_enc))
  }
  if (start) {
    theta = *start;
    torque(theta, tau);
  }
  Vector r = encoder - compliance.cwiseProduct(tau) - theta;  // N(θ)
  double residual = r.template lpNorm<Eigen::Infinity>();
  Vector best = theta;
  double best_residual = residual;
  bool refresh = !lu.formed();
  for (int it = 0; it < settings.max_iterations && !(residual <= settings.tolerance); ++it) {
    if (refresh || settings.jacobian == NewtonJacobian::kEachIteration) {
      jacobian(theta, tau, G);
      if (it == 0 && !carried) out.per_joint = encoder - tau.cwiseQuotient(stiffness + G.diagonal());
      factor_of(lu);
    }
    theta += lu.solve(stiffness.cwiseProduct(r));
    if (it == 0 && !carried) out.one_step = theta;
    out.iterations = it + 1;
    const double previous = residual;
    const double rate = std::max(lu.rate(), kPredictedContraction);
    if (carried && settings.predicted_convergence && rate * previous <= settings.tolerance &&
        lu.predicted_solves() < kMaxPredictedSolves) {
      lu.predicted();
      out.predicted = true;
      tau = stiffness.cwiseProduct(encoder - theta);  // (K + G̃) Δ = K N(θ₀): τ₀ + G̃ Δ = K (θ_enc − θ₀ − Δ)
      residual = best_residual = rate * previous;
      best = theta;
      break;
    }
    torque(theta, tau);
    r = encoder - compliance.cwiseProduct(tau) - theta;
    residual = r.template lpNorm<Eigen::Infinity>();
    if (carried) lu.measured(residual / previous);
    refresh = !(residual <= (carried ? kKeptChordContraction : kChordContraction) * previous);
    if (!std::isfinite(residual)) break;
    if (residual < best_residual) {
      best = theta;
      best_residual = residual;
    }
  }
  if (out.iterations == 0 && !carried) out.one_step = out.per_joint = theta;
  out.converged = residual <= settings.tolerance;
  if (out.converged) {
    out.newton = theta;
    out.residual = residual;
    out.torque = tau;
    return out;
  }
  // Fallback: the best iterate, or the conventional estimate if that is better.
  if (!(out.conventional == out.conventional)) {  // (not formed: a start was given)
    torque(encoder, tau);
    out.conventional = encoder - compliance.cwiseProduct(tau);
  }
  torque(out.conventional, tau);
  const double conventional_residual =
      (encoder - compliance.cwiseProduct(tau) - out.conventional).template lpNorm<Eigen::Infinity>();
  const bool use_conventional = !(best_residual <= conventional_residual);
  out.newton = use_conventional ? out.conventional : best;
  out.residual = use_conventional ? conventional_residual : best_residual;
  if (!use_conventional) torque(best, tau);
  out.torque = tau;
  return out;
}

}  // namespace flexgait::compensation
