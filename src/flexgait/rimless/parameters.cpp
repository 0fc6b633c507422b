#include "flexgait/rimless/parameters.hpp"

#include <fmt/format.h>

namespace flexgait::rimless {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

Schema rimless_schema() {
  Schema s;
  s.add(real_param("rimless.m", "1.0", "kg", "total mass", 0, kInf, false));
  s.add(real_param("rimless.I", "0.3", "kg m^2", "moment of inertia about the hub (0: point mass)", 0, kInf));
  s.add(integer_param("rimless.legs", "10", "number of legs N (alpha = pi/N)", 3, 100));
  s.add(real_param("rimless.slope", "0.1", "rad", "slope angle phi", 0, std::numbers::pi / 4));
  s.add(real_param("rimless.L0", "1.0", "m", "leg rest length", 0, kInf, false));
  s.add(real_param("rimless.K", "1000.0", "N/m", "leg spring stiffness", 0, kInf, false));
  s.add(real_param("rimless.C", "30.0", "N s/m", "leg damping", 0, kInf));
  s.add(real_param("rimless.mu_s", "0.6", "", "static friction coefficient", 0, kInf));
  s.add(real_param("rimless.mu_k", "0.6", "", "kinetic friction coefficient (<= mu_s)", 0, kInf));
  s.add(real_param("rimless.g", "9.81", "m/s^2", "gravitational acceleration", 0, kInf, false));
  s.add(real_param("initial.omega", "1.4", "rad/s", "initial wheel angular velocity", -100, 100));
  s.add(real_param("initial.beta", "0.0", "rad", "initial stance-leg angle from the slope normal, |beta| < pi/N",
             -std::numbers::pi / 2, std::numbers::pi / 2, false, false));
  s.add(choice_param("sim.model", "flexible", "flexible legs with stick-slip, or the rigid rimless wheel",
               {"flexible", "rigid"}));
  s.add(integer_param("sim.steps", "20", "steps to simulate (touchdowns of new legs)", 1, 1e6));
  s.add(real_param("sim.max_time", "120.0", "s", "simulated-time limit", 0, kInf, false));
  s.add(real_param("sim.max_step_time", "10.0", "s", "a step longer than this is reported as stopped", 0, kInf, false));
  s.add(real_param("sim.sample_dt", "0.001", "s", "log sampling interval (events are logged too)", 1e-6, 10));
  s.add(real_param("solver.rtol", "1e-10", "", "CVODE relative tolerance", 1e-14, 1e-2));
  s.add(real_param("solver.atol", "1e-12", "", "CVODE absolute tolerance", 1e-16, 1e-2));
  s.add(choice_param("solver.method", "adams", "CVODE linear multistep method", {"adams", "bdf"}));
  return s;
}

WheelParams wheel_from_config(const Config& c) {
  WheelParams w;
  w.m = c.real("rimless.m");
  w.I = c.real("rimless.I");
  w.legs = static_cast<int>(c.integer("rimless.legs"));
  w.slope = c.real("rimless.slope");
  w.L0 = c.real("rimless.L0");
  w.K = c.real("rimless.K");
  w.C = c.real("rimless.C");
  w.mu_s = c.real("rimless.mu_s");
  w.mu_k = c.real("rimless.mu_k");
  w.g = c.real("rimless.g");
  return w;
}

InitialState initial_from_config(const Config& c) {
  InitialState s;
  s.omega = c.real("initial.omega");
  s.beta = c.real("initial.beta");
  return s;
}

SimulationOptions simulation_from_config(const Config& c) {
  SimulationOptions o;
  o.steps = static_cast<int>(c.integer("sim.steps"));
  o.max_time = c.real("sim.max_time");
  o.max_step_time = c.real("sim.max_step_time");
  o.sample_dt = c.real("sim.sample_dt");
  o.rtol = c.real("solver.rtol");
  o.atol = c.real("solver.atol");
  o.method = c.choice("solver.method") == "bdf" ? OdeMethodChoice::Bdf : OdeMethodChoice::Adams;
  return o;
}

void validate(const WheelParams& w, const InitialState& s) {
  if (w.mu_k > w.mu_s)
    throw ConfigError("rimless.mu_k", fmt::format("key 'rimless.mu_k' = '{}': must not exceed rimless.mu_s = {}",
                                                  w.mu_k, w.mu_s));
  if (std::abs(s.beta) >= w.alpha())
    throw ConfigError("initial.beta",
                      fmt::format("key 'initial.beta' = '{}': allowed: |beta| < pi/legs = {} (rad)", s.beta, w.alpha()));
}

}  // namespace flexgait::rimless
