#pragma once
/// \file walking_controller.hpp
/// The walking controller of the thesis's Fig. 2, without the compensators (docs/theory/humanoid.md,
/// "The walking controller"): footsteps → ZMP reference → COM by preview control → balance
/// controller → swing foot → analytic leg IK → joint commands.
///
/// It is plant-agnostic: `update` reads SensorReadings (encoders, F/T, IMU) and the time and
/// returns motor position commands; it sees nothing of the simulator. Everything is allocated
/// at construction (the ZMP reference of the whole plan, the preview gains); `update` allocates
/// nothing.
///
/// Balance controller (ROBOTIS-style PD loops with clamps, gains in BalanceParams):
///  - pelvis attitude: the IMU's roll/pitch and rates tilt the pelvis command the other way,
///    Δφ = −sat(k_p φ + k_d ω);
///  - foot torque compliance: each loaded foot's torque about its sole centre, from its F/T
///    sensor, rotates its command, δ̇ = τ / D − δ / T (Kajita et al. 2010), clamped;
///  - foot force control: each foot's vertical load against its share of the weight (from the
///    ZMP reference between the feet) raises or lowers it (Kajita et al. 2010);
///  - ZMP feedback: the commanded COM is shifted by a clamped PI on (reference − measured ZMP),
///    so that the gear deflections' shift of the real COM is taken out.
/// The measured ZMP combines both feet's centres of pressure from the F/T sensors.
///
/// balance.mode = dcm replaces the foot torque compliance and the ZMP feedback by the DCM
/// stabiliser (the sway damping stays: without it the twin's lateral rocking grows and it falls
/// before the first step) (dcm_stabiliser.hpp, eq. D2): the COM is estimated by kinematics —
/// encoders, the estimated pelvis roll and pitch, the plan's heading, anchored at the loaded soles'
/// planned places (weighted by their F/T loads), its mean pulled onto the measured ZMP's with
/// balance.com_bias_time (the COM's and the ZMP's means agree over any stretch the robot ends as
/// it began; the encoders miss the gear deflections' centimetres) — its velocity by a filtered difference; the ZMP
/// command from ξ = c + ċ/ω against the plan's ξ_ref is distributed to the feet (load shares
/// along the line between the soles — by the command while standing where the robot began, by
/// the ZMP reference once the plan steps (load_split_point) — the remainder as a centre of
/// pressure under each loaded sole, clamped to the sole) and each loaded foot's rotation follows its torque error about
/// the sole centre with the CoP admittance A (Caron et al. 2019): δ̇ = A (τ − τ_d), clamped.
///
/// Sensors (docs/guide/humanoid.md, "Sensors, faults and the attitude estimate"): every reading passes SensorHealth
/// first (NaN, stale, stuck →
/// the last good value is held, for at most health.hold_time). The pelvis attitude comes from
/// the AttitudeEstimator (Mahony filter on gyro and accelerometer, with the planned COM
/// acceleration taken out), or from the IMU's AHRS output (estimator.source = ahrs). While a
/// sensor is held, the loops it feeds stop integrating (F/T: foot torque, foot force and ZMP
/// feedback; gyro: the attitude estimate and the sway damping hold). A sensor the controller
/// uses that stays bad beyond the hold time has failed: its loops fade out (health.fade_time) and
/// the walk stops safely (health.safe_stop) — the plan is cut at the next double support: a
/// swinging foot completes its step, a step not yet lifted is dropped, the ZMP reference blends
/// to the middle of the feet where they stand over one double-support time, and the robot stands
/// there until the planned end of the walk.
#include <array>
#include <vector>

#include "flexgait/robot/joints.hpp"
#include "flexgait/robot/robot_params.hpp"
#include "flexgait/robot/sensors.hpp"
#include "flexgait/walking/attitude_estimator.hpp"
#include "flexgait/walking/dcm_stabiliser.hpp"
#include "flexgait/walking/foot_wrench.hpp"
#include "flexgait/walking/footstep_plan.hpp"
#include "flexgait/walking/landing_adaptation.hpp"
#include "flexgait/walking/leg_kinematics.hpp"
#include "flexgait/walking/planned_motion.hpp"
#include "flexgait/walking/preview_control.hpp"
#include "flexgait/walking/robot_model.hpp"
#include "flexgait/walking/sensor_health.hpp"
#include "flexgait/walking/step_adjustment.hpp"
#include "flexgait/walking/tilt_observer.hpp"
#include "flexgait/walking/walk_params.hpp"

namespace flexgait::walking {

/// What the controller decided in its last update (for logs and evaluation).
struct ControllerStatus {
  double t = 0;                                            ///< time of the update [s]
  int step = -1;                                           ///< current step (see FeetTarget::step)
  Eigen::Vector2d zmp_ref = Eigen::Vector2d::Zero();       ///< reference ZMP at t [m]
  Eigen::Vector2d zmp_measured = Eigen::Vector2d::Zero();  ///< from the F/T sensors [m]
  bool zmp_valid = false;                                  ///< enough normal force to define it
  Eigen::Vector2d com_ref = Eigen::Vector2d::Zero();       ///< planned COM at t + T [m]
  Pose pelvis;                                             ///< commanded pelvis pose (with the balance correction)
  double imu_roll = 0, imu_pitch = 0;                      ///< estimated pelvis attitude [rad]
  double roll_correction = 0, pitch_correction = 0;        ///< balance: pelvis counter-tilt [rad]
  Eigen::Vector2d com_shift = Eigen::Vector2d::Zero();     ///< balance: COM shift of the ZMP feedback [m]
  std::array<Pose, 2> sole;                                ///< planned sole poses (world)
  std::array<bool, 2> swinging{};                          ///< which feet the plan swings now
  std::array<bool, 2> contact{};                           ///< foot loaded above balance.contact_force
  std::array<Eigen::Vector2d, 2> foot_rotation{Eigen::Vector2d::Zero(),
                                               Eigen::Vector2d::Zero()};  ///< balance: foot roll, pitch offsets [rad]
  std::array<double, 2> foot_force{};  ///< vertical ground force on each foot (F/T) [N]
  std::array<double, 2> foot_lift{};   ///< balance: foot height offsets of the force control [m]
  std::array<IkStatus, 2> ik{IkStatus::kOk, IkStatus::kOk};
  humanoid::JointVector desired{};  ///< joint angles from the IK (θ_d) [rad]
  unsigned sensor_flags = 0;        ///< bit i: sensor i (humanoid::SensorId) bad this period
  bool safe_stop = false;           ///< the walk is being stopped for a failed sensor
  // balance.mode = dcm:
  Eigen::Vector2d com_estimate = Eigen::Vector2d::Zero();  ///< COM by kinematics [m]
  Eigen::Vector2d dcm = Eigen::Vector2d::Zero();           ///< ξ of the estimate [m]
  Eigen::Vector2d dcm_ref = Eigen::Vector2d::Zero();       ///< ξ of the plan [m]
  Eigen::Vector2d zmp_command = Eigen::Vector2d::Zero();   ///< the stabiliser's ZMP command (eq. D2) [m]
  Eigen::Vector2d step_shift = Eigen::Vector2d::Zero();    ///< step adjustment: the last shift of a landing [m]
  PlannedMotion motion;  ///< the plan's joint and pelvis motion at the commanded pose (set_plan_motion)
};

/// Why and when the controller stopped the walk.
struct SafeStop {
  bool active = false;
  humanoid::SensorId sensor = humanoid::kSensors;  ///< the sensor that failed (kSensors: none)
  SignalFault fault = SignalFault::kOk;            ///< its fault when it failed
  double t = 0;                                    ///< [s]
  int steps_kept = 0;                              ///< steps of the plan still taken
};

class WalkingController {
 public:
  /// \param robot the controller's belief of the robot (its own model)
  /// \param period control period T [s]
  WalkingController(const humanoid::RobotParams& robot, const WalkParams& walk, const BalanceParams& balance,
                    double period, const EstimatorParams& estimator = {}, const HealthParams& health = {});
  /// \param model the controller's model of any robot (e.g. make_robot_model of a loaded description)
  WalkingController(const RobotModel& model, const WalkParams& walk, const BalanceParams& balance, double period,
                    const EstimatorParams& estimator = {}, const HealthParams& health = {});

  /// The standing pose the walk starts from (joint angles) [rad].
  const humanoid::JointVector& initial_pose() const { return initial_pose_; }
  /// One control period: sensors at time t in, motor position commands out [rad].
  const humanoid::JointVector& update(const humanoid::SensorReadings& sensors, double t);
  /// Tells the controller the floor's height(x, y) [m] at its footprints before the walk
  /// (terrain.known_heights): the soles are placed there and the pelvis keeps walk.pelvis_height
  /// above the mean of the feet's floor heights. Unknown (the default), the floor is z = 0.
  template <class Height>
  void know_floor(const Height& height) {
    set_footprint_heights(plan_, height);
  }

  const ControllerStatus& status() const { return status_; }
  /// The motor commands sent to the servos after this update (the deformation compensators'
  /// output, or update()'s own) [rad]: the next update's health check expects an encoder to move
  /// when its command moved (a stuck encoder), and reads a bad encoder as its command.
  void sent(const humanoid::JointVector& command) { health_.set_command(command); }
  /// Also compute the plan's joint and pelvis velocities and accelerations (status().motion;
  /// control.load_model = dynamic): three more poses' IK per update.
  void set_plan_motion(bool on) { plan_motion_ = on; }
  /// The plan being walked (cut short by a safe stop).
  const WalkPlan& plan() const { return plan_; }
  /// The readings of the last update as the controller used them (bad values held).
  const humanoid::SensorReadings& sensors() const { return health_.clean(); }
  const SensorHealth& health() const { return health_; }
  /// The pelvis attitude the controller used in the last update (pelvis to world).
  const Matrix3d& attitude() const { return attitude_; }
  const SafeStop& safe_stop() const { return safe_stop_; }
  const PreviewGains& gains() const { return gains_; }
  const RobotModel& model() const { return model_; }
  double period() const { return period_; }

 private:
  /// Pelvis pose and joint angles that put the soles at `soles` and the COM's xy at `com`
  /// (a fixed-point iteration on the pelvis position through the model's COM). With `kinematics`, the pose's
  /// kinematics in data_ (only the start pose's are read: its COM height).
  void solve_pose(const Eigen::Vector2d& com, const std::array<Pose, 2>& soles, const Matrix3d& pelvis_R,
                  int iterations, bool kinematics = false);
  /// The plan's ZMP reference at t plus the stiffness calibration's COM offsets (calibration_motion.hpp) [m].
  Eigen::Vector2d planned_zmp(double t) const;
  void measure_zmp(const humanoid::SensorReadings& sensors);
  /// Where the load split between the feet follows (foot force control and the dcm distribution) [m].
  Eigen::Vector2d load_split_point() const;
  /// Foot force control: updates foot_lift_ from the feet's loads against their shares.
  /// (the loads' shares follow `zmp` between the soles)
  void update_foot_lift(const FeetTarget& feet, const Eigen::Vector2d& zmp);
  /// The DCM stabiliser: COM estimate, ZMP command, foot rotations toward its centres of pressure.
  void dcm_balance(const humanoid::SensorReadings& sensors, const FeetTarget& feet, double yaw);
  /// estimator.source tilt: one period of the tilt observer (tilt_observer.hpp) on the gyro (less
  /// the Mahony filter's bias), the accelerometer (nullptr: bad) and the loaded soles' kinematics.
  void update_tilt(const humanoid::SensorReadings& sensors, const Vector3d& gyro, const Vector3d* accel);
  /// Step adjustment (step_adjustment.hpp): while walking, moves the current step's landing and
  /// the later footsteps once per step, and ends an adjusted step whose swing foot meets the floor
  /// early there (S3); standing (a plan without steps), inserts one recovery step. Rewrites the ZMP
  /// reference from sample k on, so the preview controller replans.
  void adjust_steps(double t, std::size_t k, const FeetTarget& feet);
  /// Standing step adjustment, (C0): the capture point has left the feet; both stay down, the
  /// centre of pressure at the feet's edge nearest the DCM, until the stance leg can carry the load
  /// (capture_lift_due). Rewrites the ZMP reference from sample k.
  void begin_capture_transfer(double t, std::size_t k, int swing, double omega);
  /// (C0) ends: the stance leg alone could carry the measured ground force through the capture
  /// step's centre of pressure within balance.capture_torque_limit (stance_load.hpp (L1)), or the
  /// transfer has lasted balance.recovery_step_time.
  bool capture_lift_due(double t);
  /// (C1): the point of the `stance` sole, 2 cm inside its edges, nearest the DCM `xi` (world) [m].
  Eigen::Vector2d capture_cop(int stance, const Eigen::Vector2d& xi) const;
  /// (C0) for soles that are not rectangles: the point of the hull of both soles (each 2 cm inside
  /// its edges) where they stand nearest `xi` (world) [m]; in transfer_points_ / transfer_hull_.
  Eigen::Vector2d nearest_in_capture_soles(const Eigen::Vector2d& xi);
  /// The capture step of foot capture_.swing lasting T [s] from now (C1–C3 in the definition), its
  /// settling [s]; rewrites the ZMP reference from sample k.
  void begin_capture_step(double t, std::size_t k, double omega, double T, double settle, const StepLimits& limits);
  /// During a capture step: the cart follows the inverted pendulum about its centre of pressure.
  void propagate_capture(double t);
  /// ZMP feedback: advances its filter and integral, returns the COM shift [m].
  Eigen::Vector2d zmp_feedback();
  /// Health of the readings, escalation to a safe stop and the attitude estimate.
  void check_sensors(const humanoid::SensorReadings& sensors, double t, std::size_t k);
  /// Cuts the plan at the next double support and rewrites the ZMP reference from sample k on.
  void begin_safe_stop(double t, std::size_t k);

  WalkParams walk_;
  BalanceParams balance_;
  double period_;
  RobotModel model_;
  RobotModelData data_;
  WalkPlan plan_;
  PreviewGains gains_;
  std::vector<double> ref_x_, ref_y_;  ///< ZMP reference sampled at k T, padded by the horizon
  std::array<CartTable, 2> cart_;
  Pose pelvis_;
  humanoid::JointVector desired_{}, initial_pose_{};
  std::array<Eigen::Vector2d, 2> foot_rotation_{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  std::array<double, 2> foot_lift_{};
  LandingAdaptation landing_;                  ///< each sole's tilt adapted to the floor at touchdown
  std::array<FootContact, 2> foot_contact_{};  ///< each foot's ground wrench from its F/T sensor
  DcmStabiliser dcm_;
  RobotModelData estimate_data_;                            ///< the COM estimate's kinematics
  Eigen::Vector2d com_velocity_ = Eigen::Vector2d::Zero();  ///< estimated, low-passed [m/s]
  Eigen::Vector2d com_bias_ = Eigen::Vector2d::Zero();      ///< correction of the kinematic COM [m]
  bool com_estimated_ = false;
  Eigen::Vector2d gyro_filtered_ = Eigen::Vector2d::Zero();  ///< IMU roll/pitch rate, low-passed [rad/s]
  Eigen::Vector2d zmp_integral_ = Eigen::Vector2d::Zero();   ///< ZMP feedback's integral [m]
  std::array<Eigen::Vector2d, 2> zmp_filtered_{Eigen::Vector2d::Zero(),
                                               Eigen::Vector2d::Zero()};  ///< the measured ZMP, low-passed [m]
  EstimatorParams estimator_params_;
  AttitudeEstimator estimator_;
  TiltObserver tilt_;         ///< estimator.source tilt
  RobotModelData tilt_data_;  ///< its leg kinematics
  std::array<Vector3d, 2> anchor_{Vector3d::Zero(),
                                  Vector3d::Zero()};  ///< each sole centre, pelvis frame, last period [m]
  bool anchors_known_ = false;
  SensorHealth health_;
  Matrix3d attitude_ = Matrix3d::Identity();
  bool ft_live_ = true;                ///< both F/T sensors good this period
  bool gyro_live_ = true;              ///< the gyro good this period
  double ft_fade_ = 1, imu_fade_ = 1;  ///< 1, fading to 0 after a failure of the F/T or IMU
  bool ft_failed_ = false, imu_failed_ = false;
  SafeStop safe_stop_;
  int adjusted_step_ = -1;       ///< the step whose landing is being adjusted
  Footprint planned_landing_;    ///< its landing before adjustment
  bool step_adjusted_ = false;   ///< the DCM error has left the stance sole during that step
  int early_landing_step_ = -1;  ///< the adjusted step whose swing foot met the floor before its touchdown (S3)
  bool recovery_step_ = false;   ///< a recovery step was inserted (standing)
  struct CaptureStep {
    bool active = false;
    bool transfer = false;                        ///< both feet still down (the weight transfer before lift-off)
    int swing = 0;                                ///< the stepping foot
    double t_begin = 0;                           ///< when the capture point left the feet [s]
    Eigen::Vector2d p = Eigen::Vector2d::Zero();  ///< its centre of pressure (world) [m]
    int feasible_periods = 0;                     ///< (C0): periods in a row the stance leg could carry the load
  } capture_;                                     ///< the standing capture step under way
  static constexpr double kCaptureMargin = 0.02;  ///< the capture step's CoP stays this far inside the sole [m]
  /// Each sole kCaptureMargin inside its edges (where capture_cop puts the centre of pressure).
  std::array<SolePolygon, 2> capture_sole_{inset(model_.sole_polygon[0], kCaptureMargin),
                                           inset(model_.sole_polygon[1], kCaptureMargin)};
  /// nearest_in_capture_soles' scratch: both capture soles' corners placed, and their hull.
  std::vector<Eigen::Vector2d> transfer_points_ =
      std::vector<Eigen::Vector2d>(capture_sole_[0].corners.size() + capture_sole_[1].corners.size());
  std::vector<Eigen::Vector2d> transfer_hull_ = std::vector<Eigen::Vector2d>(2 * transfer_points_.size());
  ControllerStatus status_;
  bool plan_motion_ = false;
  RobotModelData motion_data_;                                             ///< the planned motion's scratch
  Eigen::Matrix2d motion_jacobian_inverse_ = Eigen::Matrix2d::Identity();  ///< its pelvis Newton step per COM miss
};

}  // namespace flexgait::walking
