#pragma once
/// \file deformation_compensator.hpp
/// The input and output compensators of the thesis's Fig. 2 (docs/theory/humanoid.md, "The actuator
/// deformation model"), around the walking controller:
///     θ_d → input compensator → θ_cmd → robot → θ_enc → output compensator → θ̂ (real joint angles)
///  - input (eqs. 8-9): θ_cmd = θ_d + τ_g(θ_d) / k, τ_g in the desired pose (pelvis attitude as
///    commanded);
///  - output (eqs. 10-13): θ̂ solves θ_enc − τ_g(θ̂)/k − θ̂ = 0 by Newton's method, τ_g in the
///    estimated pose with the pelvis attitude from the IMU (eq. 1: the robot is a floating base);
///    G = ∂τ_g/∂θ analytic (gravity_torque_derivative, walking::inverse_dynamics_derivative; forward
///    differences only for the gravity loads split about the pose's COM, which couple the legs). The
///    one-step form (12) and the conventional estimate are reported beside it.
/// k is the controller's belief (control.k_joint), apart from the plant's true stiffness.
///
/// control.gear_damping d > 0 (docs/guide/compensation.md): the gear is a Kelvin–Voigt element, τ = k δ + d δ̇, so
/// the deflection is the torque through a first-order lag, δ = τ / (k (1 + (d/k) s)). Backward
/// Euler over the period T, a = T / (T + d/k):  δ_n = a τ_n / k + (1 − a) δ_{n−1}. The input
/// compensator commands θ_d + δ_n; the output compensator solves eq. 11 with it,
///     θ_enc − (1 − a) δ_{n−1} − a τ(θ̂)/k − θ̂ = 0   (the same Newton with k/a and a shifted
/// encoder), and keeps δ_n = θ_enc − θ̂. The first period starts from the static deflection.
///
/// The load (control.load_model, docs/guide/compensation.md): `gravity` is the thesis's static model above
/// (gravity_torque.hpp). `measured`: the output compensator's legs carry their own links' weight
/// and, at the ankle, the wrench the F/T sensor reads (low-passed with control.load_filter_time;
/// the foot below the sensor is in the reading) — τ = g_leg,above(θ) + J_sᵀ w_s, by
/// robot_model_dynamics with the feet's wrenches given; its Newton solves with it. The input
/// compensator, a feed-forward, keeps the plan's loads (the full form): the F/T reading fed into
/// the commands closes a loop of gain ≈ 1 through the gears, and the walks fall. `dynamic`: both
/// add the legs' inertial torques of the planned motion — the plan's joint and pelvis velocities
/// and accelerations (SupportPlan::motion, walking/planned_motion.hpp: the exact derivatives of
/// the plan's IK, without the balance loops) through the recursive Newton–Euler. With
/// control.plan_horizontal_force f > 0 the input side's ground wrench is the plan's own: the whole
/// body's Newton–Euler of the planned motion with no foot loaded gives the wrench (F, N) the ground
/// must supply; its centre of pressure p (the plan's multibody ZMP) is where the split is made, and
/// each stance foot carries share · F (its horizontal part times f) at its centre of pressure and
/// the share of the free moment about the vertical, beside its own Newton–Euler. The weight alone
/// at the reference ZMP (f = 0) leaves out the horizontal force (~15 Nm of the stance hip roll's
/// ~50 Nm at 1 s/step), and the cart-table's force M c̈ at the reference ZMP misplaces the
/// plan's centre of pressure by up to 1.7 cm (rms 0.8 cm at 1 s/step): ~10 Nm too much at the stance
/// hip roll, which made f = 1 overshoot in closed loop.
///
/// control.compensation = robotis | talos: the field's baselines (field_baselines.hpp), input side
/// only. Allocation-free after construction.
#include <array>
#include <string_view>

#include "flexgait/compensation/field_baselines.hpp"
#include "flexgait/compensation/gravity_torque.hpp"
#include "flexgait/compensation/link_angle_newton.hpp"
#include "flexgait/core/config.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/robot/sensors.hpp"
#include "flexgait/walking/planned_motion.hpp"
#include "flexgait/walking/robot_model.hpp"
#include "flexgait/walking/robot_model_dynamics.hpp"

namespace flexgait::compensation {

enum class CompensationMode { kOff, kInput, kOutput, kBoth, kRobotis, kTalos };
constexpr std::array<EnumName<CompensationMode>, 6> enum_names(CompensationMode) {
  return {{{CompensationMode::kOff, "off"},
           {CompensationMode::kInput, "input"},
           {CompensationMode::kOutput, "output"},
           {CompensationMode::kBoth, "both"},
           {CompensationMode::kRobotis, "robotis"},
           {CompensationMode::kTalos, "talos"}}};
}

/// What loads the deformation model's torque comes from (docs/guide/compensation.md).
enum class LoadModel { kGravity, kMeasured, kDynamic };
constexpr std::array<EnumName<LoadModel>, 3> enum_names(LoadModel) {
  return {{{LoadModel::kGravity, "gravity"}, {LoadModel::kMeasured, "measured"}, {LoadModel::kDynamic, "dynamic"}}};
}

/// Online stiffness identification while walking (docs/guide/compensation.md, stiffness_estimator.hpp).
/// calibrate: each leg joint's k from the calibration in the start stance (chain_stiffness_calibration.hpp).
enum class KEstimation { kOff, kOn, kCalibrate };
constexpr std::array<EnumName<KEstimation>, 3> enum_names(KEstimation) {
  return {{{KEstimation::kOff, "off"}, {KEstimation::kOn, "on"}, {KEstimation::kCalibrate, "calibrate"}}};
}

/// The torque the walking identification regresses on (stiffness_estimator.hpp): the compensators' modelled torque
/// (one 1/k per leg joint group), or each servo's torque from its motor current less its rotor's inertia (one 1/k per
/// joint).
enum class KTorque { kModelled, kMeasured };
constexpr std::array<EnumName<KTorque>, 2> enum_names(KTorque) {
  return {{{KTorque::kModelled, "modelled"}, {KTorque::kMeasured, "measured"}}};
}

/// The output compensator's Newton: G formed at each iterate, or reused (link_angle_newton.hpp).
constexpr std::array<EnumName<NewtonJacobian>, 3> enum_names(NewtonJacobian) {
  return {
      {{NewtonJacobian::kEachIteration, "each"}, {NewtonJacobian::kReused, "reused"}, {NewtonJacobian::kKept, "kept"}}};
}

/// About which point the weight is split between the feet (eqs. 5-6): the COM of the pose (the
/// thesis), or the controller's reference ZMP (where the ground force acts in a dynamic gait; it
/// moves onto the stance sole by the end of double support, so the split is continuous at lift-off).
enum class WeightSplit { kCom, kZmpReference };
constexpr std::array<EnumName<WeightSplit>, 2> enum_names(WeightSplit) {
  return {{{WeightSplit::kCom, "com"}, {WeightSplit::kZmpReference, "zmp"}}};
}

/// What the walking controller plans at this instant.
struct SupportPlan {
  std::array<bool, 2> swinging{};                     ///< which feet swing
  std::array<walking::Pose, 2> soles;                 ///< planned sole poses (world)
  Eigen::Vector2d zmp_ref = Eigen::Vector2d::Zero();  ///< reference ZMP (world) [m]
  walking::Pose pelvis;                               ///< commanded pelvis pose (world; load_model dynamic)
  double single_support_phase = -1;  ///< s ∈ [0, 1] from lift-off to touchdown, −1 outside single support (robotis)
  walking::PlannedMotion motion;     ///< the plan's joint and pelvis motion (load_model dynamic; not valid: at rest)
};

/// control.load_filter_time of the static model (no gear damping believed): the 1 s walk's best estimate there
/// (20 % of the deflection against 28 % at 0.02 s) [s].
inline constexpr double kStaticLoadFilterTime = 0.1;
/// control.load_filter_time with the gears' lag believed: the F/T low-pass can be short [s].
inline constexpr double kLagLoadFilterTime = 0.02;

/// The members' defaults are the thesis's static model (the keys' schema defaults); `humanoid walk` resolves the
/// compensation keys left unset to the default case both-dynamic-horizontal-lag when its own compensators run
/// (experiments::walk_run_from_config; docs/guide/compensation.md, "The default case").
struct CompensationParams {
  CompensationMode mode = CompensationMode::kBoth;
  GravityForm gravity = GravityForm::kFull;
  WeightSplit split = WeightSplit::kZmpReference;
  double k_joint = 1000.0;    ///< the controller's belief of the gears' stiffness [Nm/rad], times k_scale per joint
  double gear_damping = 0.0;  ///< the belief of the gears' damping d [Nm s/rad]; 0: the static model (the thesis)
  humanoid::JointVector k_scale = [] {  ///< factor on k_joint for each joint (not a key)
    humanoid::JointVector ones;
    ones.fill(1.0);
    return ones;
  }();
  LoadModel load_model = LoadModel::kGravity;
  double load_filter_time = kStaticLoadFilterTime;  ///< time constant of the F/T low-pass [s]
  /// dynamic: the share f of the plan's horizontal ground force M c̈ (the cart-table's c̈) that the
  /// input compensator's stance feet carry beside the weight [-]; 1: the whole (the physics), 0: the weight alone.
  double plan_horizontal_force = 0.0;
  KEstimation k_estimation = KEstimation::kOff;
  /// The controller's kinematic estimators (the dcm COM estimate, the tilt observer) read the
  /// encoders plus the output compensator's last deflection estimate θ̂ − θ_enc (spec (1): the
  /// estimated joint angles and the IMU give the real pose); false: the encoders alone (the schema's default;
  /// humanoid walk resolves it true when its output compensator runs).
  bool compensated_feedback = false;
  double k_estimation_memory = 5.0;       ///< forgetting time constant: λ = e^{−T/memory} [s]
  double k_estimation_min_torque = 5.0;   ///< smallest |regressor| a sample needs [Nm]
  double k_estimation_noise = 0.002;      ///< standard deviation of the foot-tilt observation [rad]
  double k_estimation_confidence = 0.05;  ///< relative standard deviation below which the compensators use the estimate
  KTorque k_estimation_torque = KTorque::kModelled;  ///< k_estimation on: the regressor's torque
  bool k_estimation_per_joint = false;               ///< k_estimation on: one 1/k per joint (else per leg joint group)
  double rotor_inertia = 0.8;  ///< the belief of each rotor's inertia at the gear's output, J_m [kg m^2]
  /// calibrate: the window is split into this many passes, each fitted afresh with the torques modelled (the estimated
  /// pose, the gears' lag) at the previous pass's estimate [-]
  int k_calibration_passes = 1;
  /// k_estimation: the belief of the soles' rotational stiffness about the sole's x (roll) and y (pitch) axes, the foot
  /// pad and the floor contact in series with the ankle gears [Nm/rad]; 0: rigid soles
  double sole_stiffness_roll = 0.0;
  double sole_stiffness_pitch = 0.0;
  /// the gyro's attitude pulled to the controller's with this time constant; 0: the controller's [s]. 1000 s: the
  /// gyro's over a walk (the controller's attitude errs slowly, ~0.01–0.02 rad, as the deflections do).
  double k_estimation_attitude_time = 1000.0;
  bool k_estimation_stance_offset =
      false;  ///< each stance's tilt has an unknown offset of its own (estimated beside 1/k)
  double k_estimation_gyro_rest =
      0.0;                          ///< the gyro is calibrated over this long at rest before the COM moves; 0: none [s]
  double robotis_hip_roll = 0.017;  ///< ROBOTIS's stance hip roll feed-forward at mid single support [rad] (1°)
  double talos_cutoff = 1.0;        ///< TALOS's hip torque low-pass [Hz]
  double talos_limit = 0.01;        ///< TALOS's hip roll correction saturation [rad]
  NewtonSettings newton;
  double fd_step = 1e-6;  ///< forward-difference step for G = ∂τ_g/∂θ with the gravity loads split about the COM [rad]

  /// The belief of each gear's stiffness, k_joint × k_scale [Nm/rad].
  humanoid::JointVector stiffness() const { return humanoid::scaled(k_joint, k_scale); }

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("control.compensation", s.mode,
      {.doc = "actuator deformation compensation: none, the input compensator (eqs. 8-9), the output "
              "compensator (eqs. 10-13), both, or a field baseline: robotis (THORMANG3's fixed stance hip roll "
              "feed-forward) or talos (TALOS's stance hip roll tau/K, low-passed, saturated)"});
    v("control.gravity_model", s.gravity,
      {.doc = "gravity torque: thesis = J^T F only (eq. 4), full = the legs' own weight too"});
    v("control.weight_split", s.split,
      {.doc = "split of the weight between the feet (eqs. 5-6) about: com = the pose's centre of mass (the "
              "thesis), zmp = the reference ZMP (continuous at lift-off in a dynamic gait)"});
    v("control.load_model", s.load_model,
      {.doc = "the compensators' load: gravity = the weight split (the thesis), measured = the output compensator "
              "reads each foot's ankle F/T wrench (plus the legs' own weight), dynamic = measured plus, in both "
              "compensators, the legs' inertial torques of the planned motion (left unset, humanoid walk's own "
              "compensators take dynamic: the default case both-dynamic-horizontal-lag)"});
    v("control.load_filter_time", s.load_filter_time,
      {.unit = "s",
       .doc = "measured/dynamic: time constant of the F/T low-pass (0: none; left unset with the gears' damping "
              "believed, humanoid walk takes 0.02)",
       .bounds = closed(0, 1)});
    v("control.plan_horizontal_force", s.plan_horizontal_force,
      {.doc = "dynamic: share of the plan's horizontal ground force in the input compensator's foot loads; f > 0: "
              "the plan's whole ground wrench (the whole body's Newton-Euler of the planned motion) at its own "
              "centre of pressure, its horizontal force times f; 0 = the weight alone at the reference ZMP; 1 = the "
              "physics (left unset with dynamic loads, humanoid walk takes 1)",
       .bounds = closed(0, 1)});
    v("control.compensated_feedback", s.compensated_feedback,
      {.doc = "the controller's kinematic estimators (the dcm COM estimate, the tilt observer) read the encoders "
              "plus the output compensator's last deflection estimate (needs compensation output or both; left unset, "
              "humanoid walk's own output compensator takes true)"});
    v("control.k_estimation", s.k_estimation,
      {.doc = "online stiffness identification while walking: on = estimate 1/k of each leg's roll and pitch joint "
              "groups by RLS from the stance foot's tilt seen through the encoders and the IMU; the compensators "
              "use a group's estimate once confident; calibrate = estimate 1/k of each leg roll and pitch joint in the "
              "start stance's calibration (calibration.*) from the two flat soles' relative tilt through the encoders, "
              "used once confident and kept while walking"});
    v("control.k_estimation_torque", s.k_estimation_torque,
      {.doc = "k_estimation on: the torque the stance foot's tilt is regressed on: modelled = the output "
              "compensator's, measured = each servo's torque from its motor current less its rotor's inertia times "
              "the encoder's acceleration"});
    v("control.k_estimation_per_joint", s.k_estimation_per_joint,
      {.doc = "k_estimation on: one 1/k per leg joint, not per leg joint group (roll, pitch); needs "
              "control.k_estimation_torque measured (the parallel joints' modelled torques move together) and an "
              "attitude good to ~0.1 mrad over the walk"});
    v("control.rotor_inertia", s.rotor_inertia,
      {.unit = "kg m^2",
       .doc = "k_estimation_torque measured: the belief of each rotor's inertia at the gear's output (left unset, "
              "humanoid walk takes plant.rotor_inertia)",
       .bounds = closed(0, 100)});
    v("control.k_estimation_memory", s.k_estimation_memory,
      {.unit = "s",
       .doc = "k_estimation on: forgetting time constant of the RLS (calibrate: none)",
       .bounds = closed(0.01, 1e6)});
    v("control.k_estimation_min_torque", s.k_estimation_min_torque,
      {.unit = "Nm",
       .doc = "k_estimation: a sample is used when its torque regressor is at least this",
       .bounds = closed(0, 1e4)});
    v("control.k_estimation_noise", s.k_estimation_noise,
      {.unit = "rad",
       .doc = "k_estimation: standard deviation of the foot-tilt observation",
       .bounds = closed(1e-9, 1)});
    v("control.k_estimation_confidence", s.k_estimation_confidence,
      {.doc = "k_estimation: the compensators use a group's (or joint's) estimate once its relative standard deviation "
              "is at most this",
       .bounds = closed(1e-6, 1)});
    v("control.k_calibration_passes", s.k_calibration_passes,
      {.doc = "k_estimation calibrate: the calibration window is split into this many passes; each fits afresh, its "
              "torques modelled (the estimated pose, the gears' lag d/k) with the previous pass's estimate",
       .bounds = closed(1, 10)});
    v("control.sole_stiffness_roll", s.sole_stiffness_roll,
      {.unit = "Nm/rad",
       .doc = "k_estimation: the belief of each sole's roll stiffness (pad and floor contact, in series with the ankle "
              "roll gear), taken out of the soles' tilt; 0 = rigid soles",
       .bounds = closed(0, 1e9)});
    v("control.sole_stiffness_pitch", s.sole_stiffness_pitch,
      {.unit = "Nm/rad",
       .doc =
           "k_estimation: the belief of each sole's pitch stiffness (pad and floor contact, in series with the ankle "
           "pitch gear), taken out of the soles' tilt; 0 = rigid soles",
       .bounds = closed(0, 1e9)});
    v("control.k_estimation_attitude_time", s.k_estimation_attitude_time,
      {.unit = "s",
       .doc = "k_estimation: the pelvis attitude the identification uses is the gyro's turn pulled towards the "
              "controller's estimate with this time constant (0 = the controller's estimate itself; the default, "
              "1000 s, is the gyro's over a walk)",
       .bounds = closed(0, 1e6)});
    v("control.k_estimation_stance_offset", s.k_estimation_stance_offset,
      {.doc = "k_estimation: each stance foot's tilt carries an unknown constant offset, estimated beside 1/k and "
              "started anew at each stance (the attitude's slow errors, the gyro's drift, cancel; only the tilt's "
              "changes within a stance inform 1/k)"});
    v("control.k_estimation_gyro_rest", s.k_estimation_gyro_rest,
      {.unit = "s",
       .doc = "k_estimation: the gyro is calibrated over this long at rest before the COM starts to move (its bias: "
              "the gyro's turn less the pelvis's turn through the legs; at most walk.start_time - walk.preview_time); "
              "no samples before it; 0 = no calibration",
       .bounds = closed(0, 100)});
    v("control.robotis_hip_roll", s.robotis_hip_roll,
      {.unit = "rad", .doc = "robotis: stance hip roll feed-forward at mid single support", .bounds = closed(0, 0.2)});
    v("control.talos_cutoff", s.talos_cutoff,
      {.unit = "Hz", .doc = "talos: hip roll torque low-pass cut-off", .bounds = closed(0.01, 100)});
    v("control.talos_limit", s.talos_limit,
      {.unit = "rad", .doc = "talos: hip roll correction saturation", .bounds = closed(0, 0.2)});
    v("control.k_joint", s.k_joint,
      {.unit = "Nm/rad", .doc = "the controller's belief of the gears' stiffness", .bounds = closed(1, 1e7)});
    v("control.gear_damping", s.gear_damping,
      {.unit = "Nm s/rad",
       .doc = "the belief of the gears' damping d (Kelvin-Voigt, tau = k delta + d delta'): the deflection lags the "
              "torque by d/k in both compensators; 0 = the static model delta = tau/k (the thesis); left unset, "
              "humanoid walk's own compensators take plant.gear_damping",
       .bounds = closed(0, 1e5)});
    v("control.newton_max_iterations", s.newton.max_iterations,
      {.doc = "output compensator: Newton steps at most", .bounds = closed(1, 100)});
    v("control.newton_tolerance", s.newton.tolerance,
      {.unit = "rad", .doc = "output compensator: converged when |N(theta)| <= this", .bounds = closed(1e-15, 1e-3)});
    v("control.newton_jacobian", s.newton.jacobian,
      {.doc = "output compensator: G = dtau/dtheta formed at each Newton iterate (each), or reused while a step cuts "
              "the residual a hundredfold (the chord method): formed afresh at each period's first step (reused), or "
              "carried from period to period, Newton starting from the deflection extrapolated from the last three "
              "periods, and formed again when a step cuts the residual less than a thousandfold or the supporting "
              "feet change (kept)"});
    v("control.newton_predicted_convergence", s.newton.predicted_convergence,
      {.doc = "output compensator, newton_jacobian = kept: a step whose residual, predicted as the kept factor's "
              "measured contraction rate times the residual before it, meets newton_tolerance ends the solve without "
              "evaluating the torque there (CVODE's test; at most 4 periods in a row, the next measures the rate "
              "again); false: every step evaluated"});
  }

  bool input() const { return mode == CompensationMode::kInput || mode == CompensationMode::kBoth; }
  bool output() const { return mode == CompensationMode::kOutput || mode == CompensationMode::kBoth; }
};

/// Keys control.compensation, control.gravity_model, control.weight_split, control.load_model,
/// control.load_filter_time, control.robotis_hip_roll, control.talos_*, control.k_joint, control.newton_*.
inline Schema compensation_schema() {
  return schema_of<CompensationParams>();
}
inline CompensationParams compensation_from_config(const Config& config) {
  return record_from_config<CompensationParams>(config);
}

inline constexpr int kLegDofs = 2 * humanoid::kLegJoints;  ///< the unknowns of the output compensator
using LegVector = Eigen::Matrix<double, kLegDofs, 1>;      ///< left leg then right leg, kinematic order

struct OutputEstimate {
  humanoid::JointVector newton{};    ///< θ̂ by Newton (eq. 11; the fallback if not converged) [rad]
  humanoid::JointVector one_step{};  ///< eq. 12 [rad] (newton_jacobian = kept: NaN in the legs unless estimate_forms)
  humanoid::JointVector
      per_joint{};  ///< eq. 12 joint by joint, the thesis's scalar form (G's diagonal) [rad] (likewise)
  humanoid::JointVector conventional{};    ///< θ_enc − τ_g(θ_enc)/k [rad] (likewise)
  humanoid::JointVector gravity_torque{};  ///< τ_g(θ̂) [Nm]
  int iterations = 0;
  double residual = 0;  ///< ||N(θ̂)||_inf [rad] (predicted: the chord's prediction of it)
  bool converged = false;
  bool predicted = false;  ///< Newton's last step was not evaluated (its residual predicted; NewtonSettings)
};

class DeformationCompensator {
 public:
  /// \param period control period T [s] (the filters)
  DeformationCompensator(const walking::RobotModel& model, const CompensationParams& params, double period = 0.004);

  /// load_model measured/dynamic: this period's ankle F/T readings (the leg's wrench on each foot,
  /// foot frame, at the foot origin), low-passed. Call once per period before input and output.
  void sense(const std::array<humanoid::ForceTorque, 2>& ft);

  /// Eqs. 8-9: motor commands for the desired joint angles and the commanded pelvis attitude
  /// `pelvis_R` (world). With input compensation off: θ_d itself; robotis, talos: θ_d with their
  /// hip roll offsets. Call once per period (talos's filter).
  const humanoid::JointVector& input(const humanoid::JointVector& desired, const walking::Matrix3d& pelvis_R,
                                     const SupportPlan& support);
  /// τ_g(θ_d) of the last `input` call [Nm].
  const humanoid::JointVector& input_torque() const { return input_torque_; }

  /// Eqs. 10-13: the real joint angles from the encoders, the IMU's attitude and the support.
  /// The one-step and per-joint forms (eq. 12, for comparison) are formed with control.newton_jacobian = kept
  /// only once asked for by estimate_forms; Newton's estimate does not depend on it.
  const OutputEstimate& output(const humanoid::JointVector& encoder, const walking::Matrix3d& imu_R,
                               const SupportPlan& support);

  /// τ_g at joint angles q, pelvis attitude R (world), with this compensator's split [Nm].
  const humanoid::JointVector& torque(const humanoid::JointVector& q, const walking::Matrix3d& R,
                                      const SupportPlan& support);

  /// Whether `output` forms the conventional, one-step and per-joint estimates (a study comparing them asks; off by
  /// default; with newton_jacobian = kept they are NaN otherwise).
  void estimate_forms(bool on) { forms_ = on; }
  const CompensationParams& params() const { return params_; }
  /// Replaces the belief of the gears' stiffness (control.k_estimation: the confident estimate) [Nm/rad], > 0.
  void set_stiffness(const humanoid::JointVector& k) { stiffness_ = k; }
  const humanoid::JointVector& stiffness() const { return stiffness_; }

 private:
  /// The Kelvin–Voigt lag's weight of this period's torque for joint j, a = T / (T + d/k_j) (1 without damping).
  double lag_weight(int j) const;
  /// control.plan_horizontal_force > 0, the input side: the plan's ground wrench (plan_ground_, about its centre of
  /// pressure), each foot's own Newton–Euler (foot_need_) and the split about that centre (plan_loads_), for the pose
  /// in data_; false (nothing set) if the plan pushes nothing on the ground.
  bool plan_ground_wrench(const SupportPlan& support);
  /// With kZmpReference: the loads about the plan's reference ZMP (the same for every pose).
  void split_by_plan(const SupportPlan& support);
  /// The field baselines' hip roll offsets on command_.
  void apply_baseline(const humanoid::JointVector& desired, const walking::Matrix3d& pelvis_R,
                      const SupportPlan& support);
  /// τ_g with the loads of the last split_by_plan (kZmpReference) or of this pose (kCom). `first` =
  /// walking::kFirstLegBody after a whole evaluation with the same R and support whose q differed in the legs alone:
  /// the legs' bodies alone are recomputed (the same numbers; the pelvis's and the chest's kept).
  const humanoid::JointVector& torque_at(const humanoid::JointVector& q, const walking::Matrix3d& R,
                                         const SupportPlan& support, int first = 0);

  walking::RobotModel model_;
  CompensationParams params_;
  double period_;
  double filter_gain_;               ///< 1 − e^{−T/τ} of control.load_filter_time
  humanoid::JointVector stiffness_;  ///< params_.stiffness(), computed once [Nm/rad]
  // control.gear_damping: the deflections of the last period (Kelvin–Voigt lag; the output side's: deflection_[0])
  bool input_lagged_ = false, output_lagged_ = false;  ///< a previous deflection exists
  humanoid::JointVector input_deflection_{};
  walking::RobotModelData data_;
  FootLoads plan_loads_;                      ///< the split about the reference ZMP (kZmpReference), from the plan
  walking::Wrench plan_ground_;               ///< the plan's ground wrench, about its centre of pressure (world)
  std::array<walking::Wrench, 2> foot_need_;  ///< each foot's own Newton–Euler wrench of the plan, at its origin
  humanoid::JointVector q_{}, tau_{}, command_{}, input_torque_{};
  OutputEstimate estimate_;
  bool forms_ = false;  ///< estimate_forms
  /// NewtonJacobian::kKept: the factorisation of K + G carried from period to period, and what it was formed for
  /// (forgotten when the supporting feet or G's coupling change).
  LinkAngleFactor<kLegDofs> kept_;
  std::array<bool, 2> kept_swinging_{};
  bool kept_coupled_ = false;
  /// The output side's θ_enc − θ̂ of the last three periods, newest first [rad] (the gears' lag reads the last; Newton
  /// starts from their extrapolation), and how many of them, newest first, are converged estimates since the
  /// factorisation was formed for this support (0-3).
  std::array<LegVector, 3> deflection_{LegVector::Zero(), LegVector::Zero(), LegVector::Zero()};
  int extrapolable_ = 0;
  // load_model measured/dynamic:
  bool sensed_ = false;                  ///< a reading has arrived (the filter starts from it)
  bool planned_cop_ = false;             ///< evaluating for the input side: measured force at the plan's CoP
  std::array<walking::Wrench, 2> ft_{};  ///< low-passed F/T wrenches, foot frame
  /// This period's reading of each foot was finite (a failed sensor's NaN: the foot's load is the plan's split
  /// meanwhile, and the filter keeps its state).
  std::array<bool, 2> ft_usable_{};
  walking::FootWrenches feet_;  ///< the same in the world for the pose being evaluated
  walking::RobotDynamicsData dynamics_;
  // baselines
  std::array<TalosHipRoll, 2> talos_;
};

}  // namespace flexgait::compensation
