#pragma once
/// \file stiffness_bench.hpp
/// Experiment 1 of the thesis (spec humanoid.md; thesis Fig. 12): one elastic actuator with a
/// load arm, swept through poses. At each pose the angle error (true link angle − encoder) is
/// logged against the gravity torque m g l cos θ estimated from the encoder; a linear fit gives
/// k_joint; the sweep is repeated with the command compensated by τ_g(θ_d) / k_fit (eqs. 8-9).
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/humanoid/elastic_actuator.hpp"

namespace flexgait::humanoid {

/// The bench's actuator: the twin's, with the servo's integral action on (a servo that holds its
/// position under load, so the whole error sits in the gear).
inline ActuatorParams bench_actuator() {
  ActuatorParams a;
  a.integral_time = 0.05;
  return a;
}

struct BenchParams {
  ActuatorParams actuator = bench_actuator();  ///< the plant's actuator (its k is the truth to recover)
  double arm_length = 0.3;       ///< hinge to load [m]
  double load_mass = 13.6;       ///< point load at the arm's end [kg] (±40 Nm at 0.3 m, as in the thesis)
  double angle_min = 0.2;        ///< first pose, from horizontal, positive down [rad]
  double angle_max = 2.94;       ///< last pose [rad]: the sweep passes hanging straight down (π/2)
  int poses = 25;
  double settle_time = 2.0;      ///< time at each pose before sampling [s]
  double physics_dt = 0.001;     ///< [s]
};
Schema bench_schema();
BenchParams bench_from_config(const Config& config);

struct BenchSample {
  double command = 0;        ///< θ_d [rad]
  double encoder = 0;        ///< θ_enc [rad]
  double link = 0;           ///< true link angle [rad]
  double gravity_torque = 0; ///< m g l cos θ_link [Nm]
  /// The output compensator on the bench (eqs. 10-13, k = k_fit): the link angle from the encoder.
  double estimate_newton = 0;        ///< Newton [rad]
  double estimate_conventional = 0;  ///< θ_enc − τ_g(θ_enc)/k [rad]
  int newton_iterations = 0;
};

struct BenchResult {
  std::vector<BenchSample> uncompensated, compensated;
  double k_fit = 0;           ///< [Nm/rad], from error = τ_g / k
  double r_squared = 0;
  double max_error_uncompensated = 0;  ///< max |link − command| [rad]
  double max_error_compensated = 0;
  double min_residual_compensated = 0, max_residual_compensated = 0;  ///< signed range of link − command [rad]
  double max_error_newton = 0, max_error_conventional = 0;  ///< max |estimate − link| over both sweeps [rad]
  double max_newton_conventional = 0;                       ///< max |Newton − conventional| [rad]
  int max_newton_iterations = 0;
};

BenchResult run_stiffness_bench(const BenchParams& params);

}  // namespace flexgait::humanoid
