#pragma once
// Shared set-up of the rimless tests: the spec's measured parameter set and run options.
#include <cmath>
#include <cstdint>
#include <span>

#include "flexgait/numerics/ode_system.hpp"
#include "flexgait/rimless/flexible_wheel.hpp"
#include "flexgait/rimless/flow.hpp"

namespace flexgait::rimless::testing {

/// m = 1, I = 0.3, N = 10, φ = 0.1, L0 = 1, K = 1000, C = 30 (spec rimless.md), μ given.
inline WheelParams measured_wheel(double mu) {
  WheelParams w;
  w.mu_s = w.mu_k = mu;
  return w;
}

inline SimulationOptions run_options(int steps, double rtol = 1e-10) {
  SimulationOptions o;
  o.steps = steps;
  o.rtol = rtol;
  o.atol = 1e-12;
  o.sample_dt = 2e-3;
  o.max_step_time = 3.0;
  return o;
}

/// The random generator of the seeded random samples of wheels, written out (splitmix64, 53-bit
/// uniforms) so that a sample is the same on every platform.
struct SplitMix64 {
  std::uint64_t s;
  double uniform(double a, double b) {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return a + (b - a) * static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  double log_uniform(double a, double b) { return std::exp(uniform(std::log(a), std::log(b))); }
};

/// One wheel of the seeded random sample: μ 0.05–5 (log-uniform), I 0.02–1, C 5–60, K 300–1e4
/// (log-uniform), N 6–14, φ 0.03–0.2, ω0 1–3; m = L0 = 1 (drawn in this order).
struct RandomWheel {
  double mu, I, C, K;
  int legs;
  double slope, omega0;
  static RandomWheel draw(SplitMix64& rng) {
    RandomWheel s;
    s.mu = rng.log_uniform(0.05, 5);
    s.I = rng.uniform(0.02, 1);
    s.C = rng.uniform(5, 60);
    s.K = rng.log_uniform(300, 1e4);
    s.legs = static_cast<int>(std::floor(rng.uniform(6, 15)));
    s.slope = rng.uniform(0.03, 0.2);
    s.omega0 = rng.uniform(1, 3);
    return s;
  }
  WheelParams params() const {
    WheelParams w;
    w.mu_s = w.mu_k = mu;
    w.I = I;
    w.C = C;
    w.K = K;
    w.legs = legs;
    w.slope = slope;
    return w;
  }
};

/// The flow of one contact mode with no guards: a segment of a run integrated again on its own.
class Segment final : public numerics::OdeSystem {
 public:
  Segment(const WheelParams& w, const ContactSet& c) : w_(w), c_(c) {}
  bool rhs(double, std::span<const double> y, std::span<double> yd) override { return flow_derivative(w_, c_, y, yd); }
  void guards(double, std::span<const double>, std::span<double>) override {}

 private:
  const WheelParams& w_;
  ContactSet c_;
};

}  // namespace flexgait::rimless::testing
