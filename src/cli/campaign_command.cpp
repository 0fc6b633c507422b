#include "campaign_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "flexgait/campaign/campaign.hpp"
#include "flexgait/campaign/reduction.hpp"
#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/run_directory.hpp"
#include "flexgait/core/text.hpp"
#include "mpi_distributor.hpp"
#include "options.hpp"

namespace flexgait::cli {
namespace {

struct CampaignArgs {
  RunOptions run;
  std::string experiment;
  std::vector<std::string> grid;
  int jobs = 0;
  bool resume = false;
  bool keep_runs = false;
  double max_run_bytes = 1e10;            ///< --max-run-bytes: cap on the kept runs' projected size
  std::vector<std::string> plot_metrics;  ///< --plot-metrics: campaign.png shows only these
  std::vector<std::string> reduce;        ///< --reduce: axes reduced over in reduced.csv
  std::vector<std::string> random;        ///< --random KEY=A:B
  int samples = 0;                        ///< --samples: draws of the --random keys
  std::string seed;                       ///< --seed of the draws as given (default 1), checked by seed_check
};

/// The seed `text` spells in full: decimal digits only (no sign: CLI11's own reading takes -1 as
/// 2^64 - 1), at most 2^64 - 1; nullopt otherwise.
std::optional<std::uint64_t> parse_seed(const std::string& text) {
  std::uint64_t v = 0;
  const char* last = text.data() + text.size();
  const auto [end, ec] = std::from_chars(text.data(), last, v);
  if (text.empty() || text.front() < '0' || text.front() > '9' || ec != std::errc() || end != last) return std::nullopt;
  return v;
}

CLI::Validator seed_check() {
  return CLI::Validator(
      [](std::string& text) {
        return parse_seed(text) ? std::string()
                                : fmt::format("'{}' is not an integer in [0, {}]", one_line(text),
                                              std::numeric_limits<std::uint64_t>::max());
      },
      "INTEGER in [0, 2^64-1]");
}

std::string joined(const std::vector<std::string>& items) {
  return fmt::format("{}", fmt::join(items, ","));
}

/// Throws UsageError naming the first of `metrics` that is not a column of `experiment`.
void check_plot_metrics(const campaign::Experiment& experiment, const std::vector<std::string>& metrics) {
  for (const std::string& m : metrics)
    if (std::find(experiment.metrics.begin(), experiment.metrics.end(), m) == experiment.metrics.end()) {
      std::string allowed;
      for (const auto& k : experiment.metrics) allowed += (allowed.empty() ? "" : ", ") + k;
      throw UsageError(fmt::format("--plot-metrics: '{}' is not a metric of {}; allowed: {}", one_line(m),
                                   experiment.name, allowed));
    }
}

/// The campaign of the arguments, every point checked; nothing is written.
campaign::Campaign checked_campaign(const CampaignArgs& a) {
  campaign::Experiment experiment = campaign::find_experiment(a.experiment);
  check_plot_metrics(experiment, a.plot_metrics);
  std::vector<campaign::GridAxis> axes;
  for (const auto& text : a.grid) axes.push_back(campaign::parse_grid_axis(text));
  std::vector<campaign::RandomAxis> random_axes;
  for (const auto& text : a.random) random_axes.push_back(campaign::parse_random_axis(text));
  if (!a.seed.empty() && random_axes.empty())
    throw UsageError("--seed: given without a --random axis; add one, e.g. --random KEY=A:B");
  campaign::RandomDesign random(std::move(random_axes), a.samples, a.seed.empty() ? 1 : *parse_seed(a.seed));
  if (!random.empty()) axes.push_back(random.sample_axis());
  const Config base = resolve(experiment.schema, a.run);
  check_output_directory(a.run.out, "--out");  // a file, a device, a FIFO inside: refused before any work
  campaign::Grid grid(std::move(axes));
  campaign::check_reduction(grid, a.reduce);
  campaign::Campaign c(std::move(experiment), base, std::move(grid), std::move(random));
  if (a.keep_runs) campaign::check_kept_runs_size(c, a.max_run_bytes);
  return c;
}

int run_campaign_command(const CampaignArgs& a) {
  const std::unique_ptr<MpiRanks> mpi = mpi_distributor_if_launched();
  // Everything checked in every rank before anything is written. Under MPI the ranks agree on
  // the outcome: all go on, or all exit 2 and rank 0 alone says why (a node may fail alone, e.g.
  // on a --config it cannot read: rank 0 names that rank).
  std::optional<campaign::Campaign> checked;
  std::string error;
  try {
    checked.emplace(checked_campaign(a));
  } catch (const UsageError& e) {
    if (!mpi) throw;
    error = e.what();
  }
  if (mpi) error = mpi->first_error(error);
  if (!error.empty()) throw UsageError(error);
  const campaign::Campaign& c = *checked;
  std::optional<RunDirectory> directory;  // `complete` once reduced.csv and the figure are written too
  const SweepOutcome out = campaign::run_campaign(
      c, {a.run.out, a.jobs > 0 ? a.jobs : (mpi ? 1 : 0), a.resume, a.keep_runs, mpi.get(), &directory});
  if (mpi && !mpi->coordinator()) return 0;  // a worker rank: rank 0 reports
  const auto csv = std::filesystem::path(a.run.out) / "campaign.csv";
  const auto reduced = std::filesystem::path(a.run.out) / "reduced.csv";
  if (!a.reduce.empty())
    write_file_atomic(
        reduced, campaign::reduce_campaign_table(c.grid(), a.reduce, read_text_file(csv), c.random().axes().size()));
  if (a.run.plot) {
    std::vector<std::string> args{a.run.out};
    if (!a.plot_metrics.empty()) args.insert(args.end(), {"--metrics", joined(a.plot_metrics)});
    if (!a.reduce.empty()) args.insert(args.end(), {"--reduced", joined(a.reduce)});
    run_plot_script("plot_campaign.py", args);
  }
  if (a.run.json) {
    nlohmann::ordered_json j;
    j["experiment"] = c.experiment().name;
    j["points"] = c.size();
    j["computed"] = out.computed;
    j["resumed"] = out.resumed;
    j["seconds"] = out.seconds;
    j["csv"] = csv.string();
    if (!a.reduce.empty()) j["reduced"] = reduced.string();
    fmt::print("{}\n", j.dump(2));
  } else {
    fmt::print("campaign of {}, {} points: {} computed, {} resumed, {:.2f} s\n", c.experiment().name, c.size(),
               out.computed, out.resumed, out.seconds);
    fmt::print("results in {}\n", csv.string());
    if (!a.reduce.empty()) fmt::print("reduced over {} in {}\n", joined(a.reduce), reduced.string());
  }
  return 0;
}

}  // namespace

void add_campaign_command(CLI::App& app, std::function<int()>& action) {
  auto a = std::make_shared<CampaignArgs>();
  std::string names;
  for (const auto& n : campaign::experiment_names()) names += (names.empty() ? "" : ", ") + n;
  CLI::App* cmd = app.add_subcommand(
      "campaign",
      "Run an experiment at every point of a grid of configuration keys (Cartesian product of the --grid "
      "axes): campaign.csv with one row per point, on all cores or over MPI ranks (mpirun), resumable");
  add_run_options(*cmd, a->run, "runs/campaign");
  cmd->get_option("--out")->description("directory for campaign.csv, config.yaml, campaign.png (and the partial file)");
  cmd->get_option("--json")->description(
      "print the outcome (points, computed, resumed, seconds, csv) as JSON on stdout");
  cmd->add_option("experiment", a->experiment, "the experiment: " + names)->required();
  cmd->add_option("--grid", a->grid,
                  "one axis: KEY=A:B:N (N values from A to B, ends included) or KEY=v1,v2,... "
                  "(numbers or names, e.g. control.compensation=off,both); repeatable")
      ->type_name("KEY=VALUES")
      ->allow_extra_args(false);
  cmd->add_option("--random", a->random,
                  "a real key drawn uniformly from [A, B] at each of --samples samples (from --seed): KEY=A:B; "
                  "the samples are one more axis, `sample` (the last), crossed with the --grid axes; sample s "
                  "draws the same values at every grid point; repeatable")
      ->type_name("KEY=A:B")
      ->allow_extra_args(false);
  cmd->add_option("--samples", a->samples, "the number of samples of the --random keys")->check(CLI::Range(1, 100000));
  cmd->add_option("--seed", a->seed, "the seed of the --random draws, an integer in [0, 2^64-1] (default 1)")
      ->check(seed_check());
  cmd->add_option("--jobs", a->jobs, "worker threads per process (0: all cores; under mpirun 0 means 1 per rank)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  cmd->add_flag("--resume", a->resume, "keep the finished points of an interrupted campaign of the same grid in --out");
  cmd->add_option("--plot-metrics", a->plot_metrics,
                  "campaign.png shows only these metrics, in this order; a third axis becomes the figure's rows "
                  "(one per value, shared colour scales), e.g. fell,pelvis_roll_error_max")
      ->delimiter(',')
      ->type_name("M1,M2,...");
  cmd->add_option("--reduce", a->reduce,
                  "also write reduced.csv: the table reduced over these axes (e.g. the seeds, or `sample` of "
                  "--random axes), one row per value of the others: points, errors, M_fraction of each true/false "
                  "metric (fell_fraction: a fall rate), M_mean, M_min, M_max of each numeric one; with a figure")
      ->delimiter(',')
      ->type_name("KEY1,KEY2,...");
  cmd->add_flag("--keep-runs", a->keep_runs, "also write each point's run files to OUT/runs/NNNNNN");
  cmd->add_option("--max-run-bytes", a->max_run_bytes,
                  "with --keep-runs: a campaign whose kept run files could exceed this many bytes (each run's logs as "
                  "projected from its keys) is refused before it starts")
      ->check(positive_number())
      ->capture_default_str();
  cmd->callback([a, &action] { action = [a] { return run_campaign_command(*a); }; });
}

}  // namespace flexgait::cli
