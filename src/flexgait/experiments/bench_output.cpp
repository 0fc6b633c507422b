#include "flexgait/experiments/bench_output.hpp"

#include <nlohmann/json.hpp>

#include "flexgait/core/text.hpp"

namespace flexgait::experiments {

std::string bench_csv(const humanoid::BenchResult& r) {
  CsvWriter csv({"compensated", "command", "encoder", "link", "gravity_torque", "error_link_minus_encoder",
                 "error_link_minus_command", "estimate_newton", "estimate_conventional", "newton_iterations"});
  for (const auto* set : {&r.uncompensated, &r.compensated}) {
    for (const auto& b : *set) {
      csv.cell(set == &r.compensated ? "true" : "false").cell(b.command).cell(b.encoder).cell(b.link);
      csv.cell(b.gravity_torque).cell(b.link - b.encoder).cell(b.link - b.command).cell(b.estimate_newton);
      csv.cell(b.estimate_conventional).cell(static_cast<long long>(b.newton_iterations)).end_row();
    }
  }
  return csv.str();
}

std::string bench_summary_json(const humanoid::BenchParams& params, const humanoid::BenchResult& r) {
  nlohmann::ordered_json j;
  j["k_true"] = params.actuator.k;
  j["k_fit"] = r.k_fit;
  j["k_fit_error"] = (r.k_fit - params.actuator.k) / params.actuator.k;
  j["r_squared"] = r.r_squared;
  j["max_error_uncompensated"] = r.max_error_uncompensated;
  j["max_error_compensated"] = r.max_error_compensated;
  j["residual_compensated_min"] = r.min_residual_compensated;
  j["residual_compensated_max"] = r.max_residual_compensated;
  j["estimate_newton_error_max"] = r.max_error_newton;
  j["estimate_conventional_error_max"] = r.max_error_conventional;
  j["newton_conventional_max"] = r.max_newton_conventional;
  j["newton_iterations_max"] = r.max_newton_iterations;
  return j.dump(2) + "\n";
}

}  // namespace flexgait::experiments
