#pragma once
/// \file stiffness_bench.hpp
/// Experiment 1 of the thesis (Kim 2017, Fig. 12; docs/theory/humanoid.md): one elastic actuator with a
/// load arm, swept through poses. At each pose the angle error (true link angle − encoder) is
/// logged against the gravity torque m g l cos θ estimated from the encoder; a linear fit gives
/// k_joint; the sweep is repeated with the command compensated by τ_g(θ_d) / k_fit (eqs. 8-9).
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/enum_names.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/twin/elastic_actuator.hpp"

namespace flexgait::experiments {

using twin::ActuatorParams;

/// The bench's actuator: the twin's, with the servo's integral action on (a servo that holds its
/// position under load, so the whole error sits in the gear).
inline ActuatorParams bench_actuator() {
  ActuatorParams a;
  a.integral_time = 0.05;
  return a;
}

struct BenchParams {
  ActuatorParams actuator = bench_actuator();  ///< the plant's actuator (its k is the truth to recover)
  double arm_length = 0.3;                     ///< hinge to load [m]
  double load_mass = 13.6;  ///< point load at the arm's end [kg] (±40 Nm at 0.3 m, as in the thesis)
  double angle_min = 0.2;   ///< first pose, from horizontal, positive down [rad]
  double angle_max = 2.94;  ///< last pose [rad]: the sweep passes hanging straight down (π/2)
  int poses = 25;
  double settle_time = 2.0;   ///< time at each pose before sampling [s]
  double physics_dt = 0.001;  ///< [s]

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("plant.k_joint", s.actuator.k,
      {.unit = "Nm/rad", .doc = "true gear stiffness of the bench actuator", .bounds = positive()});
    v("plant.gear_damping", s.actuator.d, {.unit = "Nm s/rad", .doc = "gear damping", .bounds = closed(0, 10000)});
    v("plant.backlash", s.actuator.backlash,
      {.unit = "rad", .doc = "backlash dead band, total width", .bounds = closed(0, 0.1)});
    v("plant.servo_integral_time", s.actuator.integral_time,
      {.unit = "s",
       .doc = "integral time of the bench servo's position loop (0: PD only; the motor side then sags by tau/Kp)",
       .bounds = closed(0, 100)});
    v("bench.arm_length", s.arm_length, {.unit = "m", .doc = "hinge to load", .bounds = closed(0.01, 5)});
    v("bench.load_mass", s.load_mass,
      {.unit = "kg", .doc = "load at the arm's end (13.6 kg at 0.3 m: ±40 Nm)", .bounds = closed(0.01, 1000)});
    v("bench.angle_min", s.angle_min,
      {.unit = "rad", .doc = "first pose (from horizontal, positive down)", .bounds = closed(-3.2, 3.2)});
    v("bench.angle_max", s.angle_max,
      {.unit = "rad", .doc = "last pose (past hanging straight down at pi/2)", .bounds = closed(-3.2, 3.2)});
    v("bench.poses", s.poses, {.doc = "poses in the sweep", .bounds = closed(3, 10000)});
    v("bench.settle_time", s.settle_time,
      {.unit = "s", .doc = "time at each pose before sampling", .bounds = closed(0.1, 100)});
  }
};
inline Schema bench_schema() {
  return schema_of<BenchParams>();
}
/// The bench's keys; throws ConfigError when bench.angle_max does not exceed bench.angle_min.
BenchParams bench_from_config(const Config& config);

struct BenchSample {
  double command = 0;         ///< θ_d [rad]
  double encoder = 0;         ///< θ_enc [rad]
  double link = 0;            ///< true link angle [rad]
  double gravity_torque = 0;  ///< m g l cos θ_link [Nm]
  /// The output compensator on the bench (eqs. 10-13, k = k_fit): the link angle from the encoder.
  double estimate_newton = 0;        ///< Newton [rad]
  double estimate_conventional = 0;  ///< θ_enc − τ_g(θ_enc)/k [rad]
  int newton_iterations = 0;
};

/// Why the bench ended early (docs/guide/library.md: a run that stops early says why: a reason plus its detail).
enum class BenchFailureReason : std::uint8_t {
  kMuJoCoWarning,  ///< MuJoCo warned in a sweep; detail: its text
  kDiverged,       ///< a sweep's state is no longer finite
  kNoFit,          ///< no finite positive stiffness fits the uncompensated sweep; detail: the k_fit
};
constexpr std::array<EnumName<BenchFailureReason>, 3> enum_names(BenchFailureReason) {
  return {{{BenchFailureReason::kMuJoCoWarning, "mujoco_warning"},
           {BenchFailureReason::kDiverged, "diverged"},
           {BenchFailureReason::kNoFit, "no_fit"}}};
}

/// The sweep a failure happened in.
enum class BenchSweep : std::uint8_t { kUncompensated, kCompensated };

struct BenchFailure {
  BenchFailureReason reason = BenchFailureReason::kDiverged;
  std::string detail;  ///< MuJoCo's warnings (kMuJoCoWarning), the fitted k (kNoFit); empty otherwise
  BenchSweep sweep = BenchSweep::kUncompensated;  ///< where (kMuJoCoWarning, kDiverged)
  int pose = 0;                                   ///< the pose of that sweep (kMuJoCoWarning, kDiverged)
  /// summary.json's failure: "uncompensated sweep, pose 3: MuJoCo: <warnings>", "compensated
  /// sweep, pose 0: the simulation diverged: a non-finite state", "no finite positive stiffness
  /// fits the sweep (k_fit = -12)".
  std::string text() const;
};

/// The bench's sweeps and scores (`summary.json`, in the order of visit_fields).
struct BenchResult {
  std::vector<BenchSample> uncompensated, compensated;
  double k_true = 0;  ///< the actuator's stiffness, plant.k_joint [Nm/rad]
  double k_fit = 0;   ///< [Nm/rad], from error = τ_g / k
  double r_squared = 0;
  double max_error_uncompensated = 0;  ///< max |link − command| [rad]
  double max_error_compensated = 0;
  double min_residual_compensated = 0, max_residual_compensated = 0;  ///< signed range of link − command [rad]
  double max_error_newton = 0, max_error_conventional = 0;  ///< max |estimate − link| over both sweeps [rad]
  double max_newton_conventional = 0;                       ///< max |Newton − conventional| [rad]
  int max_newton_iterations = 0;
  /// Why the bench failed (none when it did not): a MuJoCo warning or a non-finite state in a
  /// sweep, or no finite fit. The scores after the failed part are left at zero.
  std::optional<BenchFailure> failure;

  /// (k_fit − k_true) / k_true.
  double k_fit_error() const { return (k_fit - k_true) / k_true; }
  /// summary.json's failure ("" when it did not fail).
  std::string failure_text() const { return failure ? failure->text() : std::string(); }

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("k_true", s.k_true, {.unit = "Nm/rad", .doc = "true stiffness of the bench actuator (plant.k_joint)"});
    v("k_fit", s.k_fit, {.unit = "Nm/rad", .doc = "stiffness fitted to link − encoder against the gravity torque"});
    double k_fit_error = s.k_fit_error();
    v("k_fit_error", k_fit_error, {.doc = "(k_fit − k_true) / k_true (derived)"});
    v("r_squared", s.r_squared, {.doc = "coefficient of determination of the fit"});
    v("max_error_uncompensated", s.max_error_uncompensated,
      {.unit = "rad", .doc = "max |link − command| without compensation"});
    v("max_error_compensated", s.max_error_compensated,
      {.unit = "rad", .doc = "max |link − command| with the input compensator"});
    v("residual_compensated_min", s.min_residual_compensated,
      {.unit = "rad", .doc = "smallest signed link − command, compensated"});
    v("residual_compensated_max", s.max_residual_compensated,
      {.unit = "rad", .doc = "largest signed link − command, compensated"});
    v("estimate_newton_error_max", s.max_error_newton,
      {.unit = "rad", .doc = "max |Newton estimate − link| (eqs. 10-13)"});
    v("estimate_conventional_error_max", s.max_error_conventional,
      {.unit = "rad", .doc = "max |conventional estimate − link|"});
    v("newton_conventional_max", s.max_newton_conventional, {.unit = "rad", .doc = "max |Newton − conventional|"});
    v("newton_iterations_max", s.max_newton_iterations, {.doc = "Newton iterations at most, one pose"});
    std::string failure = s.failure_text();
    v("failure", failure,
      {.doc = "why the bench failed (a MuJoCo warning, a non-finite state or fit); empty when it did not"});
  }
};

/// `poll`, when set, is called before every physics step and may throw to abandon the bench (Ctrl-C from Python).
BenchResult run_stiffness_bench(const BenchParams& params, const std::function<void()>& poll = {});

}  // namespace flexgait::experiments
