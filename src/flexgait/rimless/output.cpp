#include "flexgait/rimless/output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/record_json.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait::rimless {
namespace {

std::vector<std::string> log_columns() {
  std::vector<std::string> cols{"t", "x", "y", "theta", "xd", "yd", "thetad"};
  for (int i = 1; i <= kMaxContacts; ++i)
    for (const char* c : {"leg", "phase", "N", "T", "c", "cdot"}) cols.push_back(fmt::format("{}{}", c, i));
  for (const char* c : {"E_kinetic", "E_gravity", "E_spring", "E_total", "W_damp", "W_fric", "balance"})
    cols.emplace_back(c);
  return cols;
}
const std::vector<std::string> kEventColumns{"t", "kind", "leg", "modes"};
const std::vector<std::string> kStepColumns{"step",         "stance_leg", "t_start",        "t_end",
                                            "duration",     "x_start",    "x_end",          "speed",
                                            "energy_start", "gait",       "contact_phases", "complete"};

// One row of log.csv; e0 = the run's initial mechanical energy [J]. Writer: CsvWriter or Table.
template <class Writer>
void log_row(Writer& csv, const LogSample& s, double e0) {
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

}  // namespace

std::vector<std::string> log_column_names() {
  return log_columns();
}

std::vector<double> log_values(const LogSample& sample, double e0) {
  Table row(log_columns());
  log_row(row, sample, e0);
  std::vector<double> out;
  for (const Table::Column& c : row.columns())
    out.push_back(c.numbers.empty() ? std::numeric_limits<double>::quiet_NaN() : c.numbers.front());
  return out;
}

namespace {

template <class Writer>
void event_row(Writer& csv, const EventRecord& e) {
  csv.cell(e.t).cell(run_event_name(e.kind)).cell(static_cast<long long>(e.leg));
  csv.cell(e.kind == RunEvent::Failure ? e.message : describe_contacts(e.contacts)).end_row();
}

template <class Writer>
void step_row(Writer& csv, const StepRecord& s) {
  const double dt = s.t_end - s.t_start;
  csv.cell(static_cast<long long>(s.index)).cell(static_cast<long long>(s.stance_leg)).cell(s.t_start).cell(s.t_end);
  csv.cell(dt).cell(s.x_start).cell(s.x_end).cell(dt > 0 ? (s.x_end - s.x_start) / dt : 0.0).cell(s.energy_start);
  csv.cell(step_gait(s)).cell(gait_label(s.contact)).cell(s.complete ? "true" : "false").end_row();
}

template <class Writer>
Writer log_rows(const SimulationResult& r) {
  Writer w(log_columns());
  for (const auto& s : r.samples) log_row(w, s, r.energy_initial);
  return w;
}

template <class Writer>
Writer event_rows(const SimulationResult& r) {
  Writer w(kEventColumns);
  for (const auto& e : r.events) event_row(w, e);
  return w;
}

template <class Writer>
Writer step_rows(const SimulationResult& r) {
  Writer w(kStepColumns);
  for (const auto& s : r.steps) step_row(w, s);
  return w;
}

// The longest run the options allow [s]: the time limit, or every step at its own limit.
double log_horizon(const SimulationOptions& o) {
  return std::min(o.max_time, static_cast<double>(o.steps) * o.max_step_time);
}

}  // namespace

double projected_log_bytes(const SimulationOptions& o) {
  // Measured at the spec's parameters, 20 steps: flexible 379 bytes a row, 2 rows per event, 59
  // events (7866 rows over 7.75 s at 1 ms); rigid 319-327 bytes a row, 3 rows a step.
  constexpr double kRowBytes = 400, kRowsPerStep = 6;
  return kRowBytes * (std::floor(log_horizon(o) / o.sample_dt) + 1 + kRowsPerStep * o.steps);
}

void check_log_size(const SimulationOptions& o) {
  const double bytes = projected_log_bytes(o);
  if (bytes <= o.max_log_bytes) return;
  throw ConfigError(
      "sim.sample_dt",
      fmt::format("key 'sim.sample_dt' = {} s: the log could reach {:.3g} bytes (about 400 bytes a row, a "
                  "row every sim.sample_dt over {} s and 6 a step for {} steps), above sim.max_log_bytes "
                  "= {:.3g}; allowed: a larger sim.sample_dt, a smaller sim.max_time or sim.steps, or "
                  "sim.max_log_bytes raised to at least {:.3g}",
                  format_number(o.sample_dt), bytes, format_number(log_horizon(o)), o.steps, o.max_log_bytes, bytes));
}

std::string log_csv(const SimulationResult& r) {
  return log_rows<CsvWriter>(r).str();
}
std::string events_csv(const SimulationResult& r) {
  return event_rows<CsvWriter>(r).str();
}
std::string steps_csv(const SimulationResult& r) {
  return step_rows<CsvWriter>(r).str();
}
Table log_table(const SimulationResult& r) {
  return log_rows<Table>(r);
}
Table events_table(const SimulationResult& r) {
  return event_rows<Table>(r);
}
Table steps_table(const SimulationResult& r) {
  return step_rows<Table>(r);
}

nlohmann::ordered_json simulation_summary(const SimulationResult& r, const std::string& model) {
  nlohmann::ordered_json j;
  j["model"] = model;
  add_record_json(j, r);
  return j;
}

std::string summary_json(const SimulationResult& r, const std::string& model) {
  return json_file_text(simulation_summary(r, model));
}

void write_run(const RunDirectory& dir, const SimulationResult& result, const std::string& model) {
  dir.write("log.csv", log_csv(result));
  dir.write("events.csv", events_csv(result));
  dir.write("steps.csv", steps_csv(result));
  dir.write("summary.json", summary_json(result, model));
}

// A CSV file built a piece at a time: rows collect in `csv` and go to the temporary file when
// they pass kPiece bytes.
struct RunFiles::File {
  static constexpr std::size_t kPiece = std::size_t{1} << 20;
  File(const std::filesystem::path& path, const std::vector<std::string>& columns) : file(path), csv(columns) {}
  void row_done() {
    if (csv.str().size() >= kPiece) flush();
  }
  void flush() {
    file.append(csv.str());
    csv.clear();
  }
  AtomicFileWriter file;
  CsvWriter csv;
};

RunFiles::RunFiles(const RunDirectory& dir)
    : log_(std::make_unique<File>(dir.path() / "log.csv", log_columns())),
      events_(std::make_unique<File>(dir.path() / "events.csv", kEventColumns)),
      steps_(std::make_unique<File>(dir.path() / "steps.csv", kStepColumns)) {}

RunFiles::~RunFiles() = default;

void RunFiles::on_start(double energy_initial) {
  energy_initial_ = energy_initial;
}

void RunFiles::on_sample(const LogSample& sample) {
  log_row(log_->csv, sample, energy_initial_);
  log_->row_done();
}

void RunFiles::on_event(const EventRecord& event) {
  event_row(events_->csv, event);
  events_->row_done();
}

void RunFiles::on_step(const StepRecord& step) {
  step_row(steps_->csv, step);
  steps_->row_done();
}

void RunFiles::finish() {
  for (File* f : {log_.get(), events_.get(), steps_.get()}) {
    f->flush();
    f->file.commit();
  }
}

}  // namespace flexgait::rimless
