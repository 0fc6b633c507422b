#include "flexgait/experiments/stiffness_bench.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "flexgait/compensation/link_angle_newton.hpp"
#include "flexgait/experiments/walk_outcome.hpp"
#include "flexgait/twin/actuator_rig.hpp"

namespace flexgait::experiments {

BenchParams bench_from_config(const Config& c) {
  BenchParams p = record_from_config<BenchParams>(c);
  if (p.angle_max <= p.angle_min)
    throw ConfigError(
        "bench.angle_max",
        fmt::format("key 'bench.angle_max' = '{}': must exceed bench.angle_min = {} (rad)", p.angle_max, p.angle_min));
  return p;
}

std::string BenchFailure::text() const {
  const char* sweep_name = sweep == BenchSweep::kUncompensated ? "uncompensated" : "compensated";
  switch (reason) {
    case BenchFailureReason::kMuJoCoWarning:
      return fmt::format("{} sweep, pose {}: {}", sweep_name, pose,
                         WalkFailure{SimulationFailure::kMuJoCoWarning, detail}.text());
    case BenchFailureReason::kDiverged:
      return fmt::format("{} sweep, pose {}: {}", sweep_name, pose,
                         WalkFailure{SimulationFailure::kDiverged, {}}.text());
    case BenchFailureReason::kNoFit:
      return fmt::format("no finite positive stiffness fits the sweep (k_fit = {})", detail);
  }
  throw std::logic_error("BenchFailureReason without a text");
}

namespace {

/// One sweep of the bench over its poses, each commanded with the input compensator (eq. 9) at
/// stiffness k_comp (0: uncompensated), settled, then read. Sets `failure` and stops at a MuJoCo
/// warning or a non-finite state.
std::vector<BenchSample> bench_sweep(const BenchParams& p, const twin::ActuatorRigParams& rig, double weight_arm,
                                     BenchSweep which, double k_comp, const std::function<void()>& poll,
                                     std::optional<BenchFailure>& failure) {
  twin::ActuatorRig bench(rig, p.angle_min);
  std::vector<BenchSample> out;
  const int settle = static_cast<int>(std::lround(p.settle_time / p.physics_dt));
  for (int i = 0; i < p.poses; ++i) {
    const double desired = p.angle_min + (p.angle_max - p.angle_min) * i / (p.poses - 1);
    // Input compensator (eq. 9) with the bench's gravity model: the arm sags by τ_g / k.
    const double command = k_comp > 0 ? desired - weight_arm * std::cos(desired) / k_comp : desired;
    for (int s = 0; s < settle && bench.warnings() == 0; ++s) {
      if (poll) poll();
      bench.step(command);
    }
    if (bench.warnings() > 0)
      failure = BenchFailure{BenchFailureReason::kMuJoCoWarning, bench.warnings_text(), which, i};
    else if (!std::isfinite(bench.link_angle()) || !std::isfinite(bench.motor().theta_m))
      failure = BenchFailure{BenchFailureReason::kDiverged, {}, which, i};
    if (failure) break;
    BenchSample b;
    b.command = desired;
    b.encoder = twin::encoder_reading(p.actuator, bench.motor().theta_m);
    b.link = bench.link_angle();
    b.gravity_torque = weight_arm * std::cos(b.link);  // the torque the gear carries at the true pose
    out.push_back(b);
  }
  return out;
}

/// Least squares of error = link − encoder against τ_g over the uncompensated sweep: slope 1/k (the
/// load drives θ positive). Sets r.k_fit and r.r_squared.
void fit_stiffness(BenchResult& r) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  const double n = static_cast<double>(r.uncompensated.size());
  for (const auto& b : r.uncompensated) {
    const double x = b.gravity_torque, y = b.link - b.encoder;
    sx += x, sy += y, sxx += x * x, sxy += x * y, syy += y * y;
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / n;
  double ss_res = 0, ss_tot = 0;
  for (const auto& b : r.uncompensated) {
    const double y = b.link - b.encoder, fit = intercept + slope * b.gravity_torque;
    ss_res += (y - fit) * (y - fit);
    ss_tot += (y - sy / n) * (y - sy / n);
  }
  r.k_fit = 1.0 / slope;
  r.r_squared = 1.0 - ss_res / ss_tot;
}

/// The input compensator's errors over both sweeps.
void score_input_compensator(BenchResult& r) {
  r.min_residual_compensated = INFINITY;
  r.max_residual_compensated = -INFINITY;
  for (const auto& b : r.uncompensated)
    r.max_error_uncompensated = std::max(r.max_error_uncompensated, std::abs(b.link - b.command));
  for (const auto& b : r.compensated) {
    const double e = b.link - b.command;
    r.max_error_compensated = std::max(r.max_error_compensated, std::abs(e));
    r.min_residual_compensated = std::min(r.min_residual_compensated, e);
    r.max_residual_compensated = std::max(r.max_residual_compensated, e);
  }
}

/// The output compensator with the fitted stiffness on every sample: the gear carries
/// τ_g(θ) = −m g l cos θ in the convention θ_enc = θ + τ_g/k (the load pulls the link ahead of the
/// motor); Newton's estimate against the conventional one.
void score_output_compensator(BenchResult& r, double weight_arm) {
  using V = Eigen::Matrix<double, 1, 1>;
  auto torque = [&](const V& q, V& tau) { tau(0) = -weight_arm * std::cos(q(0)); };
  auto jacobian = [&](const V& q, const V&, V& G) { G(0) = weight_arm * std::sin(q(0)); };
  for (auto* set : {&r.uncompensated, &r.compensated}) {
    for (auto& b : *set) {
      const auto e = compensation::solve_link_angles<1>(V::Constant(b.encoder), V::Constant(r.k_fit), torque, jacobian);
      b.estimate_newton = e.newton(0);
      b.estimate_conventional = e.conventional(0);
      b.newton_iterations = e.iterations;
      r.max_error_newton = std::max(r.max_error_newton, std::abs(b.estimate_newton - b.link));
      r.max_error_conventional = std::max(r.max_error_conventional, std::abs(b.estimate_conventional - b.link));
      r.max_newton_conventional =
          std::max(r.max_newton_conventional, std::abs(b.estimate_newton - b.estimate_conventional));
      r.max_newton_iterations = std::max(r.max_newton_iterations, e.iterations);
    }
  }
}

}  // namespace

BenchResult run_stiffness_bench(const BenchParams& p, const std::function<void()>& poll) {
  const twin::ActuatorRigParams rig{p.actuator, p.arm_length, p.load_mass, p.physics_dt};
  const double weight_arm = p.load_mass * rig.gravity * p.arm_length;  // m g l [Nm]
  BenchResult r;
  r.k_true = p.actuator.k;
  r.uncompensated = bench_sweep(p, rig, weight_arm, BenchSweep::kUncompensated, 0.0, poll, r.failure);
  if (r.failure) return r;
  fit_stiffness(r);
  if (!std::isfinite(r.k_fit) || r.k_fit <= 0) {
    r.failure = BenchFailure{BenchFailureReason::kNoFit, fmt::format("{}", r.k_fit)};
    r.k_fit = 0;
    return r;
  }
  r.compensated = bench_sweep(p, rig, weight_arm, BenchSweep::kCompensated, r.k_fit, poll, r.failure);
  if (r.failure) return r;
  score_input_compensator(r);
  score_output_compensator(r, weight_arm);
  return r;
}

}  // namespace flexgait::experiments
