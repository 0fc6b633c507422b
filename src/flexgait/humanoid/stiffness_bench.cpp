#include "flexgait/humanoid/stiffness_bench.hpp"

#include "flexgait/compensation/link_angle_newton.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <limits>
#include <memory>

#include "flexgait/humanoid/model_xml.hpp"
#include "flexgait/humanoid/mujoco_messages.hpp"

namespace flexgait::humanoid {
namespace {

// A fixed actuator housing, a hinge about +y and a light arm along +x carrying a point load.
std::string bench_mjcf(const BenchParams& p) {
  return fmt::format(R"(<mujoco model="flexgait_stiffness_bench">
  <compiler angle="radian" inertiafromgeom="true"/>
  <option timestep="{dt}" integrator="Euler" gravity="0 0 -9.81"/>
  <worldbody>
    <body name="arm" pos="0 0 1">
      <joint name="joint" type="hinge" axis="0 1 0" stiffness="{k}" damping="{d}"/>
      <geom type="capsule" fromto="0 0 0 {l} 0 0" size="0.01" mass="0.001" contype="0" conaffinity="0"/>
      <geom type="sphere" pos="{l} 0 0" size="0.03" mass="{m}" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>
)",
                     fmt::arg("dt", p.physics_dt), fmt::arg("k", p.actuator.k), fmt::arg("d", p.actuator.d),
                     fmt::arg("l", p.arm_length), fmt::arg("m", p.load_mass));
}

struct Model {
  mjModel* m;
  ~Model() { mj_deleteModel(m); }
};
struct Data {
  mjData* d;
  ~Data() { mj_deleteData(d); }
};

}  // namespace

BenchParams bench_from_config(const Config& c) {
  BenchParams p = record_from_config<BenchParams>(c);
  if (p.angle_max <= p.angle_min)
    throw ConfigError("bench.angle_max", fmt::format("key 'bench.angle_max' = '{}': must exceed bench.angle_min = {} (rad)",
                                                     p.angle_max, p.angle_min));
  return p;
}

BenchResult run_stiffness_bench(const BenchParams& p) {
  Model model{load_mjcf(bench_mjcf(p))};
  const double weight_arm = p.load_mass * 9.81 * p.arm_length;  // m g l [Nm]
  std::string failure;  // the first sweep's failure ends the bench
  auto sweep = [&](double k_comp) {
    Data data{mj_makeData(model.m)};
    mjModel* m = model.m;
    mjData* d = data.d;
    ElasticDrives drive(m, {0}, {p.actuator});
    d->qpos[0] = p.angle_min;
    mj_forward(m, d);
    drive.reset_to_links(d);
    std::vector<BenchSample> out;
    const int settle = static_cast<int>(std::lround(p.settle_time / p.physics_dt));
    for (int i = 0; i < p.poses; ++i) {
      const double desired = p.angle_min + (p.angle_max - p.angle_min) * i / (p.poses - 1);
      // Input compensator (eq. 9) with the bench's gravity model: the arm sags by τ_g / k.
      const double command = k_comp > 0 ? desired - weight_arm * std::cos(desired) / k_comp : desired;
      for (int s = 0; s < settle && mujoco_warning_count(d) == 0; ++s) drive.step(m, d, &command);
      if (mujoco_warning_count(d) > 0) failure = fmt::format("pose {}: MuJoCo: {}", i, mujoco_warnings_text(d));
      else if (!std::isfinite(d->qpos[0]) || !std::isfinite(drive.states()[0].theta_m))
        failure = fmt::format("pose {}: the simulation diverged: a non-finite state", i);
      if (!failure.empty()) break;
      BenchSample b;
      b.command = desired;
      b.encoder = encoder_reading(p.actuator, drive.states()[0].theta_m);
      b.link = d->qpos[0];
      b.gravity_torque = weight_arm * std::cos(b.link);  // the torque the gear carries at the true pose
      out.push_back(b);
    }
    return out;
  };
  BenchResult r;
  r.k_true = p.actuator.k;
  r.uncompensated = sweep(0.0);
  if (!failure.empty()) {
    r.failure = "uncompensated sweep, " + failure;
    return r;
  }
  // Least squares of error = link − encoder against τ_g: slope 1/k (the load drives θ positive).
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
  if (!std::isfinite(r.k_fit) || r.k_fit <= 0) {
    r.failure = fmt::format("no finite positive stiffness fits the sweep (k_fit = {})", r.k_fit);
    r.k_fit = 0;
    return r;
  }
  r.compensated = sweep(r.k_fit);
  if (!failure.empty()) {
    r.failure = "compensated sweep, " + failure;
    return r;
  }
  r.min_residual_compensated = INFINITY;
  r.max_residual_compensated = -INFINITY;
  for (const auto& b : r.uncompensated) r.max_error_uncompensated = std::max(r.max_error_uncompensated, std::abs(b.link - b.command));
  for (const auto& b : r.compensated) {
    const double e = b.link - b.command;
    r.max_error_compensated = std::max(r.max_error_compensated, std::abs(e));
    r.min_residual_compensated = std::min(r.min_residual_compensated, e);
    r.max_residual_compensated = std::max(r.max_residual_compensated, e);
  }
  // The output compensator with the fitted stiffness: the gear carries τ_g(θ) = −m g l cos θ in
  // the convention θ_enc = θ + τ_g/k (the load pulls the link ahead of the motor).
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
      r.max_newton_conventional = std::max(r.max_newton_conventional, std::abs(b.estimate_newton - b.estimate_conventional));
      r.max_newton_iterations = std::max(r.max_newton_iterations, e.iterations);
    }
  }
  return r;
}

}  // namespace flexgait::humanoid
