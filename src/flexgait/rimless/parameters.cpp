#include "flexgait/rimless/parameters.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
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
                                           "(it is coulomb)",
                                           key, value.first));
  }
  // The wheel's scales (inertia about the foot m L0² + I, weight moment m g L0, leg spring and
  // damper moments K L0², C L0) must be finite and the first two positive: beyond them the
  // equations of motion overflow (an impact of infinite momentum) or divide by zero.
  const double scales[] = {w.m * w.L0 * w.L0 + w.I, w.m * w.g * w.L0, w.K * w.L0 * w.L0, w.C * w.L0};
  if (!std::all_of(std::begin(scales), std::end(scales), [](double x) { return std::isfinite(x); }) ||
      !(scales[0] > 0) || !(scales[1] > 0)) {
    const std::array<std::pair<const char*, double>, 6> keys{{{"rimless.L0", w.L0},
                                                              {"rimless.m", w.m},
                                                              {"rimless.I", w.I},
                                                              {"rimless.K", w.K},
                                                              {"rimless.C", w.C},
                                                              {"rimless.g", w.g}}};
    const auto extreme = [](double v) { return v > 0 ? std::abs(std::log10(v)) : 0.0; };
    const auto* worst = &keys[0];
    for (const auto& k : keys)
      if (extreme(k.second) > extreme(worst->second)) worst = &k;
    throw ConfigError(worst->first,
                      fmt::format("key '{}' = '{}': the wheel's scales overflow or vanish (m L0^2 + I = {}, m g L0 = "
                                  "{}, K L0^2 = {}, C L0 = {}); allowed: m, I, L0, K, C and g whose products are "
                                  "finite, m L0^2 + I and m g L0 above 0",
                                  worst->first, worst->second, scales[0], scales[1], scales[2], scales[3]));
  }
  if (std::abs(s.beta) >= w.alpha())
    throw ConfigError("initial.beta", fmt::format("key 'initial.beta' = '{}': allowed: |beta| < pi/legs = {} (rad)",
                                                  s.beta, w.alpha()));
}

}  // namespace flexgait::rimless
