#include "flexgait/rimless/parameters.hpp"

#include <fmt/format.h>

#include <array>
#include <utility>

namespace flexgait::rimless {
Schema rimless_schema() {
  Schema s = schema_of<WheelParams>();
  s.merge(schema_of<InitialState>()).merge(schema_of<SimulationOptions>());
  return s.alias("rimless.mu", {"rimless.mu_s", "rimless.mu_k"},
                 "one friction coefficient: sets rimless.mu_s and rimless.mu_k to the same value");
}

void validate(const WheelParams& w, const InitialState& s) {
  if (w.mu_k > w.mu_s)
    throw ConfigError("rimless.mu_k", fmt::format("key 'rimless.mu_k' = '{}': must not exceed rimless.mu_s = {}; lower "
                                                  "rimless.mu_k too, or set both with rimless.mu",
                                                  w.mu_k, w.mu_s));
  if (w.friction == Friction::Coulomb) {
    const WheelParams d;
    const std::array<std::pair<const char*, std::pair<double, double>>, 3> stribeck{
        {{"rimless.stribeck_velocity", {w.stribeck_velocity, d.stribeck_velocity}},
         {"rimless.stribeck_exponent", {w.stribeck_exponent, d.stribeck_exponent}},
         {"rimless.viscous", {w.viscous, d.viscous}}}};
    for (const auto& [key, value] : stribeck)
      if (value.first != value.second)
        throw ConfigError(key, fmt::format("key '{}' = '{}': applies only with rimless.friction = stribeck "
                                           "(it is coulomb)", key, value.first));
  }
  if (std::abs(s.beta) >= w.alpha())
    throw ConfigError("initial.beta",
                      fmt::format("key 'initial.beta' = '{}': allowed: |beta| < pi/legs = {} (rad)", s.beta, w.alpha()));
}

}  // namespace flexgait::rimless
