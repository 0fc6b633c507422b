#pragma once
/// \file continuation.hpp
/// Pseudo-arclength continuation of fixed points of a parametrised map z ↦ P(z, p) (Keller 1977;
/// Kuznetsov, "Elements of Applied Bifurcation Theory", 3rd ed., §10.2 and §10.3), with the
/// codimension-one bifurcations of maps detected and located on the branch.
///
/// The branch is the solution curve x(s) = (z(s), p(s)) ∈ R^{n+1} of
///   F(z, p) = P(z, p) - z = 0,                                                           (C1)
/// parametrised by (pseudo-)arclength s. One step from a point x₀ with unit tangent t₀:
///   predictor   x = x₀ + Δs t₀,
///   corrector   Newton on  F(x) = 0,  t₀ · (x - x₀) - Δs = 0                              (C2)
///               with the bordered matrix [F_z F_p; t₀ᵀ] (nonsingular at regular points and folds),
///   tangent     [F_z F_p; t₀ᵀ] t₁ = (0, …, 0, 1)ᵀ,  t₁ ← t₁/|t₁|,                          (C3)
/// so that t₀ · t₁ > 0: the direction of travel is kept through folds. Step rules: a corrector
/// that converges in ≤ 3 iterations grows Δs by 1.5 (up to max_step), one that needs ≥ 6 halves
/// it for the next step; a corrector that fails (no convergence, map failure, or a tangent that
/// turns by more than max_turn) is retried with Δs/2 down to min_step, where the branch ends.
///
/// Test functions on the branch (Kuznetsov §10.2.2), each evaluated at every point; a sign change
/// between two points is located by the Illinois (modified regula falsi) method in s along the
/// step (C2) to `locate_tolerance`:
///   fold (a multiplier through +1)         ψ_LP = t_p, the tangent's parameter component;
///   branch point (two branches cross)      ψ_BP = det [F_z F_p; tᵀ];
///   period doubling (through −1)           ψ_PD = det (P_z + I);
///   Neimark–Sacker (λ, λ̄ through |λ| = 1)  ψ_NS = Π_{i<j} (λᵢ λⱼ − 1),
/// the last also vanishing when two real multipliers have λᵢ λⱼ = 1 (a neutral saddle, which is
/// no bifurcation and is not reported). An optional label of each point (e.g. a gait's contact
/// sequence) is watched too: where it changes, the change is located by bisection in s.
///
/// A branch that turns vertical (two folds located at the same parameter, to 1e-8, with a
/// multiplier at +1 between them: a continuum of fixed points at one parameter value) ends there.
///
/// Jacobians: F_z by central differences (newton.hpp) unless an exact ∂P/∂z is supplied; F_p by
/// central differences unless ∂P/∂p is supplied with it (MapFamily::jacobians: by sensitivity, so
/// that no evaluation leaves the point: a corrector can then reach a non-smooth boundary of the
/// map to its own step, not to the difference step). Period-k orbits are fixed points of P^k (iterate()); at a period
/// doubling the period-2 branch is switched to along the critical eigenvector (switch_at_period_doubling()).
#include <Eigen/Dense>

#include <array>
#include <complex>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/numerics/reason_table.hpp"

namespace flexgait::numerics {

/// P: writes P(z, p) into `out` (dim z), or returns why it cannot be evaluated there.
using ParametrisedMap =
    std::function<std::optional<std::string>(const Eigen::VectorXd& z, double p, Eigen::VectorXd& out)>;
/// ∂P/∂z at (z, p) into J (n x n), or why not.
using ParametrisedJacobian =
    std::function<std::optional<std::string>(const Eigen::VectorXd& z, double p, Eigen::MatrixXd& J)>;
/// ∂P/∂z (n x n) and ∂P/∂p (n) at (z, p) together (e.g. from one variational run), or why not.
using ParametrisedJacobians = std::function<std::optional<std::string>(const Eigen::VectorXd& z, double p,
                                                                       Eigen::MatrixXd& J, Eigen::VectorXd& J_p)>;
/// A discrete label of the point (z, p), e.g. a gait's contact sequence.
using PointLabel = std::function<std::string(const Eigen::VectorXd& z, double p)>;

/// The family of maps to continue, as plain callbacks.
struct MapFamily {
  ParametrisedMap map;
  ParametrisedJacobian state_jacobian;  ///< exact ∂P/∂z; empty: central differences
  ParametrisedJacobians jacobians;      ///< exact ∂P/∂z and ∂P/∂p; when set, used instead of both
  PointLabel label;                     ///< empty: no labels watched
  int period = 1;                       ///< this map is the period-th iterate of the underlying map
  /// Whether p is a parameter value of the family (e.g. inside a key's bounds); empty: every p.
  /// A difference step in p stays among valid values (parameter_derivative).
  std::function<bool(double p)> valid;
};

/// ∂P/∂p at (z, p) by differences of step h: central, (P(p + h) - P(p - h)) / 2h, where both are
/// valid parameter values (MapFamily::valid); else one-sided towards the valid side,
/// (-3 P(p) + 4 P(p ± h) - P(p ± 2h)) / (±2h), of the same order h² (Fornberg 1988, Math. Comp. 51,
/// table 1); the step halved while neither fits (a range narrower than 2h). Returns why not.
std::optional<std::string> parameter_derivative(const MapFamily& f, const Eigen::VectorXd& z, double p, double h,
                                                Eigen::VectorXd& J_p);

/// P^k with ∂P^k/∂z by the chain rule, ∂P(z_{k-1}) ⋯ ∂P(z_0), when `family` has an exact ∂P/∂z.
MapFamily iterate(const MapFamily& family, int k);

struct BranchPoint;

struct ContinuationOptions {
  double initial_step = 1e-2;  ///< Δs of the first step (units of |(z, p)|)
  double min_step = 1e-9;      ///< the branch ends when a step this small fails
  double max_step = 0.1;
  int max_points = 1000;     ///< points on the branch, the start included
  double tolerance = 1e-11;  ///< a point is accepted when ||F||_inf <= tolerance (state units)
  int max_corrector_iterations = 10;
  double max_turn = 0.3;  ///< largest angle between consecutive tangents [rad]
  /// Central-difference step h = this · max(|z_i|, state_scale_i) (and max(|p|, parameter_scale)).
  /// 1e-6 suits maps evaluated to round-off; a map integrated to rtol 1e-12 wants ~3e-5 (newton.hpp).
  double fd_relative_step = 1e-6;
  Eigen::VectorXd state_scale;      ///< typical |z_i| (empty: ones)
  double parameter_scale = 1;       ///< typical |p|
  double locate_tolerance = 1e-10;  ///< special points located to this in s (so in p)
  double label_tolerance = 1e-8;    ///< label changes located to this in s
  bool detect = true;               ///< detect and locate special points
  /// Called with each point accepted on the branch, the start included (e.g. to show progress).
  std::function<void(const BranchPoint& point)> on_point = {};
};

enum class SpecialKind { Fold, BranchPoint, PeriodDoubling, NeimarkSacker, LabelChange };
/// "fold", "branch point", "period doubling", "Neimark-Sacker", "label change".
std::string to_string(SpecialKind kind);

struct BranchPoint {
  double p = 0;
  Eigen::VectorXd z;     ///< (dim n)
  double arclength = 0;  ///< s from the branch's start
  double residual = 0;   ///< ||P(z, p) - z||_inf
  int corrector_iterations = 0;
  Eigen::VectorXd tangent;                        ///< unit (dz/ds, dp/ds) (dim n + 1)
  Eigen::MatrixXd jacobian;                       ///< ∂P/∂z (n x n)
  std::vector<std::complex<double>> multipliers;  ///< eigenvalues of ∂P/∂z, largest modulus first
  bool stable = false;                            ///< every multiplier strictly inside the unit circle
  std::string label;
};

struct SpecialPoint {
  SpecialKind kind = SpecialKind::Fold;
  BranchPoint point;                      ///< the located point
  std::size_t after = 0;                  ///< index of the branch point before it
  Eigen::VectorXd eigenvector;            ///< fold: null vector of P_z − I; period doubling: of P_z + I (unit)
  double angle = 0;                       ///< Neimark–Sacker: argument of the critical multiplier in (0, π) [rad]
  double test_value = 0;                  ///< the test function at the located point
  std::string label_before, label_after;  ///< label change only
  bool located = true;  ///< false: detected, not located (at the step's end; why in Branch::stop_reason)
};

/// How a branch ended (Branch::end); Branch::stop_reason says it in words, with its numbers.
enum class BranchEnd {
  NotStarted,  ///< not even the start converged (Branch::start_failure says why)
  ReachedEnd,  ///< reached p = p_end
  TurnedBack,  ///< left the parameter interval at the other bound
  NoStep,      ///< no predictor-corrector step of min_step or more
  NotStopped,  ///< the end point on the bound could not be located
  Vertical,    ///< two folds at the same parameter with a multiplier at +1: a continuum of fixed points
  MaxPoints,   ///< max_points reached
  OtherSide,   ///< branch switching: the period-2 branch lies on the other side of the period doubling
};
constexpr std::array<EnumName<BranchEnd>, 8> enum_names(BranchEnd) {
  return {{{BranchEnd::NotStarted, "not_started"},
           {BranchEnd::ReachedEnd, "reached_end"},
           {BranchEnd::TurnedBack, "turned_back"},
           {BranchEnd::NoStep, "no_step"},
           {BranchEnd::NotStopped, "not_stopped"},
           {BranchEnd::Vertical, "vertical"},
           {BranchEnd::MaxPoints, "max_points"},
           {BranchEnd::OtherSide, "other_side"}}};
}

/// Why a branch did not start (Branch::start_failure, with Branch::start_detail; Branch::failure()
/// says it in words, reason_table.hpp).
enum class StartFailure {
  EmptyInterval,           ///< p_end = p0 (detail: the interval)
  NoFixedPoint,            ///< the corrector found no fixed point at p0 (detail: p0, the corrector's words)
  NoPeriodDoubling,        ///< branch switching was given no period doubling with its eigenvector
  PeriodDoublingNotFixed,  ///< the period-doubling point is not a fixed point of P² (detail: why)
  NoPeriodTwoPoint,        ///< no period-2 point next to the period doubling down to min_step (detail: p, why)
};

inline constexpr std::array<ReasonEntry<StartFailure>, 5> kStartFailureTable{{
    {StartFailure::EmptyInterval, "empty_interval", "the parameter interval is empty ({})"},
    {StartFailure::NoFixedPoint, "no_fixed_point", "no fixed point at p = {}"},
    {StartFailure::NoPeriodDoubling, "no_period_doubling",
     "branch switching needs a period doubling with its eigenvector"},
    {StartFailure::PeriodDoublingNotFixed, "period_doubling_not_fixed",
     "the period-doubling point is not a fixed point of P²: {}"},
    {StartFailure::NoPeriodTwoPoint, "no_period_two_point", "no period-2 point next to the period doubling at p = {}"},
}};
constexpr std::array<EnumName<StartFailure>, kStartFailureTable.size()> enum_names(StartFailure) {
  return reason_names(kStartFailureTable);
}

struct Branch {
  int period = 1;
  std::vector<BranchPoint> points;
  std::vector<SpecialPoint> special;      ///< in the order met
  bool reached_end = false;               ///< the branch reached p = p_end
  BranchEnd end = BranchEnd::NotStarted;  ///< how it ended
  std::string stop_reason;  ///< why it ended (also when reached_end), then notes (a special point not located)
  std::optional<StartFailure> start_failure;  ///< set when not even the start converged (end = NotStarted)
  std::string start_detail;                   ///< its detail

  /// Why the branch did not start, in words; "" when it started.
  std::string failure() const;
};

/// Newton on F(z, p) = 0 at fixed p from z0 (the corrector (C2) with t₀ = e_p, Δs = 0): a fixed
/// point of `family` (a period-k orbit when family = iterate(P, k)). Returns the point or why not.
std::optional<std::string> fixed_point_at(const MapFamily& family, const Eigen::VectorXd& z0, double p,
                                          const ContinuationOptions& options, BranchPoint& out);

/// The branch through the fixed point near (z0, p0), continued towards p_end until it reaches
/// p_end, leaves [min(p0, p_end), max(p0, p_end)] (it turned back), has max_points, turns
/// vertical, or a step below min_step fails.
Branch continue_fixed_points(const MapFamily& family, const Eigen::VectorXd& z0, double p0, double p_end,
                             const ContinuationOptions& options);

/// The period-2 branch born at the period doubling `pd` of `family`'s branch: the corrector on
/// P² from the PD point along its critical eigenvector v (tangent (v, 0), sign `side` = ±1: the
/// two points of the orbit), then continued towards p_end as a branch of iterate(family, 2).
Branch switch_at_period_doubling(const MapFamily& family, const SpecialPoint& pd, double p_end,
                                 const ContinuationOptions& options, int side = 1);

}  // namespace flexgait::numerics
