#include "flexgait/experiments/bench_output.hpp"

#include "flexgait/core/record_json.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait::experiments {

std::string bench_csv(const BenchResult& r) {
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

std::string bench_summary_json(const BenchResult& r) {
  return json_file_text(record_json(r));
}

}  // namespace flexgait::experiments
