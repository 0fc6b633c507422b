#pragma once
/// \file walk_params.hpp
/// Parameters of the walking controller (docs/theory/humanoid.md, "The walking controller"): the
/// footstep plan and the preview controller (keys walk.*), and the balance controller (balance.*).
/// SI units; each struct lists its keys once (core/record.hpp).
#include <array>

#include "flexgait/core/config.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/robot/joints.hpp"
#include "flexgait/walking/calibration_motion.hpp"

namespace flexgait::walking {

struct WalkParams {
  int steps = 10;              ///< footsteps, the last one closes the feet side by side
  double step_length = 0.10;   ///< advance of each footprint over the previous one [m]
  double step_width = 0.186;   ///< lateral distance between the sole centres [m] (auto: stance_defaults.hpp)
  double step_time = 1.0;      ///< one step: double support then single support [s]
  double dsp_ratio = 0.2;      ///< double-support share of a step
  double turn = 0.0;           ///< heading change per step [rad] (> 0: left)
  double swing_height = 0.05;  ///< swing foot apex above the floor [m]
  double pelvis_height =
      0.723;  ///< pelvis origin above the floor [m] (auto: stance_defaults.hpp; the builtin's is ROBOTIS's)
  double start_time = 1.5;        ///< standing before the first step [s]
  double end_time = 2.0;          ///< standing after the last step [s]
  double preview_time = 1.6;      ///< preview horizon [s]
  double preview_q = 1.0;         ///< weight of the ZMP error (integral form) [1/m^2]
  double preview_r = 1e-6;        ///< weight of the jerk increment [s^6/m^2]
  CalibrationMotion calibration;  ///< a stiffness calibration in the start stance (keys calibration.*)

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("walk.steps", s.steps, {.doc = "footsteps (the last closes the feet side by side)", .bounds = closed(0, 10000)});
    v("walk.step_length", s.step_length,
      {.unit = "m", .doc = "advance of each footprint over the previous", .bounds = closed(-0.3, 0.3)});
    v("walk.step_width", s.step_width,
      {.unit = "m",
       .doc = "lateral distance between the sole centres",
       .bounds = closed(0.02, 2.0),
       .derived =
           "the hip points' lateral distance, to 1 mm (the builtin: 0.186 m); a loaded robot's at most 0.186 m x "
           "leg / the builtin's (3 significant digits), at least its soles' width + 2 cm"});
    v("walk.step_time", s.step_time,
      {.unit = "s", .doc = "one step: double then single support", .bounds = closed(0.3, 100)});
    v("walk.dsp_ratio", s.dsp_ratio, {.doc = "double-support share of a step", .bounds = left_open(0.0, 0.9)});
    v("walk.turn", s.turn, {.unit = "rad", .doc = "heading change per step (> 0: left)", .bounds = closed(-0.5, 0.5)});
    v("walk.swing_height", s.swing_height,
      {.unit = "m", .doc = "swing foot apex above the floor", .bounds = closed(0.0, 0.2)});
    v("walk.pelvis_height", s.pelvis_height,
      {.unit = "m",
       .doc = "pelvis origin above the floor",
       .bounds = closed(0.1, 3.0),
       .derived =
           "the stretched legs' height less 14.08 % of thigh + shank, to 1 mm (the builtin: 0.723 m, ROBOTIS's); where "
           "that bends a joint out of its range, the nearest height that keeps each joint 0.1 rad inside it"});
    v("walk.start_time", s.start_time,
      {.unit = "s", .doc = "standing before the first step", .bounds = closed(0.0, 4000)});
    v("walk.end_time", s.end_time, {.unit = "s", .doc = "standing after the last step", .bounds = closed(0.0, 100)});
    v("walk.preview_time", s.preview_time, {.unit = "s", .doc = "preview horizon", .bounds = closed(0.1, 5)});
    v("walk.preview_q", s.preview_q,
      {.unit = "1/m^2", .doc = "weight of the integrated ZMP error", .bounds = left_open(0, 1e6)});
    v("walk.preview_r", s.preview_r,
      {.unit = "s^6/m^2", .doc = "weight of the jerk increment", .bounds = left_open(0, 1e6)});
    CalibrationMotion::visit_fields(s.calibration, v);
  }
};

/// The balance layer: ROBOTIS-style PD loops with clamps, or the DCM stabiliser (dcm_stabiliser.hpp).
enum class BalanceMode { kPd, kDcm };
constexpr std::array<EnumName<BalanceMode>, 2> enum_names(BalanceMode) {
  return {{{BalanceMode::kPd, "pd"}, {BalanceMode::kDcm, "dcm"}}};
}

struct BalanceParams {
  bool enabled = true;
  BalanceMode mode = BalanceMode::kPd;
  double imu_kp = 0.3;                 ///< pelvis attitude: counter-tilt per radian of IMU tilt
  double imu_kd = 0.0;                 ///< per rad/s of gyro rate [s]
  double imu_limit = 0.1;              ///< clamp of the attitude correction [rad]
  double ankle_damping = 3000.0;       ///< foot torque compliance D: δ̇ = τ/D − δ/T [Nm s/rad]
  double ankle_return_time = 0.2;      ///< T [s]
  double ankle_limit = 0.05;           ///< clamp of the foot rotation [rad]
  double ankle_gyro_gain = 0.05;       ///< sway damping: stance sole rotation per rad/s of IMU rate [s]
  double gyro_filter_time = 0.05;      ///< low-pass time constant on that rate [s]
  double contact_force = 50.0;         ///< a foot loaded above this is in contact [N]
  double foot_force_damping = 3000.0;  ///< foot force control D_z: ż = (f − f_d)/D_z − z/T_z [N s/m]
  double foot_return_time = 0.5;       ///< T_z [s]
  double foot_lift_limit = 0.03;       ///< clamp of the foot height offset [m]
  double zmp_kp = 0.0;                 ///< ZMP feedback: COM shift per metre of (reference − measured) ZMP
  double zmp_ki = 0.3;                 ///< integral gain of the ZMP feedback [1/s]
  double zmp_limit = 0.04;             ///< clamp of the COM shift [m]
  double zmp_filter_time = 0.02;       ///< time constant of each of two low-pass stages on the measured ZMP [s]
  // The DCM stabiliser (mode dcm; Caron et al. 2019's HRP-4 gains).
  double dcm_kp = 5.0;               ///< DCM proportional gain k_p [1/s]
  double dcm_ki = 10.0;              ///< DCM integral gain k_i [1/s^2]
  double dcm_integral_limit = 0.05;  ///< clamp of the DCM error's integral [m s]
  /// Foot rotation rate per Nm of torque error about the sole [rad/(N m s)]. Caron et al.'s 0.01
  /// rocks this twin (stiff servos, 4 ms period) over within 2.6 s of a 10-step walk; 0.002
  /// walks it (measured; 0.005 falls at step 2).
  double cop_admittance = 0.002;
  double com_velocity_filter_time = 0.01;  ///< low-pass on the estimated COM velocity [s]
  double com_bias_time = 2.0;  ///< time constant pulling the COM estimate's mean onto the measured ZMP's [s]; 0: off
  // Step adjustment (mode dcm; step_adjustment.hpp).
  bool step_adjustment = false;         ///< move the next footstep when the DCM error leaves the sole
  double step_adjustment_limit = 0.25;  ///< |Δ| along each axis of the stance sole [m]
  bool early_landing = true;            ///< an adjusted step whose swing foot meets the floor early lands there (S3)
  double step_reach = 0.4;              ///< landing to stance sole centre, at most [m]
  double recovery_step_time = 0.25;     ///< standing: the capture step's duration from lift-off [s]
  /// Standing: the capture step's foot lifts once the stance leg alone could carry the measured
  /// ground force within this joint torque (stance_load.hpp; the twin's servos: plant.torque_limit) [N m]; 0: at once.
  double capture_torque_limit = 100.0;
  /// The same check per joint: each joint's own limit where it has one, capture_torque_limit where 0 (not a key: a
  /// loaded robot's file limits while balance.capture_torque_limit is derived, as its servos have them) [N m].
  humanoid::JointVector capture_joint_torque_limit{};
  // Landing orientation control (landing_adaptation.hpp; both modes).
  double landing_admittance = 0.0;  ///< A: sole tilt rate per Nm of ground torque after touchdown [rad/(N m s)]; 0: off
  double landing_window = 0.1;      ///< how long after touchdown the sole follows the torque [s]
  double landing_tilt_limit = 0.15;  ///< clamp of the adapted sole tilt per axis [rad]

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("balance.enabled", s.enabled, {.doc = "balance controller on (IMU attitude and foot torque loops)"});
    v("balance.mode", s.mode,
      {.doc = "pd: PD loops with clamps; dcm: DCM tracked by a CoP command (Englsberger 2015, Caron 2019)"});
    v("balance.imu_kp", s.imu_kp, {.doc = "pelvis counter-tilt per radian of IMU tilt", .bounds = closed(0, 5)});
    v("balance.imu_kd", s.imu_kd,
      {.unit = "s", .doc = "pelvis counter-tilt per rad/s of gyro rate", .bounds = closed(0, 1)});
    v("balance.imu_limit", s.imu_limit,
      {.unit = "rad", .doc = "clamp of the pelvis attitude correction", .bounds = closed(0, 0.3)});
    v("balance.ankle_damping", s.ankle_damping,
      {.unit = "Nm s/rad", .doc = "foot torque compliance D (δ' = τ/D − δ/T)", .bounds = closed(1, 1e7)});
    v("balance.ankle_return_time", s.ankle_return_time,
      {.unit = "s", .doc = "return time T of the foot rotation", .bounds = closed(0.001, 100)});
    v("balance.ankle_limit", s.ankle_limit,
      {.unit = "rad", .doc = "clamp of the foot rotation", .bounds = closed(0, 0.3)});
    v("balance.ankle_gyro_gain", s.ankle_gyro_gain,
      {.unit = "s", .doc = "sway damping: stance sole rotation per rad/s of IMU rate", .bounds = closed(0, 2)});
    v("balance.gyro_filter_time", s.gyro_filter_time,
      {.unit = "s", .doc = "low-pass time constant on the IMU rate of the sway damping", .bounds = closed(0, 10)});
    v("balance.contact_force", s.contact_force,
      {.unit = "N", .doc = "a foot loaded above this is in contact", .bounds = closed(0, 1000)});
    v("balance.foot_force_damping", s.foot_force_damping,
      {.unit = "N s/m", .doc = "foot force control D_z (z' = (f - f_d)/D_z - z/T_z)", .bounds = closed(1, 1e7)});
    v("balance.foot_return_time", s.foot_return_time,
      {.unit = "s", .doc = "return time T_z of the foot height offset", .bounds = closed(0.001, 100)});
    v("balance.foot_lift_limit", s.foot_lift_limit,
      {.unit = "m", .doc = "clamp of the foot height offset", .bounds = closed(0, 0.1)});
    v("balance.zmp_kp", s.zmp_kp,
      {.doc = "ZMP feedback: COM shift per metre of ZMP error (reference − measured)", .bounds = closed(0, 5)});
    v("balance.zmp_ki", s.zmp_ki, {.unit = "1/s", .doc = "ZMP feedback: integral gain", .bounds = closed(0, 100)});
    v("balance.zmp_filter_time", s.zmp_filter_time,
      {.unit = "s",
       .doc = "time constant of each of two low-pass stages on the measured ZMP",
       .bounds = closed(0, 10)});
    v("balance.zmp_limit", s.zmp_limit,
      {.unit = "m", .doc = "clamp of the COM shift of the ZMP feedback", .bounds = closed(0, 0.2)});
    v("balance.dcm_kp", s.dcm_kp,
      {.unit = "1/s", .doc = "DCM stabiliser: proportional gain", .bounds = closed(0, 100)});
    v("balance.dcm_ki", s.dcm_ki, {.unit = "1/s^2", .doc = "DCM stabiliser: integral gain", .bounds = closed(0, 1000)});
    v("balance.dcm_integral_limit", s.dcm_integral_limit,
      {.unit = "m s", .doc = "DCM stabiliser: clamp of the error's integral", .bounds = closed(0, 1)});
    v("balance.cop_admittance", s.cop_admittance,
      {.unit = "rad/(N m s)",
       .doc = "DCM stabiliser: foot rotation rate per Nm of sole torque error",
       .bounds = closed(0, 1)});
    v("balance.com_velocity_filter_time", s.com_velocity_filter_time,
      {.unit = "s",
       .doc = "DCM stabiliser: low-pass time constant on the estimated COM velocity",
       .bounds = closed(0, 1)});
    v("balance.com_bias_time", s.com_bias_time,
      {.unit = "s",
       .doc = "DCM stabiliser: time constant pulling the COM estimate's mean onto the measured ZMP's (0: off)",
       .bounds = closed(0, 100)});
    v("balance.step_adjustment", s.step_adjustment,
      {.doc = "dcm mode: move the next footstep toward the capture point when the DCM error leaves the sole (standing: "
              "step)"});
    v("balance.early_landing", s.early_landing,
      {.doc = "step adjustment while walking: an adjusted step whose swing foot meets the floor past its apex lands "
              "there, and the load follows the stabiliser's centre of pressure until the next step lifts"});
    v("balance.step_adjustment_limit", s.step_adjustment_limit,
      {.unit = "m", .doc = "step adjustment: largest shift of a footstep along each axis", .bounds = closed(0, 0.5)});
    v("balance.step_reach", s.step_reach,
      {.unit = "m",
       .doc = "step adjustment: largest distance from the stance sole centre to the landing",
       .bounds = closed(0.2, 1)});
    v("balance.recovery_step_time", s.recovery_step_time,
      {.unit = "s",
       .doc = "step adjustment while standing: duration of the capture step from lift-off",
       .bounds = closed(0.1, 2)});
    v("balance.capture_torque_limit", s.capture_torque_limit,
      {.unit = "N m",
       .doc = "step adjustment while standing: the capture step's foot lifts once the stance leg alone could carry the "
              "measured ground force within this joint torque (at the latest after balance.recovery_step_time; 0: at "
              "once; derived for a loaded robot, each joint within its servo's own limit)",
       .bounds = closed(0, 1e4)});
    v("balance.landing_admittance", s.landing_admittance,
      {.unit = "rad/(N m s)",
       .doc = "landing orientation control: sole tilt rate per Nm of ground torque after touchdown (0: off)",
       .bounds = closed(0, 1)});
    v("balance.landing_window", s.landing_window,
      {.unit = "s",
       .doc = "landing orientation control: how long after touchdown the sole follows the torque",
       .bounds = closed(0, 10)});
    v("balance.landing_tilt_limit", s.landing_tilt_limit,
      {.unit = "rad",
       .doc = "landing orientation control: clamp of the adapted sole tilt per axis",
       .bounds = closed(0, 0.4)});
  }
};

inline Schema walk_schema() {
  return schema_of<WalkParams>();
}
inline Schema balance_schema() {
  return schema_of<BalanceParams>();
}
inline WalkParams walk_from_config(const Config& config) {
  return record_from_config<WalkParams>(config);
}
inline BalanceParams balance_from_config(const Config& config) {
  return record_from_config<BalanceParams>(config);
}

}  // namespace flexgait::walking
