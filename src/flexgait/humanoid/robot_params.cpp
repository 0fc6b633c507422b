#include "flexgait/humanoid/robot_params.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace flexgait::humanoid {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

Schema robot_schema() {
  Schema s;
  s.add(real_param("robot.total_mass", "57.0", "kg", "total mass; the mass beyond the listed links goes to pelvis and chest",
                   43.72, 500));
  s.add(real_param("robot.thigh", "0.300", "m", "hip pitch axis to knee", 0.05, 2, false));
  s.add(real_param("robot.shank", "0.300", "m", "knee to ankle axes", 0.05, 2, false));
  s.add(real_param("robot.ankle_to_sole", "0.1145", "m", "ankle axes to the sole", 0.01, 1));
  s.add(real_param("robot.sole_friction", "1.0", "", "sole-floor friction coefficient", 0.05, 5));
  return s;
}

Schema plant_schema() {
  Schema s;
  s.add(real_param("plant.k_joint", "1000.0", "Nm/rad", "true gear stiffness of every joint", 0, kInf, false));
  for (auto name : kJointNames)
    s.add(real_param(fmt::format("plant.k_scale.{}", name), "1.0", "", "factor on plant.k_joint for this joint", 0, 100, false));
  s.add(real_param("plant.gear_damping", "80.0", "Nm s/rad", "gear damping (implicit in MuJoCo)", 0, 10000));
  s.add(real_param("plant.backlash", "0.0", "rad", "backlash dead band, total width", 0, 0.1));
  s.add(real_param("plant.torque_limit", "100.0", "Nm", "servo torque limit", 0, kInf, false));
  s.add(real_param("plant.rotor_inertia", "0.8", "kg m^2", "reflected rotor inertia", 1e-4, 100));
  s.add(real_param("plant.servo_bandwidth", "30.0", "Hz", "motor-side position loop bandwidth", 0.1, 1000));
  s.add(real_param("plant.servo_integral_time", "0", "s", "integral time of the position loop (0: none, PD only)", 0, 100));
  s.add(real_param("plant.encoder_steps", "501923", "", "encoder steps per output turn", 1, 1e12));
  s.add(real_param("plant.physics_dt", "0.001", "s", "MuJoCo step", 1e-5, 0.002));
  s.add(real_param("plant.contact_time_constant", "0.005", "s",
                   "sole-floor contact time constant (MuJoCo solref; softer contacts let the feet rock)", 1e-4, 0.1));
  s.add(real_param("plant.control_period", "0.004", "s", "controller period (a multiple of the physics step)", 1e-4, 0.008));
  s.add(real_param("plant.noise.ft_force", "0.0", "N", "F/T force noise std", 0, 1000));
  s.add(real_param("plant.noise.ft_torque", "0.0", "Nm", "F/T torque noise std", 0, 1000));
  s.add(real_param("plant.noise.gyro", "0.0", "rad/s", "gyro noise std", 0, 100));
  s.add(real_param("plant.noise.accel", "0.0", "m/s^2", "accelerometer noise std", 0, 1000));
  s.add(integer_param("plant.noise.seed", "1", "seed of the sensor noise", 0, 2147483647));
  return s;
}

RobotParams robot_from_config(const Config& c) {
  RobotParams r;
  r.total_mass = c.real("robot.total_mass");
  r.thigh = c.real("robot.thigh");
  r.shank = c.real("robot.shank");
  r.ankle_to_sole = c.real("robot.ankle_to_sole");
  r.sole_friction = c.real("robot.sole_friction");
  return r;
}

PlantParams plant_from_config(const Config& c) {
  PlantParams p;
  for (int j = 0; j < kJoints; ++j)
    p.k_joint[j] = c.real("plant.k_joint") * c.real(fmt::format("plant.k_scale.{}", kJointNames[j]));
  p.gear_damping = c.real("plant.gear_damping");
  p.backlash = c.real("plant.backlash");
  p.torque_limit = c.real("plant.torque_limit");
  p.rotor_inertia = c.real("plant.rotor_inertia");
  p.servo_bandwidth = c.real("plant.servo_bandwidth");
  p.servo_integral_time = c.real("plant.servo_integral_time");
  p.encoder_steps = c.real("plant.encoder_steps");
  p.physics_dt = c.real("plant.physics_dt");
  p.control_period = c.real("plant.control_period");
  p.contact_time_constant = c.real("plant.contact_time_constant");
  p.ft_force_noise = c.real("plant.noise.ft_force");
  p.ft_torque_noise = c.real("plant.noise.ft_torque");
  p.gyro_noise = c.real("plant.noise.gyro");
  p.accel_noise = c.real("plant.noise.accel");
  p.noise_seed = static_cast<int>(c.integer("plant.noise.seed"));
  const double ratio = p.control_period / p.physics_dt;
  if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio)
    throw ConfigError("plant.control_period",
                      fmt::format("key 'plant.control_period' = '{}': must be a whole multiple of plant.physics_dt = {} (s)",
                                  p.control_period, p.physics_dt));
  return p;
}

}  // namespace flexgait::humanoid
