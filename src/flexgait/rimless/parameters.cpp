#include "flexgait/rimless/parameters.hpp"

#include <fmt/format.h>

namespace flexgait::rimless {
Schema rimless_schema() {
  Schema s = schema_of<WheelParams>();
  s.merge(schema_of<InitialState>()).merge(schema_of<SimulationOptions>());
  return s;
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
