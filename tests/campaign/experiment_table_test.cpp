// The campaign's experiments: every name is found and an unknown one is refused naming them all;
// each experiment's metrics (campaign.csv's columns) are exactly the keys of the summary a run
// returns, in the summary's order (a renamed or added summary field breaks this test, not a map),
// less only the fields a record leaves out when they do not apply.
#include "flexgait/campaign/experiment_table.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

namespace flexgait::campaign {
namespace {

std::vector<std::string> summary_keys(const Experiment& e, const std::vector<std::string>& overrides) {
  const Config c = resolve_config(e.schema, std::nullopt, overrides);
  e.check(c);
  std::vector<std::string> keys;
  const nlohmann::ordered_json json = e.run(c, {});
  for (const auto& item : json.items()) keys.push_back(item.key());
  return keys;
}

// The summary's keys are the metrics in order, with at most `optional` metrics left out.
void expect_keys_are_metrics(const Experiment& e, const std::vector<std::string>& keys, std::size_t optional = 0) {
  std::vector<std::string> expected;
  for (const auto& m : e.metrics)
    if (std::find(keys.begin(), keys.end(), m) != keys.end()) expected.push_back(m);
  EXPECT_EQ(keys, expected) << e.name << ": a summary key that is not a metric, or out of order";
  EXPECT_LE(e.metrics.size() - keys.size(), optional) << e.name;
}

TEST(ExperimentTable, FindsEveryNameAndRefusesOthersListingThem) {
  for (const auto& name : experiment_names()) EXPECT_EQ(find_experiment(name).name, name);
  try {
    find_experiment("humanoid-run");
    FAIL() << "humanoid-run found";
  } catch (const UsageError& e) {
    for (const auto& name : experiment_names())
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
  }
}

TEST(ExperimentTable, RimlessSummariesHaveTheMetricsAsKeys) {
  const Experiment sim = find_experiment("rimless-simulate");
  expect_keys_are_metrics(sim, summary_keys(sim, {"sim.model=rigid", "sim.steps=3"}));
  const Experiment fp = find_experiment("rimless-fixed-point");
  expect_keys_are_metrics(fp, summary_keys(fp, {"sim.model=rigid"}));
}

TEST(ExperimentTable, HumanoidSummariesHaveTheMetricsAsKeys) {
  const Experiment walk = find_experiment("humanoid-walk");
  // Unpushed, standing, not failed, the builtin (no joint ranges): push_impulse, capture_point_bound,
  // fall_time, failure_time, joint_limit_hits and desired_range_hits do not apply.
  expect_keys_are_metrics(walk, summary_keys(walk, {"walk.steps=1"}), 6);
  const Experiment push = find_experiment("humanoid-push-recovery");
  expect_keys_are_metrics(push, summary_keys(push, {"push_recovery.upper=1", "push_recovery.settle_time=0.5"}));
}

}  // namespace
}  // namespace flexgait::campaign
