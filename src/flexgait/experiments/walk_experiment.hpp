#pragma once
/// \file walk_experiment.hpp
/// A closed-loop walk: the walking controller drives the twin through SensorReadings only; this
/// evaluation code alone reads the ground truth, to log and score the walk (its metrics: docs/guide/humanoid.md):
/// fall detection (pelvis too low or tilted, a body other than a sole on the floor), steps
/// completed, ZMP tracking (true ZMP from contact forces against the reference), pelvis attitude
/// (IMU against the commanded level attitude), landing errors, COM tracking, support margin.
///
/// Frames: the plan's world frame has the initial feet at (0, ±w/2); the twin's truth is moved
/// into it by the offset between the truth and planned initial feet.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "flexgait/compensation/deformation_compensator.hpp"
#include "flexgait/core/config.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/experiments/walk_outcome.hpp"
#include "flexgait/loop/closed_loop.hpp"
#include "flexgait/loop/walking_control.hpp"
#include "flexgait/robot/robot_description.hpp"
#include "flexgait/robot/robot_params.hpp"
#include "flexgait/twin/plant.hpp"
#include "flexgait/walking/stance_defaults.hpp"
#include "flexgait/walking/walk_params.hpp"
#include "flexgait/walking/walking_controller.hpp"

namespace flexgait::experiments {

struct WalkRunParams {
  humanoid::RobotParams robot;  ///< the twin (truth) of the builtin robot; sole_friction for any robot
  humanoid::RobotDescriptionParams
      description;  ///< robot.description and its mapping (robot.joints.*, robot.feet.*, ...)
  /// The loaded description (null for the builtin robot): the twin and the controller's model are
  /// made from it (walk_run_from_config loads it).
  std::shared_ptr<const humanoid::LoadedRobot> loaded;
  twin::PlantParams plant;
  humanoid::RobotParams controller_robot;  ///< the controller's belief of the robot
  walking::WalkParams walk;
  walking::BalanceParams balance;
  compensation::CompensationParams control;  ///< the deformation compensators (control.*)
  walking::EstimatorParams estimator;        ///< the controller's attitude estimator (estimator.*)
  walking::HealthParams health;              ///< the controller's sensor health checks (health.*)
  twin::Push push;                           ///< a push on the twin (disturbance.push.*; none by default)
  std::vector<twin::Push> pushes;            ///< more pushes (disturbance.pushes; the single push is added after them)
  double log_period = 0.02;                  ///< log sample period [s] (a multiple of the control period)
  double fall_height = 0.2;                  ///< fallen when the pelvis sinks this far below its height [m]
  double fall_tilt = 0.6;                    ///< or tilts this far [rad]
  /// The keys left `auto` and the values walk_run_from_config derived for them from the robot, in
  /// derivation order (with_derived_values writes them into config.yaml); not keys themselves.
  std::vector<std::pair<std::string, double>> derived;
  /// The compensation keys left at their defaults that walk_run_from_config resolved for the compensation mode
  /// (off and the field's baselines keep the thesis's gravity loads, no horizontal force without the dynamic loads,
  /// the gears' damping believed at the plant's), with their values' text; with_derived_values writes them too.
  std::vector<std::pair<std::string, std::string>> case_defaults;

  /// Keys robot.*, plant.*, walk.*, balance.*, control.*, estimator.*, health.*, disturbance.push.*,
  /// disturbance.pushes, output.log_period (the controller's belief of the robot and the fall thresholds are not keys).
  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    humanoid::RobotParams::visit_fields(s.robot, v);
    humanoid::RobotDescriptionParams::visit_fields(s.description, v);
    twin::PlantParams::visit_fields(s.plant, v);
    walking::WalkParams::visit_fields(s.walk, v);
    walking::BalanceParams::visit_fields(s.balance, v);
    compensation::CompensationParams::visit_fields(s.control, v);
    walking::EstimatorParams::visit_fields(s.estimator, v);
    walking::HealthParams::visit_fields(s.health, v);
    twin::Push::visit_fields(s.push, v);
    v("disturbance.pushes", s.pushes,
      {.doc = "pushes on the twin, each {time [s] (or step, phase), body, force [N, world], duration [s]}; "
              "disturbance.push.* adds one more"});
    v("output.log_period", s.log_period,
      {.unit = "s", .doc = "period of the logged samples", .bounds = closed(1e-4, 10)});
  }
};

/// WalkRunParams's keys, those of walking::kScaledDefaults derived from the robot unless set (`auto`).
Schema walk_run_schema();
/// The run's parameters (the controller believes the twin's robot); throws ConfigError as plant_from_config
/// and, for a description file, as twin::load_robot and walking::make_robot_model.
WalkRunParams walk_run_from_config(const Config& config);
/// `config` with the values walk_run_from_config derived from the robot (the keys left `auto`)
/// written in, so a run directory's config.yaml replays its walk on its own.
Config with_derived_values(const Config& config, const WalkRunParams& params);
/// The twin of the run's robot (builtin or loaded).
twin::TwinModel walk_twin(const WalkRunParams& params);
/// The controller's model of the run's robot (its belief, controller_robot, for the builtin).
walking::RobotModel walk_controller_model(const WalkRunParams& params);

struct WalkSample {
  double t = 0;
  int step = -1;
  double zmp_ref_x = 0, zmp_ref_y = 0;     ///< [m]
  double zmp_ft_x = 0, zmp_ft_y = 0;       ///< from the F/T sensors (the controller's) [m]
  double zmp_true_x = 0, zmp_true_y = 0;   ///< from the contact forces [m]
  double com_ref_x = 0, com_ref_y = 0;     ///< planned [m]
  double com_x = 0, com_y = 0, com_z = 0;  ///< true [m]
  double pelvis_z = 0;                     ///< true [m]
  double pelvis_x = 0, pelvis_y = 0;       ///< true, the plan's frame [m]
  double imu_roll = 0, imu_pitch = 0;      ///< the controller's estimate [rad]
  double roll_true = 0, pitch_true = 0;    ///< the twin's pelvis attitude [rad]
  unsigned sensor_faults = 0;  ///< bit i: sensor i (humanoid::SensorId) bad in a period since the last sample
  bool safe_stop = false;      ///< the controller is stopping the walk for a failed sensor
  double roll_correction = 0, pitch_correction = 0;  ///< balance controller [rad]
  double support_margin = 0;  ///< true ZMP to the edge of the true support polygon (soles on the floor) [m]
  std::array<std::array<double, 3>, 2> sole{};  ///< true sole centres [m]
  // The deformation model (all joints; the estimates only when the output compensator runs):
  humanoid::JointVector desired{};          ///< θ_d from the IK [rad]
  humanoid::JointVector command{};          ///< θ_cmd sent to the servos [rad]
  humanoid::JointVector encoder{};          ///< θ_enc [rad]
  humanoid::JointVector link{};             ///< the twin's true link angles [rad]
  humanoid::JointVector estimate{};         ///< θ̂ by Newton (eq. 11) [rad]
  humanoid::JointVector conventional{};     ///< θ_enc − τ_g(θ_enc)/k [rad]
  humanoid::JointVector per_joint{};        ///< eq. 12 joint by joint (the thesis's scalar form) [rad]
  humanoid::JointVector torque_model{};     ///< τ_g of the input compensator (desired pose) [Nm]
  humanoid::JointVector torque_estimate{};  ///< τ_g of the output compensator (estimated pose) [Nm]
  humanoid::JointVector torque_true{};      ///< the twin's gear torques [Nm]
  humanoid::JointVector k_estimate{};       ///< control.k_estimation on: each joint's stiffness estimate [Nm/rad]
  /// Pelvis roll by kinematics from the stance sole (flat on the floor) through the encoders and
  /// through the estimate (eq. 1), against the IMU's [rad]; 0 in double support.
  double roll_kin_encoder = 0, roll_kin_estimate = 0;
  std::array<double, 3> push_force{};  ///< push force applied in the last physics step (world) [N]
  /// The vertical ground force on each foot (left, right) as the controller reads it from the F/T
  /// sensors (ControllerStatus::foot_force) [N].
  std::array<double, 2> foot_force{};
  /// balance.mode = dcm: the controller's DCM ξ (its COM estimate) and the plan's ξ_ref, in its
  /// own frame (0 in pd mode, where it computes none) [m].
  std::array<double, 2> dcm{}, dcm_ref{};
};

struct Landing {
  int step = 0, side = 0;
  double planned_x = 0, planned_y = 0, planned_yaw = 0;
  double actual_x = 0, actual_y = 0, actual_yaw = 0;
  double error = 0;  ///< horizontal distance [m]
};

/// The scores of a walk (`summary.json`, in this order; wall time and real-time factor go to
/// `timing.json` only, so that summary.json is the same bytes on every run).
struct WalkMetrics {
  compensation::CompensationMode compensation = compensation::CompensationMode::kOff;  ///< control.compensation
  compensation::GravityForm gravity_model = compensation::GravityForm::kFull;          ///< control.gravity_model
  std::string compensation_case;  ///< the compensation case the run's settings make (compensation_case_name)
  bool fell = false;
  std::optional<FallReason> fall_reason;  ///< empty when it did not fall
  double fall_time = 0;                   ///< [s]
  /// Why the simulation itself failed (empty when it did not): a MuJoCo warning (an unstable or
  /// overfull simulation) or a non-finite state. The walk ends there; its scores cover what ran.
  std::optional<WalkFailure> failure;
  double failure_time = 0;  ///< [s]
  int steps_planned = 0, steps_completed = 0;
  double zmp_rms_x = 0, zmp_rms_y = 0;  ///< true ZMP − reference over the walk [m]
  double zmp_max_x = 0, zmp_max_y = 0;
  double zmp_single_support_rms_y = 0;  ///< the same in single support only [m]
  double zmp_ft_rms_error = 0;          ///< F/T ZMP (soles where they are) against the contact forces' [m]
  double zmp_controller_rms_error = 0;  ///< the controller's F/T ZMP (soles where planned) against the true [m]
  double support_margin_min = 0;        ///< smallest margin of the true ZMP inside the true support polygon [m]
  double pelvis_roll_error_max = 0, pelvis_roll_error_rms = 0;  ///< true pelvis attitude against level [rad]
  double pelvis_pitch_error_max = 0, pelvis_pitch_error_rms = 0;
  double landing_error_max = 0, landing_error_mean = 0;  ///< [m]
  double com_error_rms = 0, com_error_max = 0;           ///< true COM − planned (xy) [m]
  double support_error_max = 0;  ///< largest slide of a standing sole from where it came down [m]
  int ik_clamped = 0;            ///< control periods with a leg target out of reach
  int joint_limit_hits = 0;      ///< commanded joint angles clamped into their ranges (a loaded robot)
  int desired_range_hits = 0;    ///< desired (link) joint angles outside their ranges (a loaded robot)
  bool joint_ranges = false;     ///< a loaded robot: its joint ranges bound the commands
  int mujoco_warnings = 0;       ///< MuJoCo warnings
  double simulated_time = 0;     ///< [s]
  double wall_time = 0;          ///< [s] (timing.json)
  double real_time_factor = 0;   ///< (timing.json)
  double riccati_residual = 0;
  // Deformation (leg joints, over the walk): deflection = θ_enc − θ_link (true).
  double deflection_rms = 0, deflection_max = 0;                  ///< [rad]
  double estimate_error_rms = 0, estimate_error_max = 0;          ///< θ̂ (Newton) − θ_link [rad]
  double one_step_error_rms = 0;                                  ///< eq. 12 − θ_link [rad]
  double conventional_error_rms = 0, conventional_error_max = 0;  ///< [rad]
  double newton_conventional_max = 0;                             ///< max |θ̂ − conventional| [rad]
  double per_joint_conventional_max = 0;                          ///< max |per-joint eq. 12 − conventional| [rad]
  double link_error_rms = 0, link_error_max = 0;  ///< θ_link − θ_d: what input compensation removes [rad]
  double pelvis_roll_kinematic_encoder_rms = 0,
         pelvis_roll_kinematic_estimate_rms = 0;  ///< single support, against the IMU [rad]
  int newton_iterations_max = 0;
  double newton_iterations_mean = 0;
  int newton_failures = 0;            ///< control periods not converged (fallback used)
  double newton_predicted_share = 0;  ///< control periods whose last Newton step was not evaluated
  // Sensors (docs/guide/humanoid.md, "Sensors, faults and the attitude estimate").
  double attitude_error_rms = 0, attitude_error_max = 0;  ///< controller's roll/pitch − true (norm of both) [rad]
  int sensor_fault_episodes = 0;                          ///< times a sensor turned bad (all sensors)
  double sensor_fault_time = 0;                           ///< total time sensors were bad (summed over sensors) [s]
  std::vector<std::string> sensor_faults;          ///< "<sensor>: <episodes> x, <time> s" for each flagged sensor
  bool safe_stop = false;                          ///< the controller stopped the walk for a failed sensor
  std::optional<SafeStopReason> safe_stop_reason;  ///< none without a safe stop
  double safe_stop_time = 0;                       ///< [s]
  bool pushed = false;                             ///< a push was configured (disturbance.push.*)
  double push_impulse = 0;                         ///< |applied push impulse| [N s]
  double capture_point_bound = 0;                  ///< the bound for the push's direction at its start [N s]

  /// The walk ran to its planned end: every step landed, no fall, no safe stop, no failure.
  bool completed() const { return !fell && !failure && !safe_stop && steps_completed == steps_planned; }
  /// summary.json's outcome: "walked" (completed), the fall reason's name for a fall or lost
  /// support ("pelvis_too_low", "airborne", "slid", ...), "safe_stop", "simulation_failure", or
  /// "incomplete" (ran to its end with a step not landed).
  std::string outcome() const {
    if (failure) return "simulation_failure";
    if (fell) return std::string(name_of(*fall_reason));
    if (safe_stop) return "safe_stop";
    return completed() ? "walked" : "incomplete";
  }
  /// summary.json's fall_reason ("" when it did not fall) and failure ("" when it did not).
  std::string fall_text() const { return fall_reason ? std::string(fall_sentence(*fall_reason)) : std::string(); }
  std::string failure_text() const { return failure ? failure->text() : std::string(); }
  /// summary.json's safe_stop_reason ("" without a safe stop).
  std::string safe_stop_text() const { return safe_stop_reason ? safe_stop_reason->text() : std::string(); }
  /// The output compensator ran: its estimator's scores apply.
  bool has_estimate() const {
    return compensation == compensation::CompensationMode::kOutput ||
           compensation == compensation::CompensationMode::kBoth;
  }
  /// rms estimator error over rms deflection (0 without deflection).
  double estimate_error_share_of_deflection() const {
    return deflection_rms > 0 ? estimate_error_rms / deflection_rms : 0.0;
  }

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    std::string outcome = s.outcome();
    v("outcome", outcome,
      {.doc = "walked (every step landed where planned, the robot supported to the end), or why not: a fall "
              "(pelvis_too_low, pelvis_tilted, non_sole_contact, flipped), lost support (airborne, slid, "
              "missed_step, unsupported), safe_stop, simulation_failure, incomplete"});
    v("compensation", s.compensation, {.doc = "control.compensation of the run"});
    v("gravity_model", s.gravity_model, {.doc = "control.gravity_model of the run"});
    v("compensation_case", s.compensation_case,
      {.doc = "the compensation case the run's control.* keys make, as the compensation study names it (off, "
              "robotis, talos, or input/output/both with -thesis-form, -measured/-dynamic, -horizontal, -lag; the "
              "default both-dynamic-horizontal-lag)"});
    v("fell", s.fell,
      {.doc = "the robot fell or lost its support (pelvis too low, tilted or upside down, a body other than a sole on "
              "the floor, airborne, a sole slid or a step missed): outcome names which"});
    std::string fall_reason = s.fall_text(), failure = s.failure_text();
    v("fall_reason", fall_reason, {.doc = "why it fell; empty when it did not"});
    v("fall_time", s.fall_time, {.unit = "s", .doc = "when it fell (left out when it did not)", .present = s.fell});
    v("failure", failure,
      {.doc = "why the simulation failed (a MuJoCo warning or a non-finite state); empty when it did not"});
    v("failure_time", s.failure_time,
      {.unit = "s", .doc = "when the simulation failed (left out when it did not)", .present = s.failure.has_value()});
    v("steps_planned", s.steps_planned, {.doc = "footsteps in the plan"});
    v("steps_completed", s.steps_completed,
      {.doc =
           "footsteps landed on the floor where planned relative to the standing sole (within half the sole's width)"});
    v("zmp_rms_x", s.zmp_rms_x, {.unit = "m", .doc = "rms of true ZMP − reference, x"});
    v("zmp_rms_y", s.zmp_rms_y, {.unit = "m", .doc = "rms of true ZMP − reference, y"});
    v("zmp_max_x", s.zmp_max_x, {.unit = "m", .doc = "max |true ZMP − reference|, x"});
    v("zmp_max_y", s.zmp_max_y, {.unit = "m", .doc = "max |true ZMP − reference|, y"});
    v("zmp_single_support_rms_y", s.zmp_single_support_rms_y,
      {.unit = "m", .doc = "rms of true ZMP − reference, y, single support"});
    v("zmp_ft_rms_error", s.zmp_ft_rms_error,
      {.unit = "m", .doc = "F/T ZMP (soles where they are) against the contact forces'"});
    v("zmp_controller_rms_error", s.zmp_controller_rms_error,
      {.unit = "m", .doc = "the controller's F/T ZMP (soles where planned) against the true"});
    v("support_margin_min", s.support_margin_min,
      {.unit = "m", .doc = "smallest margin of the true ZMP inside the true support polygon"});
    v("pelvis_roll_error_max", s.pelvis_roll_error_max,
      {.unit = "rad", .doc = "max |true pelvis roll| (level commanded)"});
    v("pelvis_roll_error_rms", s.pelvis_roll_error_rms, {.unit = "rad", .doc = "rms true pelvis roll"});
    v("pelvis_pitch_error_max", s.pelvis_pitch_error_max, {.unit = "rad", .doc = "max |true pelvis pitch|"});
    v("pelvis_pitch_error_rms", s.pelvis_pitch_error_rms, {.unit = "rad", .doc = "rms true pelvis pitch"});
    v("attitude_error_rms", s.attitude_error_rms,
      {.unit = "rad", .doc = "rms of the controller's pelvis roll/pitch estimate − true (norm of both)"});
    v("attitude_error_max", s.attitude_error_max, {.unit = "rad", .doc = "max of the same"});
    v("landing_error_max", s.landing_error_max, {.unit = "m", .doc = "largest horizontal distance landed − planned"});
    v("landing_error_mean", s.landing_error_mean, {.unit = "m", .doc = "mean horizontal distance landed − planned"});
    v("com_error_rms", s.com_error_rms, {.unit = "m", .doc = "rms of true COM − planned (xy)"});
    v("com_error_max", s.com_error_max, {.unit = "m", .doc = "max |true COM − planned| (xy)"});
    v("support_error_max", s.support_error_max,
      {.unit = "m", .doc = "largest slide of a standing sole from where it came down (limit: half the sole's width)"});
    v("deflection_rms", s.deflection_rms, {.unit = "rad", .doc = "rms gear deflection θ_enc − θ_link, leg joints"});
    v("deflection_max", s.deflection_max, {.unit = "rad", .doc = "max gear deflection, leg joints"});
    v("link_error_rms", s.link_error_rms, {.unit = "rad", .doc = "rms θ_link − θ_d (what input compensation removes)"});
    v("link_error_max", s.link_error_max, {.unit = "rad", .doc = "max |θ_link − θ_d|"});
    const bool estimate = s.has_estimate();
    v("estimate_error_rms", s.estimate_error_rms,
      {.unit = "rad", .doc = "rms θ̂ (Newton, eq. 11) − θ_link", .present = estimate});
    v("estimate_error_max", s.estimate_error_max, {.unit = "rad", .doc = "max |θ̂ − θ_link|", .present = estimate});
    double share = s.estimate_error_share_of_deflection();
    v("estimate_error_share_of_deflection", share,
      {.doc = "estimate_error_rms / deflection_rms (derived)", .present = estimate});
    v("one_step_error_rms", s.one_step_error_rms,
      {.unit = "rad", .doc = "rms of the one-step estimate (eq. 12) − θ_link", .present = estimate});
    v("conventional_error_rms", s.conventional_error_rms,
      {.unit = "rad", .doc = "rms of θ_enc − τ_g(θ_enc)/k − θ_link", .present = estimate});
    v("conventional_error_max", s.conventional_error_max,
      {.unit = "rad", .doc = "max of the same", .present = estimate});
    v("newton_conventional_max", s.newton_conventional_max,
      {.unit = "rad", .doc = "max |θ̂ − conventional|", .present = estimate});
    v("per_joint_conventional_max", s.per_joint_conventional_max,
      {.unit = "rad",
       .doc = "max |eq. 12 joint by joint − conventional| (thesis Fig. 15 per joint)",
       .present = estimate});
    v("newton_iterations_max", s.newton_iterations_max,
      {.doc = "Newton iterations, most in one period", .present = estimate});
    v("newton_iterations_mean", s.newton_iterations_mean,
      {.doc = "Newton iterations per period, mean", .present = estimate});
    v("newton_failures", s.newton_failures,
      {.doc = "control periods Newton did not converge (fallback used)", .present = estimate});
    v("newton_predicted_share", s.newton_predicted_share,
      {.doc = "share of control periods whose last Newton step ended on its predicted residual, unevaluated "
              "(docs/guide/compensation.md)",
       .present = estimate});
    v("pelvis_roll_kinematic_estimate_rms", s.pelvis_roll_kinematic_estimate_rms,
      {.unit = "rad", .doc = "pelvis roll by kinematics through θ̂ − IMU, single support, rms", .present = estimate});
    v("pelvis_roll_kinematic_encoder_rms", s.pelvis_roll_kinematic_encoder_rms,
      {.unit = "rad", .doc = "pelvis roll by kinematics through the encoders − IMU, single support, rms"});
    v("sensor_fault_episodes", s.sensor_fault_episodes,
      {.doc = "times a sensor reading turned bad (NaN, stale or stuck)"});
    v("sensor_fault_time", s.sensor_fault_time, {.unit = "s", .doc = "time sensors were bad, summed over sensors"});
    v("sensor_faults", s.sensor_faults, {.doc = "each flagged sensor: episodes and time bad"});
    v("safe_stop", s.safe_stop, {.doc = "the controller stopped the walk because a sensor stayed bad"});
    std::string safe_stop_reason = s.safe_stop_text();
    v("safe_stop_reason", safe_stop_reason, {.doc = "which sensor failed, how, when; empty without a safe stop"});
    v("safe_stop_time", s.safe_stop_time, {.unit = "s", .doc = "when the safe stop began"});
    v("push_impulse", s.push_impulse,
      {.unit = "N s", .doc = "magnitude of the push impulse applied", .present = s.pushed});
    v("capture_point_bound", s.capture_point_bound,
      {.unit = "N s",
       .doc = "largest impulse an ankle strategy absorbs in the push's direction at its start (m ω0 d)",
       .present = s.pushed});
    v("ik_clamped", s.ik_clamped, {.doc = "control periods with a leg target out of reach"});
    v("joint_limit_hits", s.joint_limit_hits,
      {.doc = "commanded joint angles outside the description's ranges, clamped (one per joint and control period)",
       .present = s.joint_ranges});
    v("desired_range_hits", s.desired_range_hits,
      {.doc = "desired (link) joint angles outside the description's ranges, where the joint's stop holds the link "
              "short of the plan (one per joint and control period)",
       .present = s.joint_ranges});
    v("mujoco_warnings", s.mujoco_warnings, {.doc = "MuJoCo warnings during the walk"});
    v("riccati_residual", s.riccati_residual, {.doc = "relative residual of the preview controller's DARE"});
    v("simulated_time", s.simulated_time, {.unit = "s", .doc = "simulated time"});
  }
};

struct WalkResult {
  WalkMetrics metrics;
  bool k_estimation = false;               ///< control.k_estimation was on: the fields below apply
  humanoid::JointVector k_estimate{};      ///< the final stiffness estimate of each joint [Nm/rad]
  humanoid::JointVector k_relative_std{};  ///< its relative standard deviation sqrt(P)/c, the confidence [-]
  std::array<bool, humanoid::kJoints> k_identified{};  ///< the joints the estimation identifies (leg roll and pitch)
  std::vector<WalkSample> log;  ///< the logged samples (empty when run_walk's `record` took them)
  bool log_streamed = false;    ///< the samples went to run_walk's `record`, not to `log`
  std::vector<Landing> landings;
  walking::WalkPlan plan;
};

/// The loop's parts of the run for any controller: the twin of the run's robot, its plant, the
/// controller's `model` of the robot, the compensators (control.*), the commands clamped into a
/// loaded robot's joint ranges; the stiffness identification's still stances from `plan`'s timing.
loop::LoopSetup walk_loop_setup(const WalkRunParams& params, const walking::RobotModel& model,
                                const walking::WalkPlan& plan);

/// The walk's closed loop: the builtin walking controller on the twin of the run's robot, the
/// compensators as configured, reset to the controller's start pose, the pushes timed against its plan.
struct WalkLoop {
  std::shared_ptr<loop::WalkingControl> control;
  std::unique_ptr<loop::HumanoidLoop> loop;
  std::vector<twin::Push> pushes;  ///< the pushes applied (timed)
};
/// `controller_in_its_place`, when given, drives the twin instead (a user's controller on the same
/// twin, start pose and pushes); the builtin controller is then made only for its plan and pose.
WalkLoop make_walk_loop(const WalkRunParams& params,
                        std::shared_ptr<loop::Controller> controller_in_its_place = nullptr);

/// Runs the walk to its end or to a fall. `progress(t)` is called with the simulated time now and
/// then; `attach(walk)`, once the loop is made and reset and before its first period, may attach
/// further observers to walk.loop (pictures, a replay: evaluation code only; they must live until
/// run_walk returns; each sees every period after the walk's scorer); `record(sample)`, when given,
/// takes each logged sample instead of WalkResult::log (a WalkLogWriter streaming it to disk:
/// memory flat in the walk's length).
WalkResult run_walk(const WalkRunParams& params, const std::function<void(double)>& progress = {},
                    const std::function<void(WalkLoop&)>& attach = {},
                    const std::function<void(const WalkSample&)>& record = {});

}  // namespace flexgait::experiments
