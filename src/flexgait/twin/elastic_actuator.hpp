#pragma once
/// \file elastic_actuator.hpp
/// The elastic gear actuator of the twin (docs/theory/humanoid.md, "The elastic actuator (the twin's plant)"):
///
///   link:   τ = k · dz(θ_m − θ_l) + d (θ̇_m − θ̇_l)     (dz: backlash dead band of total width b)
///   motor:  J_m θ̈_m = τ_servo − τ,   τ_servo = sat(K_p e + K_i ∫e − K_d θ̇_m),  e = θ_cmd − θ_m
///   encoder: θ_enc = q · round(θ_m / q),  q = 2π / steps
///
/// The servo is a stiff PD, critically damped at the configured bandwidth ω (K_p = J_m ω²,
/// K_d = 2 J_m ω; the motor side sags by τ/K_p, 3.5 % of the gear's τ/k at 30 Hz and k = 1000),
/// with optional integral action (K_i = K_p / T_i) that takes that sag out. Integral action
/// destabilises the walking twin (a probe: the stiff-geared twin falls at 1 s/step with
/// T_i = 0.05 s and walks without it), so it is off by default. The twin couples these to MuJoCo
/// (twin/detail/elastic_drives.hpp): the spring k dz and +d θ̇_m as a generalised force, the
/// damping −d θ̇_l implicitly (joint damping; explicit damping blows up at 1 ms, spec "Physics").

namespace flexgait::twin {

struct ActuatorParams {
  double k = 1000.0;              ///< gear stiffness [Nm/rad]
  double d = 80.0;                ///< gear damping [Nm s/rad]
  double backlash = 0.0;          ///< dead band, total width [rad]
  double torque_limit = 100.0;    ///< servo torque limit [Nm]
  double rotor_inertia = 0.8;     ///< J_m [kg m^2]
  double bandwidth = 30.0;        ///< servo bandwidth [Hz]
  double integral_time = 0.0;     ///< servo integral time [s]; 0: none (the spec's stiff PD)
  double encoder_steps = 501923;  ///< steps per output turn
};

struct ActuatorState {
  double theta_m = 0;   ///< motor-side angle (output units) [rad]
  double omega_m = 0;   ///< [rad/s]
  double integral = 0;  ///< ∫ e dt [rad s]
  double servo = 0;     ///< the servo torque of the last step, within ±torque_limit [Nm]
};

/// Gear deflection after the dead band, dz(θ_m − θ_l) [rad].
double gear_deflection(const ActuatorParams& p, double theta_m, double theta_l);
/// Gear torque on the link [Nm].
double gear_torque(const ActuatorParams& p, const ActuatorState& s, double theta_l, double omega_l);
/// Advances the motor side by dt (semi-implicit Euler) with the link state held.
void step_motor(const ActuatorParams& p, ActuatorState& s, double command, double theta_l, double omega_l, double dt);
/// The motor-side encoder's reading: θ_m quantised to 2π / encoder_steps.
double encoder_reading(const ActuatorParams& p, double theta_m);

}  // namespace flexgait::twin
