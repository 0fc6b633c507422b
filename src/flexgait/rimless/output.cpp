#include "flexgait/rimless/output.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "flexgait/core/record_json.hpp"

#include "flexgait/core/text.hpp"

namespace flexgait::rimless {

std::string log_csv(const SimulationResult& r) {
  std::vector<std::string> cols{"t", "x", "y", "theta", "xd", "yd", "thetad"};
  for (int i = 1; i <= kMaxContacts; ++i)
    for (const char* c : {"leg", "phase", "N", "T", "c", "cdot"}) cols.push_back(fmt::format("{}{}", c, i));
  for (const char* c : {"E_kinetic", "E_gravity", "E_spring", "E_total", "W_damp", "W_fric", "balance"})
    cols.emplace_back(c);
  CsvWriter csv(cols);
  const double e0 = r.energy_initial;
  for (const auto& s : r.samples) {
    csv.cell(s.t);
    for (double v : s.q) csv.cell(v);
    for (const auto& c : s.contact) {
      if (c.leg < 0) {
        csv.cell(-1LL).cell("none").cell(0.0).cell(0.0).cell(0.0).cell(0.0);
      } else {
        csv.cell(static_cast<long long>(c.leg)).cell(mode_name(c.mode)).cell(c.N).cell(c.T).cell(c.c).cell(c.cdot);
      }
    }
    const double total = s.energy.total();
    csv.cell(s.energy.kinetic).cell(s.energy.gravity).cell(s.energy.spring).cell(total);
    csv.cell(s.w_damp).cell(s.w_fric).cell(total + s.w_damp + s.w_fric - e0);
    csv.end_row();
  }
  return csv.str();
}

std::string events_csv(const SimulationResult& r) {
  CsvWriter csv({"t", "kind", "leg", "modes"});
  for (const auto& e : r.events) {
    csv.cell(e.t).cell(e.kind).cell(static_cast<long long>(e.leg)).cell(e.modes).end_row();
  }
  return csv.str();
}

std::string steps_csv(const SimulationResult& r) {
  CsvWriter csv({"step", "stance_leg", "t_start", "t_end", "duration", "x_start", "x_end", "speed", "energy_start",
                 "gait", "contact_phases", "complete"});
  for (const auto& s : r.steps) {
    const double dt = s.t_end - s.t_start;
    csv.cell(static_cast<long long>(s.index)).cell(static_cast<long long>(s.stance_leg)).cell(s.t_start).cell(s.t_end);
    csv.cell(dt).cell(s.x_start).cell(s.x_end).cell(dt > 0 ? (s.x_end - s.x_start) / dt : 0.0).cell(s.energy_start);
    csv.cell(gait_label(s.single_support)).cell(gait_label(s.contact)).cell(s.complete ? "true" : "false").end_row();
  }
  return csv.str();
}

std::string summary_json(const SimulationResult& r, const std::string& model) {
  nlohmann::ordered_json j;
  j["model"] = model;
  add_record_json(j, r);
  return j.dump(2) + "\n";
}

void write_run(const RunDirectory& dir, const SimulationResult& result, const std::string& model) {
  dir.write("log.csv", log_csv(result));
  dir.write("events.csv", events_csv(result));
  dir.write("steps.csv", steps_csv(result));
  dir.write("summary.json", summary_json(result, model));
}

}  // namespace flexgait::rimless
