#include "flexgait/humanoid/stiffness_bench.hpp"

#include "flexgait/compensation/link_angle_newton.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <limits>
#include <memory>

#include "flexgait/humanoid/model_xml.hpp"

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

Schema bench_schema() {
  Schema s;
  s.add(real_param("plant.k_joint", "1000.0", "Nm/rad", "true gear stiffness of the bench actuator", 0,
                   std::numeric_limits<double>::infinity(), false));
  s.add(real_param("plant.gear_damping", "80.0", "Nm s/rad", "gear damping", 0, 10000));
  s.add(real_param("plant.backlash", "0.0", "rad", "backlash dead band, total width", 0, 0.1));
  s.add(real_param("plant.servo_integral_time", "0.05", "s",
                   "integral time of the bench servo's position loop (0: PD only; the motor side then sags by tau/Kp)", 0, 100));
  s.add(real_param("bench.arm_length", "0.3", "m", "hinge to load", 0.01, 5));
  s.add(real_param("bench.load_mass", "13.6", "kg", "load at the arm's end (13.6 kg at 0.3 m: ±40 Nm)", 0.01, 1000));
  s.add(real_param("bench.angle_min", "0.2", "rad", "first pose (from horizontal, positive down)", -3.2, 3.2));
  s.add(real_param("bench.angle_max", "2.94", "rad", "last pose (past hanging straight down at pi/2)", -3.2, 3.2));
  s.add(integer_param("bench.poses", "25", "poses in the sweep", 3, 10000));
  s.add(real_param("bench.settle_time", "2.0", "s", "time at each pose before sampling", 0.1, 100));
  return s;
}

BenchParams bench_from_config(const Config& c) {
  BenchParams p;
  p.actuator.k = c.real("plant.k_joint");
  p.actuator.d = c.real("plant.gear_damping");
  p.actuator.backlash = c.real("plant.backlash");
  p.actuator.integral_time = c.real("plant.servo_integral_time");
  p.arm_length = c.real("bench.arm_length");
  p.load_mass = c.real("bench.load_mass");
  p.angle_min = c.real("bench.angle_min");
  p.angle_max = c.real("bench.angle_max");
  p.poses = static_cast<int>(c.integer("bench.poses"));
  p.settle_time = c.real("bench.settle_time");
  if (p.angle_max <= p.angle_min)
    throw ConfigError("bench.angle_max", fmt::format("key 'bench.angle_max' = '{}': must exceed bench.angle_min = {} (rad)",
                                                     p.angle_max, p.angle_min));
  return p;
}

BenchResult run_stiffness_bench(const BenchParams& p) {
  Model model{load_mjcf(bench_mjcf(p))};
  const double weight_arm = p.load_mass * 9.81 * p.arm_length;  // m g l [Nm]
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
      for (int s = 0; s < settle; ++s) drive.step(m, d, &command);
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
  r.uncompensated = sweep(0.0);
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
  r.compensated = sweep(r.k_fit);
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
