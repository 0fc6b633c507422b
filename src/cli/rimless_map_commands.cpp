#include "rimless_map_commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/sweep_runner.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/rimless/basin.hpp"
#include "flexgait/rimless/gait_branch.hpp"
#include "flexgait/rimless/orbit_diagram.hpp"
#include "flexgait/rimless/wheel_setup.hpp"
#include "mpi_distributor.hpp"

namespace flexgait::cli {
namespace {

/// A resumed sweep must match the one in --out: checked before anything is written.
void check_resume(const MapRun& a, const std::string& name) {
  if (!a.resume) return;
  SweepJob probe;
  probe.dir = a.run.out;
  probe.name = name;
  probe.resume = true;
  probe.signature = "?";
  if (!std::filesystem::exists(probe.dir / (name + ".signature"))) check_resumable(probe);
}

/// A --branch file larger than this is refused before it is read (a branch of the default 2000 points
/// is ~1 MB; 256 MiB holds ~800,000).
constexpr std::uintmax_t kMaxBranchBytes = std::uintmax_t{256} << 20;

/// The --branch file's text: a branch.csv of `rimless continuation` in the same key, on the same
/// section, of the same wheel (its key, section and computed_at columns; gait_branch.hpp). A file
/// written before those columns were is drawn with a warning: it is only drawn, and the run
/// directories of earlier continuations stay usable.
std::string read_branch(const std::string& path, const std::string& param, const std::string& section,
                        const Config& config) {
  const auto bad = [&](const std::string& why) {
    return UsageError(
        fmt::format("--branch: '{}' {}; allowed: a branch.csv written by `flexgait rimless continuation "
                    "--param {} --section {}` with this configuration's sim.model and rimless.* keys",
                    one_line(path), why, param, section));
  };
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw bad("does not exist");
  if (!std::filesystem::is_regular_file(status))
    throw bad("is not a regular file (a directory, FIFO, socket or device)");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxBranchBytes)
    throw bad(fmt::format("has {} bytes, above the limit of {}", size, kMaxBranchBytes));
  const std::string text = read_text_file(path);
  const auto records = parse_csv(text);
  if (records.empty()) throw bad("cannot be read or is empty");
  const auto& h = records.front().fields;
  const auto column = [&](const char* name) { return std::find(h.begin(), h.end(), name) - h.begin(); };
  const auto width = static_cast<std::ptrdiff_t>(h.size());
  if (h.empty() || h.front() != "parameter" || column("thetad") == width || column("stable") == width)
    throw bad("has no parameter, thetad and stable columns");
  const std::ptrdiff_t key = column("key"), sec = column("section"), at = column("computed_at");
  if (key == width || sec == width || at == width) {
    fmt::print(stderr,
               "warning: --branch: '{}' does not say which key, section and wheel it was continued in (written "
               "before branch.csv had key, section and computed_at columns); drawn as a branch in {} on the "
               "{} section unchecked\n",
               one_line(path), param, section);
    return text;
  }
  if (records.size() < 2) throw bad("has no rows");
  const auto& first = records[1].fields;
  for (std::size_t i = 1; i < records.size(); ++i) {
    const auto& f = records[i].fields;
    if (f.size() != h.size())
      throw bad(fmt::format("line {} has {} fields where the header has {}", i + 1, f.size(), h.size()));
    if (f[key] != first[key] || f[sec] != first[sec] || f[at] != first[at])
      throw bad(fmt::format("line {} holds another branch than line 2 (key, section or computed_at differ)", i + 1));
  }
  if (first[key] != param)
    throw bad(fmt::format("was continued in {}, not in the requested --param {}", one_line(first[key], 80), param));
  if (first[sec] != section)
    throw bad(fmt::format("has fixed points on the {} section, not on the requested --section {}",
                          one_line(first[sec], 40), section));
  const std::vector<std::string> differ = rimless::computed_at_differences(first[at], config, param);
  if (!differ.empty()) {
    std::string list;
    for (std::size_t i = 0; i < differ.size() && i < 4; ++i) list += (i ? ", " : "") + differ[i];
    if (differ.size() > 4) list += fmt::format(" and {} more", differ.size() - 4);
    throw bad(fmt::format("was computed on another wheel: {}", list));
  }
  return text;
}

/// The orbit diagram's configuration, spec and --branch files, every option checked.
struct CheckedOrbit {
  rimless::WheelSetup setup;
  rimless::OrbitDiagramSpec spec;
  std::vector<std::string> branches;
};

CheckedOrbit checked_orbit(const MapRun& a, const CLI::App& cmd) {
  if (cmd.count("--param") == 0) throw UsageError("--param: required by analysis orbit-diagram; allowed: a real key");
  for (const char* o : {"--from", "--to", "--count"})
    if (cmd.count(o) == 0) throw UsageError(fmt::format("{}: required by analysis orbit-diagram", o));
  std::vector<ConfigEntry> extra;
  add_option_value(extra, cmd, "--transient", "analysis.orbit.transient", a.map.transient);
  add_option_value(extra, cmd, "--record", "analysis.orbit.record", a.map.record);
  rimless::WheelSetup s = rimless::wheel_setup(resolve(rimless::rimless_analysis_schema(), a.run, extra));
  const auto lengths = record_from_config<rimless::OrbitDiagramOptions>(s.config);
  rimless::check_sweep_param(s.config.schema(), a.map.param);
  if (a.from == a.to)
    throw UsageError(fmt::format("--to: {} equals --from; allowed: a value other than --from", format_number(a.to)));
  if (a.count < 2) throw UsageError(fmt::format("--count: {}; allowed: an integer >= 2", a.count));
  rimless::OrbitDiagramSpec spec{{a.map.param, a.from, a.to, a.count, a.section}, lengths.transient, lengths.record};
  rimless::check_orbit_diagram(s.config, spec);
  std::vector<std::string> branches;
  for (const auto& file : a.map.branches)
    branches.push_back(read_branch(file, a.map.param, std::string(name_of(a.section)), s.config));
  return {std::move(s), spec, std::move(branches)};
}

/// Under mpirun the ranks agree on the checks: all go on, or all exit 2 and rank 0 alone says why
/// (mpi_distributor.hpp). `check()` returns the checked setup; the resume check is rank 0's. Then
/// rank 0 alone makes the run directory (with config.yaml) and writes files.
template <class Checked, class Check>
Checked checked_on_every_rank(MpiRanks* mpi, const MapRun& a, const std::string& name, const Check& check,
                              const Config& (*config_of)(const Checked&), std::optional<RunDirectory>& made) {
  std::optional<Checked> checked;
  std::string error;
  try {
    checked.emplace(check());
    if (mpi == nullptr || mpi->coordinator()) check_resume(a, name);
  } catch (const UsageError& e) {
    if (mpi == nullptr) throw;
    error = e.what();
  }
  if (mpi != nullptr) error = mpi->first_error(error);
  if (!error.empty()) throw UsageError(error);
  if (mpi == nullptr || mpi->coordinator()) {
    made.emplace(a.run.out);
    made->write_config(config_of(*checked));
  }
  return std::move(*checked);
}

int orbit_diagram(const MapRun& a, const CLI::App& cmd) {
  // Under mpirun the parameter values are spread over the ranks as the basin's cells are.
  const std::unique_ptr<MpiRanks> mpi = mpi_distributor_if_launched();
  std::optional<RunDirectory> made;
  const CheckedOrbit checked = checked_on_every_rank<CheckedOrbit>(
      mpi.get(), a, "orbit_points", [&] { return checked_orbit(a, cmd); },
      +[](const CheckedOrbit& c) -> const Config& { return c.setup.config; }, made);
  const rimless::WheelSetup& s = checked.setup;
  const rimless::OrbitDiagramSpec& spec = checked.spec;
  SweepJob job;
  job.dir = a.run.out;
  job.distributor = mpi.get();
  job.name = "orbit_points";
  job.header = rimless::orbit_points_header();
  job.count = spec.sweep.count;
  job.jobs = a.jobs > 0 ? a.jobs : (mpi ? 1 : 0);
  job.resume = a.resume;
  job.signature = fmt::format("orbit-diagram {} {} {} {} {} transient {} record {}\n{}", spec.sweep.param,
                              format_number(spec.sweep.from), format_number(spec.sweep.to), spec.sweep.count,
                              name_of(a.section), spec.transient, spec.record, s.config.to_yaml());
  const Config base = s.config;
  job.row = [base, spec](int i) { return rimless::orbit_points_row(base, spec, i); };
  job.valid_row = [spec](int i, const std::vector<std::string>& cells) {
    return rimless::orbit_points_row_valid(spec, i, cells);
  };
  const SweepOutcome out = run_sweep(job);
  if (mpi && !mpi->coordinator()) return 0;  // a worker rank: rank 0 reports
  const RunDirectory& dir = *made;
  const std::string points = read_text_file(dir.path() / "orbit_points.csv");
  dir.write("orbit.csv", rimless::orbit_csv(points));
  dir.write("summary.json", rimless::orbit_summary_json(points));
  for (std::size_t k = 0; k < checked.branches.size(); ++k)
    dir.write(fmt::format("branch_{}.csv", k + 1), checked.branches[k]);
  if (a.run.plot) run_plot_script("plot_analysis.py", {"orbit-diagram", dir.path().string(), spec.sweep.param});
  fmt::print(
      "orbit diagram of {} over [{}, {}], {} values x {} crossings after {} steps: {} computed, {} resumed, "
      "{:.2f} s\n",
      spec.sweep.param, format_number(spec.sweep.from), format_number(spec.sweep.to), spec.sweep.count, spec.record,
      spec.transient, out.computed, out.resumed, out.seconds);
  fmt::print("wrote {}\n", (dir.path() / "orbit.csv").string());
  return 0;
}

/// The basin's configuration and grid, every option checked.
std::pair<rimless::WheelSetup, rimless::BasinSpec> checked_basin(const MapRun& a, const CLI::App& cmd) {
  for (const char* o : {"--x", "--y", "--x-range", "--y-range"})
    if (cmd.count(o) == 0) throw UsageError(fmt::format("{}: required by analysis basin", o));
  std::vector<ConfigEntry> extra;
  add_option_value(extra, cmd, "--steps-limit", "analysis.basin.steps_limit", a.map.steps_limit);
  add_option_value(extra, cmd, "--tolerance", "analysis.basin.tolerance", a.map.tolerance);
  rimless::WheelSetup s = rimless::wheel_setup(resolve(rimless::rimless_analysis_schema(), a.run, extra));
  const auto limits = record_from_config<rimless::BasinOptions>(s.config);
  rimless::BasinSpec spec;
  spec.x = rimless::parse_basin_axis("--x-range", a.map.x, a.map.x_range);
  spec.y = rimless::parse_basin_axis("--y-range", a.map.y, a.map.y_range);
  spec.steps_limit = limits.steps_limit;
  spec.tolerance = limits.tolerance;
  spec.no_landing_limit = limits.no_landing_limit;
  spec.section = a.section;
  rimless::check_basin(s.config, spec);
  return {std::move(s), spec};
}

int basin(const MapRun& a, const CLI::App& cmd) {
  // Under mpirun the cells are spread over the ranks (mpi_distributor.hpp).
  const std::unique_ptr<MpiRanks> mpi = mpi_distributor_if_launched();
  using Checked = std::pair<rimless::WheelSetup, rimless::BasinSpec>;
  std::optional<RunDirectory> made;
  const Checked checked = checked_on_every_rank<Checked>(
      mpi.get(), a, "basin", [&] { return checked_basin(a, cmd); },
      +[](const Checked& c) -> const Config& { return c.first.config; }, made);
  const rimless::WheelSetup& s = checked.first;
  const rimless::BasinSpec& spec = checked.second;
  // Every rank finds the same reference (the same configuration, deterministic Newton).
  const rimless::BasinReference ref = rimless::basin_reference(s.config, spec.section);
  SweepJob job;
  job.dir = a.run.out;
  job.distributor = mpi.get();
  job.name = "basin";
  job.header = rimless::basin_header();
  job.count = static_cast<int>(spec.cells());  // at most kMaxBasinCells (check_basin)
  job.jobs = a.jobs > 0 ? a.jobs : (mpi ? 1 : 0);
  job.resume = a.resume;
  job.signature = fmt::format("basin {} {}:{}:{} {} {}:{}:{} steps {} tolerance {} {}\n{}", spec.x.key,
                              format_number(spec.x.from), format_number(spec.x.to), spec.x.count, spec.y.key,
                              format_number(spec.y.from), format_number(spec.y.to), spec.y.count, spec.steps_limit,
                              format_number(spec.tolerance), name_of(a.section), s.config.to_yaml());
  const Config base = s.config;
  job.row = [base, spec, ref](int i) { return rimless::basin_row(base, spec, ref, i); };
  job.valid_row = [spec](int i, const std::vector<std::string>& cells) {
    return rimless::basin_row_valid(spec, i, cells);
  };
  const SweepOutcome out = run_sweep(job);
  if (mpi && !mpi->coordinator()) return 0;  // a worker rank: rank 0 reports
  const RunDirectory& dir = *made;
  const auto counts = rimless::basin_counts(read_text_file(dir.path() / "basin.csv"));
  const std::string area_unit =
      fmt::format("({}) x ({})", s.config.schema().find(spec.x.key)->unit, s.config.schema().find(spec.y.key)->unit);
  dir.write("summary.json", rimless::basin_summary_json(spec, ref, counts, area_unit));
  const rimless::BasinSize size = rimless::basin_size(spec, counts);
  if (a.run.plot) run_plot_script("plot_analysis.py", {"basin", dir.path().string()});
  if (!ref.found)
    fmt::print(stderr,
               "warning: no reference gait (Newton from the configured initial state: {}); no cell can "
               "converge\n",
               one_line(ref.failure, 300));
  fmt::print(
      "basin over {} x {} ({} cells): {} converged to the '{}' gait ({:.4f} of the grid, area {:.6g} {}), "
      "{} computed, {} resumed, {:.2f} s\n",
      spec.x.key, spec.y.key, spec.cells(), size.converged, ref.gait, size.fraction, size.area(), area_unit,
      out.computed, out.resumed, out.seconds);
  fmt::print("wrote {}\n", (dir.path() / "basin.csv").string());
  return 0;
}

}  // namespace

void add_map_options(CLI::App& anc, MapOptions& o) {
  anc.add_option("--param", o.param,
                 "orbit-diagram: real configuration key to vary (e.g. rimless.slope), or "
                 "rimless.mu for mu_s = mu_k");
  const rimless::OrbitDiagramOptions orbit;
  const rimless::BasinOptions basin;
  anc.add_option("--transient", o.transient,
                 fmt::format("orbit-diagram: steps simulated before the first recorded "
                             "crossing; sets analysis.orbit.transient ({})",
                             orbit.transient))
      ->type_name("INT");
  anc.add_option("--record", o.record,
                 fmt::format("orbit-diagram: section crossings recorded at each value; sets "
                             "analysis.orbit.record ({})",
                             orbit.record))
      ->type_name("INT");
  anc.add_option("--branch", o.branches,
                 "orbit-diagram: a branch.csv of `rimless continuation` in the same key, "
                 "section and wheel (checked), copied to branch_K.csv and drawn over the dots (stable solid, unstable "
                 "dashed); repeat for more branches")
      ->allow_extra_args(false);
  anc.add_option("--x", o.x, "basin: key of the initial state on the x axis (initial.omega or initial.beta)");
  anc.add_option("--y", o.y, "basin: key of the initial state on the y axis");
  anc.add_option("--x-range", o.x_range, "basin: FROM:TO:COUNT of the x key (its unit)")->type_name("A:B:N");
  anc.add_option("--y-range", o.y_range, "basin: FROM:TO:COUNT of the y key (its unit)")->type_name("A:B:N");
  anc.add_option("--steps-limit", o.steps_limit,
                 fmt::format("basin: section crossings simulated per cell at most; "
                             "sets analysis.basin.steps_limit ({})",
                             basin.steps_limit))
      ->type_name("INT");
  anc.add_option("--tolerance", o.tolerance,
                 fmt::format("basin: converged when every section-state component is "
                             "within this fraction of its scale (sqrt(g L0), sqrt(g/L0), "
                             "alpha) of the gait's; sets analysis.basin.tolerance ({})",
                             format_number(basin.tolerance)))
      ->type_name("FLOAT");
}

const std::vector<std::string>& map_option_names() {
  static const std::vector<std::string> names{"--param", "--transient", "--record",  "--branch",      "--x",
                                              "--y",     "--x-range",   "--y-range", "--steps-limit", "--tolerance"};
  return names;
}

int run_map_analysis(const MapRun& a, const CLI::App& cmd) {
  return a.name == "basin" ? basin(a, cmd) : orbit_diagram(a, cmd);
}

}  // namespace flexgait::cli
