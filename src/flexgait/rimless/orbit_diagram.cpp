#include "flexgait/rimless/orbit_diagram.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "flexgait/core/record_json.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/rimless/poincare.hpp"

namespace flexgait::rimless {

void check_orbit_diagram(const Config& base, const OrbitDiagramSpec& spec) {
  if (spec.transient < 1)
    throw ConfigError("--transient", fmt::format("--transient: {} steps; allowed: an integer >= 1", spec.transient));
  if (spec.record < 1)
    throw ConfigError("--record", fmt::format("--record: {} crossings; allowed: an integer >= 1", spec.record));
  check_sweep(base, spec.sweep);
}

std::string orbit_points_header() {
  return "value,recorded,modes,gaits,thetad,states,failure";
}

std::string orbit_points_row(const Config& base, const OrbitDiagramSpec& spec, int i) {
  const Config c = sweep_point_config(base, spec.sweep, i);
  const WheelParams w = wheel_from_config(c);
  SimulationOptions sim = simulation_from_config(c);
  sim.log = false;
  // The run's length is its number of steps; sim.max_time (meant for one simulate run) does not cut
  // it short. sim.max_step_time still ends a wheel that stops.
  sim.max_time = std::numeric_limits<double>::infinity();
  SectionState p;
  // The full hybrid state from crossing to crossing (SectionWalk): the orbit a simulation follows.
  SectionWalk walk(w, sim, sim.model, spec.sweep.section);
  std::optional<Failure> failure = walk.settle(initial_from_config(c), spec.transient, p);
  if (failure && failure->reason == FailureReason::InitialFootBelowGround)  // a foot below the ground at the start
    failure = failure->in_stage("infeasible initial state");
  std::string modes, gaits, thetad, states;
  int recorded = 0;
  if (!failure) {
    for (; recorded < spec.record; ++recorded) {
      const MapStep s = walk.step();  // in whatever mode the section is crossed
      if (s.failure) {
        failure = s.failure;
        break;
      }
      p = s.next;
      const char* sep = recorded > 0 ? ";" : "";
      modes += sep + std::string(p.flight ? "flight" : mode_name(p.mode));
      gaits += sep + s.gait;
      thetad += sep + format_number(p.z(p.z.size() - 1));
      states += sep;
      for (Eigen::Index k = 0; k < p.z.size(); ++k) states += (k ? " " : "") + format_number(p.z(k));
    }
  }
  return fmt::format("{},{},{},{},{},{},{}", format_number(spec.sweep.value(i)), recorded, modes, gaits, thetad, states,
                     csv_field(text_of(failure)));
}

bool orbit_points_row_valid(const OrbitDiagramSpec& spec, int i, const std::vector<std::string>& cells) {
  // value,recorded,modes,gaits,thetad,states,failure
  if (cells.size() != 7 || cells[0] != format_number(spec.sweep.value(i)) || !count_text(cells[1], spec.record))
    return false;
  const auto recorded = static_cast<std::size_t>(std::stoi(cells[1]));
  if ((recorded == static_cast<std::size_t>(spec.record)) != cells[6].empty()) return false;
  if (recorded == 0) return cells[2].empty() && cells[3].empty() && cells[4].empty() && cells[5].empty();
  const auto modes = split_text(cells[2], ';'), gaits = split_text(cells[3], ';'), thetad = split_text(cells[4], ';'),
             states = split_text(cells[5], ';');
  if (modes.size() != recorded || gaits.size() != recorded || thetad.size() != recorded || states.size() != recorded)
    return false;
  for (std::size_t k = 0; k < recorded; ++k) {
    if (modes[k].empty() || !number_text(thetad[k])) return false;
    for (const std::string& x : split_text(states[k], ' '))
      if (!number_text(x)) return false;
  }
  return true;
}

std::string orbit_csv(const std::string& points_csv) {
  CsvWriter out({"parameter", "step", "mode", "gait", "thetad", "state", "failure"});
  const std::vector<CsvRecord> records = parse_csv(points_csv);
  for (std::size_t r = 1; r < records.size(); ++r) {  // records[0]: the header
    const std::vector<std::string>& f = records[r].fields;
    if (f.size() != 8) throw std::invalid_argument("orbit_points.csv: a row without its 8 fields");
    const std::string& value = f[1];
    const std::string& failure = f[7];
    const int recorded = std::stoi(f[2]);
    if (recorded == 0) {
      out.cell(value).cell("").cell("").cell("").cell("").cell("").cell(failure);
      out.end_row();
      continue;
    }
    const auto modes = split_text(f[3], ';'), gaits = split_text(f[4], ';'), thetad = split_text(f[5], ';'),
               states = split_text(f[6], ';');
    for (int k = 0; k < recorded; ++k) {
      const auto u = static_cast<std::size_t>(k);
      std::string state = states.at(u);
      for (char& ch : state)
        if (ch == ' ') ch = ';';
      out.cell(value).cell(static_cast<long long>(k + 1)).cell(modes.at(u)).cell(gaits.at(u)).cell(thetad.at(u));
      out.cell(state).cell(failure);
      out.end_row();
    }
  }
  return out.str();
}

nlohmann::ordered_json orbit_summary(const std::string& points_csv) {
  nlohmann::ordered_json values = nlohmann::ordered_json::array();
  nlohmann::ordered_json until = nullptr, first_multiple = nullptr;
  bool period_one = true;
  const std::vector<CsvRecord> records = parse_csv(points_csv);
  for (std::size_t r = 1; r < records.size(); ++r) {
    const std::vector<std::string>& f = records[r].fields;
    const double p = std::stod(f.at(1));
    const int recorded = std::stoi(f.at(2));
    std::vector<double> w;
    if (recorded > 0)
      for (const auto& t : split_text(f.at(5), ';')) w.push_back(std::stod(t));
    std::sort(w.begin(), w.end());
    int distinct = w.empty() ? 0 : 1;
    for (std::size_t k = 1; k < w.size(); ++k)
      if (w[k] - w[k - 1] > kOrbitDistinctTolerance) ++distinct;
    nlohmann::ordered_json v;
    v["parameter"] = p;
    v["recorded"] = recorded;
    v["distinct"] = distinct;
    v["thetad_min"] = w.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(w.front());
    v["thetad_max"] = w.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(w.back());
    v["failure"] = f.at(7).empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(f.at(7));
    values.push_back(v);
    if (period_one && distinct == 1 && f.at(7).empty())
      until = p;
    else
      period_one = false;
    if (distinct > 1 && first_multiple.is_null()) first_multiple = p;
  }
  nlohmann::ordered_json j;
  j["distinct_tolerance"] = kOrbitDistinctTolerance;
  j["period_one_until"] = until;
  j["first_multiple"] = first_multiple;
  j["values"] = values;
  return j;
}

std::string orbit_summary_json(const std::string& points_csv) {
  return json_file_text(orbit_summary(points_csv));
}

}  // namespace flexgait::rimless
