#include "flexgait/walking/walk_params.hpp"

#include <fmt/format.h>

namespace flexgait::walking {

Schema walk_schema() {
  Schema s;
  s.add(integer_param("walk.steps", "10", "footsteps (the last closes the feet side by side)", 0, 10000));
  s.add(real_param("walk.step_length", "0.10", "m", "advance of each footprint over the previous", -0.3, 0.3));
  s.add(real_param("walk.step_width", "0.186", "m", "lateral distance between the feet", 0.15, 0.4));
  s.add(real_param("walk.step_time", "1.0", "s", "one step: double then single support", 0.3, 100));
  s.add(real_param("walk.dsp_ratio", "0.2", "", "double-support share of a step", 0.0, 0.9, false));
  s.add(real_param("walk.turn", "0.0", "rad", "heading change per step (> 0: left)", -0.5, 0.5));
  s.add(real_param("walk.swing_height", "0.05", "m", "swing foot apex above the floor", 0.0, 0.2));
  s.add(real_param("walk.pelvis_height", "0.75", "m", "pelvis origin above the floor", 0.5, 0.79));
  s.add(real_param("walk.start_time", "1.5", "s", "standing before the first step", 0.0, 100));
  s.add(real_param("walk.end_time", "2.0", "s", "standing after the last step", 0.0, 100));
  s.add(real_param("walk.preview_time", "1.6", "s", "preview horizon", 0.1, 5));
  s.add(real_param("walk.preview_q", "1.0", "1/m^2", "weight of the integrated ZMP error", 0, 1e6, false));
  s.add(real_param("walk.preview_r", "1e-6", "s^6/m^2", "weight of the jerk increment", 0, 1e6, false));
  return s;
}

Schema balance_schema() {
  Schema s;
  s.add(boolean_param("balance.enabled", "true", "balance controller on (IMU attitude and foot torque loops)"));
  s.add(real_param("balance.imu_kp", "0.3", "", "pelvis counter-tilt per radian of IMU tilt", 0, 5));
  s.add(real_param("balance.imu_kd", "0.0", "s", "pelvis counter-tilt per rad/s of gyro rate", 0, 1));
  s.add(real_param("balance.imu_limit", "0.1", "rad", "clamp of the pelvis attitude correction", 0, 0.3));
  s.add(real_param("balance.ankle_damping", "3000", "Nm s/rad", "foot torque compliance D (δ' = τ/D − δ/T)", 1, 1e7));
  s.add(real_param("balance.ankle_return_time", "0.2", "s", "return time T of the foot rotation", 0.001, 100));
  s.add(real_param("balance.ankle_limit", "0.05", "rad", "clamp of the foot rotation", 0, 0.3));
  s.add(real_param("balance.ankle_gyro_gain", "0.05", "s", "sway damping: stance sole rotation per rad/s of IMU rate", 0, 2));
  s.add(real_param("balance.gyro_filter_time", "0.05", "s", "low-pass time constant on the IMU rate of the sway damping", 0, 10));
  s.add(real_param("balance.contact_force", "50", "N", "a foot loaded above this is in contact", 0, 1000));
  s.add(real_param("balance.foot_force_damping", "3000", "N s/m", "foot force control D_z (z' = (f - f_d)/D_z - z/T_z)", 1, 1e7));
  s.add(real_param("balance.foot_return_time", "0.5", "s", "return time T_z of the foot height offset", 0.001, 100));
  s.add(real_param("balance.foot_lift_limit", "0.03", "m", "clamp of the foot height offset", 0, 0.1));
  s.add(real_param("balance.zmp_kp", "0.0", "", "ZMP feedback: COM shift per metre of ZMP error (reference − measured)", 0, 5));
  s.add(real_param("balance.zmp_ki", "0.3", "1/s", "ZMP feedback: integral gain", 0, 100));
  s.add(real_param("balance.zmp_filter_time", "0.02", "s", "time constant of each of two low-pass stages on the measured ZMP", 0, 10));
  s.add(real_param("balance.zmp_limit", "0.04", "m", "clamp of the COM shift of the ZMP feedback", 0, 0.2));
  return s;
}

WalkParams walk_from_config(const Config& c) {
  WalkParams w;
  w.steps = static_cast<int>(c.integer("walk.steps"));
  w.step_length = c.real("walk.step_length");
  w.step_width = c.real("walk.step_width");
  w.step_time = c.real("walk.step_time");
  w.dsp_ratio = c.real("walk.dsp_ratio");
  w.turn = c.real("walk.turn");
  w.swing_height = c.real("walk.swing_height");
  w.pelvis_height = c.real("walk.pelvis_height");
  w.start_time = c.real("walk.start_time");
  w.end_time = c.real("walk.end_time");
  w.preview_time = c.real("walk.preview_time");
  w.preview_q = c.real("walk.preview_q");
  w.preview_r = c.real("walk.preview_r");
  return w;
}

BalanceParams balance_from_config(const Config& c) {
  BalanceParams b;
  b.enabled = c.boolean("balance.enabled");
  b.imu_kp = c.real("balance.imu_kp");
  b.imu_kd = c.real("balance.imu_kd");
  b.imu_limit = c.real("balance.imu_limit");
  b.ankle_damping = c.real("balance.ankle_damping");
  b.ankle_return_time = c.real("balance.ankle_return_time");
  b.ankle_limit = c.real("balance.ankle_limit");
  b.contact_force = c.real("balance.contact_force");
  b.ankle_gyro_gain = c.real("balance.ankle_gyro_gain");
  b.gyro_filter_time = c.real("balance.gyro_filter_time");
  b.foot_force_damping = c.real("balance.foot_force_damping");
  b.foot_return_time = c.real("balance.foot_return_time");
  b.foot_lift_limit = c.real("balance.foot_lift_limit");
  b.zmp_kp = c.real("balance.zmp_kp");
  b.zmp_ki = c.real("balance.zmp_ki");
  b.zmp_limit = c.real("balance.zmp_limit");
  b.zmp_filter_time = c.real("balance.zmp_filter_time");
  return b;
}

}  // namespace flexgait::walking
