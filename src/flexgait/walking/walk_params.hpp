#pragma once
/// \file walk_params.hpp
/// Parameters of the walking controller (spec humanoid.md, "The walking controller"): the
/// footstep plan and the preview controller (keys walk.*), and the balance controller (balance.*).
/// SI units; every key is documented in its schema.
#include "flexgait/core/config.hpp"

namespace flexgait::walking {

struct WalkParams {
  int steps = 10;               ///< footsteps, the last one closes the feet side by side
  double step_length = 0.10;    ///< advance of each footprint over the previous one [m]
  double step_width = 0.186;    ///< lateral distance between the feet [m]
  double step_time = 1.0;       ///< one step: double support then single support [s]
  double dsp_ratio = 0.2;       ///< double-support share of a step
  double turn = 0.0;            ///< heading change per step [rad] (> 0: left)
  double swing_height = 0.05;   ///< swing foot apex above the floor [m]
  double pelvis_height = 0.75;  ///< pelvis origin above the floor [m]
  double start_time = 1.5;      ///< standing before the first step [s]
  double end_time = 2.0;        ///< standing after the last step [s]
  double preview_time = 1.6;    ///< preview horizon [s]
  double preview_q = 1.0;       ///< weight of the ZMP error (integral form) [1/m^2]
  double preview_r = 1e-6;      ///< weight of the jerk increment [s^6/m^2]
};

struct BalanceParams {
  bool enabled = true;
  double imu_kp = 0.3;              ///< pelvis attitude: counter-tilt per radian of IMU tilt
  double imu_kd = 0.0;              ///< per rad/s of gyro rate [s]
  double imu_limit = 0.1;           ///< clamp of the attitude correction [rad]
  double ankle_damping = 3000.0;    ///< foot torque compliance D: δ̇ = τ/D − δ/T [Nm s/rad]
  double ankle_return_time = 0.2;   ///< T [s]
  double ankle_limit = 0.05;        ///< clamp of the foot rotation [rad]
  double ankle_gyro_gain = 0.05;    ///< sway damping: stance sole rotation per rad/s of IMU rate [s]
  double gyro_filter_time = 0.05;   ///< low-pass time constant on that rate [s]
  double contact_force = 50.0;      ///< a foot loaded above this is in contact [N]
  double foot_force_damping = 3000.0; ///< foot force control D_z: ż = (f − f_d)/D_z − z/T_z [N s/m]
  double foot_return_time = 0.5;    ///< T_z [s]
  double foot_lift_limit = 0.03;    ///< clamp of the foot height offset [m]
  double zmp_kp = 0.0;              ///< ZMP feedback: COM shift per metre of (reference − measured) ZMP
  double zmp_ki = 0.3;              ///< integral gain of the ZMP feedback [1/s]
  double zmp_limit = 0.04;          ///< clamp of the COM shift [m]
  double zmp_filter_time = 0.02;    ///< time constant of each of two low-pass stages on the measured ZMP [s]
};

Schema walk_schema();
Schema balance_schema();
WalkParams walk_from_config(const Config& config);
BalanceParams balance_from_config(const Config& config);

}  // namespace flexgait::walking
