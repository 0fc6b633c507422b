#pragma once
/// \file bench_output.hpp  The stiffness bench's files (thesis Fig. 12; the output compensator on
/// the bench for Fig. 15): bench.csv and summary.json, for the command line and the bindings.
#include <string>

#include "flexgait/experiments/stiffness_bench.hpp"

namespace flexgait::experiments {

/// One row per pose of both sweeps: command, encoder, true link, gravity torque, errors, estimates.
std::string bench_csv(const BenchResult& result);
/// summary.json: the BenchResult record (k_fit against the true k, R², errors uncompensated and
/// compensated, the output estimates' errors) as text (json_file_text).
std::string bench_summary_json(const BenchResult& result);

}  // namespace flexgait::experiments
