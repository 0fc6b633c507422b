// The stiffness bench's files (experiments/bench_output.hpp) from a hand-made result: bench.csv
// has a row per pose of both sweeps, uncompensated first, with the errors as differences of its
// own columns; summary.json is the result's record.
#include "flexgait/experiments/bench_output.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flexgait/core/text.hpp"
#include "flexgait/experiments/stiffness_bench.hpp"

namespace flexgait::experiments {
namespace {

// The cells of each line of a CSV text without quoted fields.
std::vector<std::vector<std::string>> rows(const std::string& csv) {
  std::vector<std::vector<std::string>> out;
  for (const std::string& line : split_text(csv, '\n'))
    if (!line.empty()) out.push_back(split_text(line, ','));
  return out;
}

BenchResult made_result() {
  BenchResult r;
  for (int i = 0; i < 3; ++i) {
    BenchSample s;
    s.command = 0.1 * i;
    s.encoder = 0.1 * i + 0.001;
    s.link = 0.1 * i + 0.04;
    s.gravity_torque = 40.0 - i;
    s.newton_iterations = 2 + i;
    r.uncompensated.push_back(s);
    s.link = 0.1 * i + 0.0005;
    r.compensated.push_back(s);
  }
  r.k_true = 1000.0;
  r.k_fit = 990.0;
  r.r_squared = 0.999;
  return r;
}

TEST(BenchOutput, CsvHasARowPerPoseOfBothSweeps) {
  const BenchResult r = made_result();
  const auto t = rows(bench_csv(r));
  ASSERT_EQ(t.size(), 1u + 6u);
  ASSERT_EQ(t[0].size(), 10u);
  EXPECT_EQ(t[0][0], "compensated");
  EXPECT_EQ(t[0][9], "newton_iterations");
  for (std::size_t i = 1; i < t.size(); ++i) {
    ASSERT_EQ(t[i].size(), 10u) << i;
    EXPECT_EQ(t[i][0], i <= 3 ? "false" : "true") << i;
    // link − encoder and link − command from the row's own cells (printed shortest round trip:
    // the differences agree to rounding, 1e-15 rad).
    const double command = std::stod(t[i][1]), encoder = std::stod(t[i][2]), link = std::stod(t[i][3]);
    EXPECT_NEAR(std::stod(t[i][5]), link - encoder, 1e-15) << i;
    EXPECT_NEAR(std::stod(t[i][6]), link - command, 1e-15) << i;
  }
  EXPECT_EQ(t[3][9], "4");
}

TEST(BenchOutput, SummaryIsTheResultsRecord) {
  const nlohmann::json j = nlohmann::json::parse(bench_summary_json(made_result()));
  EXPECT_EQ(j["k_true"], 1000.0);
  EXPECT_EQ(j["k_fit"], 990.0);
  EXPECT_EQ(j["r_squared"], 0.999);
  EXPECT_FALSE(j.contains("uncompensated"));  // the sweeps go to bench.csv
}

}  // namespace
}  // namespace flexgait::experiments
