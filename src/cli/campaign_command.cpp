#include "campaign_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>

#include "flexgait/campaign/campaign.hpp"
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
  std::vector<std::string> plot_metrics;  ///< --plot-metrics: campaign.png shows only these
};

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
  const Config base = resolve(experiment.schema, a.run);
  return campaign::Campaign(std::move(experiment), base, campaign::Grid(std::move(axes)));
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
  const SweepOutcome out = campaign::run_campaign(
      c, {a.run.out, a.jobs > 0 ? a.jobs : (mpi ? 1 : 0), a.resume, a.keep_runs, mpi.get()});
  if (mpi && !mpi->coordinator()) return 0;  // a worker rank: rank 0 reports
  const auto csv = std::filesystem::path(a.run.out) / "campaign.csv";
  if (a.run.plot) {
    std::vector<std::string> args{a.run.out};
    if (!a.plot_metrics.empty()) {
      std::string list;
      for (const auto& m : a.plot_metrics) list += (list.empty() ? "" : ",") + m;
      args.insert(args.end(), {"--metrics", list});
    }
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
    fmt::print("{}\n", j.dump(2));
  } else {
    fmt::print("campaign of {}, {} points: {} computed, {} resumed, {:.2f} s\n", c.experiment().name, c.size(),
               out.computed, out.resumed, out.seconds);
    fmt::print("results in {}\n", csv.string());
  }
  return 0;
}

}  // namespace

void add_campaign_command(CLI::App& app, std::function<int()>& action) {
  auto a = std::make_shared<CampaignArgs>();
  std::string names;
  for (const auto& n : campaign::experiment_names()) names += (names.empty() ? "" : ", ") + n;
  CLI::App* cmd = app.add_subcommand(
      "campaign", "Run an experiment at every point of a grid of configuration keys (Cartesian product of the --grid "
                  "axes): campaign.csv with one row per point, on all cores or over MPI ranks (mpirun), resumable");
  add_run_options(*cmd, a->run, "runs/campaign");
  cmd->get_option("--out")->description("directory for campaign.csv, config.yaml, campaign.png (and the partial file)");
  cmd->get_option("--json")->description("print the outcome (points, computed, resumed, seconds, csv) as JSON on stdout");
  cmd->add_option("experiment", a->experiment, "the experiment: " + names)->required();
  cmd->add_option("--grid", a->grid, "one axis: KEY=A:B:N (N values from A to B, ends included) or KEY=v1,v2,... "
                                     "(numbers or names, e.g. control.compensation=off,both); repeatable")
      ->required()
      ->type_name("KEY=VALUES")
      ->allow_extra_args(false);
  cmd->add_option("--jobs", a->jobs, "worker threads per process (0: all cores; under mpirun 0 means 1 per rank)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  cmd->add_flag("--resume", a->resume, "keep the finished points of an interrupted campaign of the same grid in --out");
  cmd->add_option("--plot-metrics", a->plot_metrics,
                  "campaign.png shows only these metrics, in this order; a third axis becomes the figure's rows "
                  "(one per value, shared colour scales), e.g. fell,pelvis_roll_error_max")
      ->delimiter(',')
      ->type_name("M1,M2,...");
  cmd->add_flag("--keep-runs", a->keep_runs, "also write each point's run files to OUT/runs/NNNNNN");
  cmd->callback([a, &action] { action = [a] { return run_campaign_command(*a); }; });
}

}  // namespace flexgait::cli
