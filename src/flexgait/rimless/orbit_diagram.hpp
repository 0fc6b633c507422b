#pragma once
/// \file orbit_diagram.hpp
/// Orbit diagram of the wheel (docs/guide/rimless.md, "Orbit diagram and basin of attraction"; Garcia et al. 1998, Fig.
/// 4): at each value of one real
/// configuration key, the Poincaré-section states of `record` successive steps after `transient`
/// steps from the configured initial state, by brute-force simulation (no Newton) that carries the
/// full hybrid state from crossing to crossing (SectionWalk, poincare.hpp). A stable
/// fixed point shows as one dot per value, a period-k orbit as k dots, chaos as a smear.
/// Points are independent: the command line runs them on the sweep runner (all cores, resumable,
/// the same bytes for any number of threads). sim.max_time does not limit these runs: their length is
/// their number of steps.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/record.hpp"
#include "flexgait/rimless/sweep.hpp"

namespace flexgait::rimless {

/// The diagram's lengths (keys analysis.orbit.*; --transient and --record set them).
struct OrbitDiagramOptions {
  int transient = 100;  ///< steps simulated from the initial state before the first recorded crossing
  int record = 30;      ///< section crossings recorded at each value

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("analysis.orbit.transient", s.transient,
      {.doc = "orbit-diagram: steps simulated before the first recorded crossing (--transient)",
       .bounds = closed(1, 100000000)});
    v("analysis.orbit.record", s.record,
      {.doc = "orbit-diagram: section crossings recorded at each value (--record)", .bounds = closed(1, 1000000)});
  }
};
inline Schema orbit_diagram_schema() {
  return schema_of<OrbitDiagramOptions>();
}

struct OrbitDiagramSpec {
  SweepSpec sweep;                                  ///< the key, its values (from, to, count) and the section
  int transient = OrbitDiagramOptions{}.transient;  ///< steps simulated before the first recorded crossing
  int record = OrbitDiagramOptions{}.record;        ///< section crossings recorded at each value
};

/// Throws ConfigError (naming --transient or --record) unless transient >= 1 and record >= 1.
void check_orbit_diagram(const Config& base, const OrbitDiagramSpec& spec);

/// The sweep runner's CSV of one value (orbit_points.csv, without the index):
///   value, recorded (crossings recorded), modes, gaits, thetad (θ̇ at each crossing [rad/s]),
///   states (each crossing's reduced state, components separated by spaces), failure.
/// The lists hold one entry per recorded crossing, separated by ';'. Thread-safe.
std::string orbit_points_header();
std::string orbit_points_row(const Config& base, const OrbitDiagramSpec& spec, int i);
/// Whether `cells` (a resumed row, after its index) could be orbit_points_row(…, i): value i's, a
/// count recorded in [0, record] with as many modes, gaits, thetad (numbers) and states (numbers
/// joined by ' ') joined by ';', and a failure named exactly when fewer than `record` were recorded.
bool orbit_points_row_valid(const OrbitDiagramSpec& spec, int i, const std::vector<std::string>& cells);

/// orbit.csv, one row per recorded crossing, from orbit_points.csv's text (with its index column):
///   parameter, step (1 = the first crossing after the transient), mode (the stance foot's at
///   the section), gait (stance-foot phases of the step that ended there), thetad [rad/s],
///   state (components separated by ';', named by mode as SectionState::names), failure (why
///   the record of this value stopped early; empty otherwise). A value that recorded nothing
///   has one row with an empty step and its failure.
std::string orbit_csv(const std::string& points_csv);

/// Two recorded θ̇ at the section count as one value of the orbit when they differ by no more than
/// this [rad/s] (a period-1 orbit: 1 value; period k: k; chaos or a runaway: about `record`).
inline constexpr double kOrbitDistinctTolerance = 1e-4;

/// summary.json of the diagram, from orbit_points.csv's text: `values`, one record per parameter
/// value (parameter, recorded, distinct: the number of θ̇ values more than kOrbitDistinctTolerance
/// apart, thetad_min, thetad_max [rad/s], failure or null); `period_one_until`: the last value,
/// walking from --from, before the first with distinct > 1 or a failure (null if the first is such a
/// value); `first_multiple`: that first value with distinct > 1 (null if none).
nlohmann::ordered_json orbit_summary(const std::string& points_csv);
/// summary.json: orbit_summary's text.
std::string orbit_summary_json(const std::string& points_csv);

}  // namespace flexgait::rimless
