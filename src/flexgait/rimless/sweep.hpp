#pragma once
/// \file sweep.hpp
/// One point of a parameter sweep of the rimless wheel: the gait reached from the initial state,
/// the fixed point of the Poincaré map near it, its multipliers, stability, speed and energy per
/// step. Points are independent, so a sweep runs them on all cores (core/sweep_runner.hpp).
#include <functional>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/rimless/poincare.hpp"

namespace flexgait::rimless {

struct SweepSpec {
  std::string param;  ///< a configuration key, or "rimless.mu" for mu_s = mu_k
  double from = 0, to = 0;
  int count = 1;
  Section section = Section::Touchdown;

  double value(int i) const { return count == 1 ? from : from + (to - from) * i / (count - 1); }
};

/// Throws ConfigError if the key is unknown or not a real number.
void check_sweep_param(const Schema& schema, const std::string& param);

/// The configuration keys `param` sets: an alias its parts (rimless.mu: rimless.mu_s and
/// rimless.mu_k), any other key itself.
std::vector<std::string> param_keys(const Schema& schema, const std::string& param);

/// The configuration with `param` (rimless.mu: mu_s and mu_k) set to the text `value`, checked as
/// a --set of it is (domain, then the wheel's cross-field checks); a ConfigError names `origin`.
Config config_at(const Config& base, const std::string& param, const std::string& value, const std::string& origin);

/// The configuration of point i (validated).
Config sweep_point_config(const Config& base, const SweepSpec& spec, int i);

/// Checks a whole sweep before anything is written: its ends (errors name --from and --to), then
/// every point.
void check_sweep(const Config& base, const SweepSpec& spec);

/// CSV header and cells of one point (no index). Thread-safe. `poll`: SimulationOptions::poll of its runs.
std::string sweep_header();
std::string sweep_row(const Config& base, const SweepSpec& spec, int i, const std::function<void()>& poll = {});
/// Whether `cells` (a resumed row of the partial file, after its index) could be sweep_row(…, i):
/// as many cells as sweep_header has columns, the value point i's (format_number of spec.value(i)),
/// numbers where the columns hold numbers (format_number's text: nan and inf too), true/false,
/// a whole count of iterations, the state and multipliers as written, and a failure named exactly
/// when the point did not converge (SweepJob::valid_row; a row it refuses is computed again).
bool sweep_row_valid(const SweepSpec& spec, int i, const std::vector<std::string>& cells);

}  // namespace flexgait::rimless
