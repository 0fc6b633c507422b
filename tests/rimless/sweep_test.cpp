// One point of a parameter sweep (rimless/sweep.hpp): the points' values, the checks of a sweep
// before anything runs (each error naming --param, --from, --to or its point), rimless.mu setting
// both coefficients, and a row of the rigid wheel against McGeer's closed form.
#include "flexgait/rimless/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "flexgait/core/text.hpp"
#include "flexgait/rimless/rigid_wheel.hpp"
#include "flexgait/rimless/wheel_setup.hpp"

namespace flexgait::rimless {
namespace {

Config configured(const std::vector<std::string>& sets) {
  return resolve_config(rimless_analysis_schema(), std::nullopt, sets);
}

TEST(Sweep, PointsRunFromToInclusiveAndOnePointIsFrom) {
  SweepSpec spec{.param = "rimless.slope", .from = 0.05, .to = 0.15, .count = 5};
  EXPECT_EQ(spec.value(0), 0.05);
  EXPECT_EQ(spec.value(4), 0.15);
  EXPECT_NEAR(spec.value(2), 0.1, 1e-17);
  spec.count = 1;
  EXPECT_EQ(spec.value(0), 0.05);
}

TEST(Sweep, ParamMustBeARealKeyOrMu) {
  const Schema schema = rimless_analysis_schema();
  EXPECT_NO_THROW(check_sweep_param(schema, "rimless.mu"));
  EXPECT_NO_THROW(check_sweep_param(schema, "rimless.K"));
  EXPECT_THROW(check_sweep_param(schema, "rimless.nonsense"), ConfigError);
  EXPECT_THROW(check_sweep_param(schema, "rimless.legs"), ConfigError);  // an integer
}

TEST(Sweep, MuSetsBothCoefficientsAndValuesAreCheckedAsASet) {
  const Config c = config_at(configured({}), "rimless.mu", "0.25", "sweep point 3");
  EXPECT_EQ(wheel_from_config(c).mu_s, 0.25);
  EXPECT_EQ(wheel_from_config(c).mu_k, 0.25);
  EXPECT_EQ(c.origin("rimless.mu_k"), "sweep point 3");
  // μ_s below the configured μ_k = 0.6: refused as --set rimless.mu_s=0.3 would be.
  try {
    config_at(configured({}), "rimless.mu_s", "0.3", "--to");
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "rimless.mu_k");
  }
}

TEST(Sweep, CheckSweepNamesTheOffendingEnd) {
  const Config base = configured({});
  // The slope is bounded by π/4: an end beyond it is refused, the error naming the option.
  const SweepSpec spec{.param = "rimless.slope", .from = 0.05, .to = 1.0, .count = 3};
  try {
    check_sweep(base, spec);
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--to"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(check_sweep(base, SweepSpec{.param = "rimless.slope", .from = 0.05, .to = 0.15, .count = 3}));
}

// The rigid point-mass wheel: the row's fixed point is McGeer's ω* and its multiplier cos²(2α)
// (rigid_wheel.hpp), to Newton's tolerance (1e-10) with margin: 1e-8.
TEST(Sweep, RigidRowHasMcGeersFixedPoint) {
  const Config base = configured({"sim.model=rigid", "rimless.I=0"});
  const SweepSpec spec{.param = "rimless.slope", .from = 0.08, .to = 0.12, .count = 2};
  const auto header = split_text(sweep_header(), ',');
  for (int i = 0; i < spec.count; ++i) {
    const auto row = split_text(sweep_row(base, spec, i), ',');
    ASSERT_EQ(row.size(), header.size()) << sweep_row(base, spec, i);
    auto column = [&](const std::string& name) {
      for (std::size_t k = 0; k < header.size(); ++k)
        if (header[k] == name) return row[k];
      ADD_FAILURE() << "no column " << name;
      return std::string();
    };
    WheelParams w = wheel_from_config(base);
    w.slope = spec.value(i);
    EXPECT_EQ(std::stod(column("value")), spec.value(i));
    EXPECT_EQ(column("converged"), "true");
    EXPECT_EQ(column("stable"), "true");
    EXPECT_NEAR(std::stod(column("state")), rigid_step_map(w).fixed_point(), 1e-8);
    EXPECT_NEAR(std::stod(column("max_multiplier")), std::pow(std::cos(2 * w.alpha()), 2), 1e-8);
    EXPECT_EQ(column("failure"), "");
  }
}

// Below tan(slope) the wheel slides away and has no fixed point: the row's multiplier, period,
// speed and energy are empty cells (a reader takes them as missing), never 0 (a number).
TEST(Sweep, RowWithoutFixedPointHasEmptyNumbers) {
  const Config base = configured({});
  const SweepSpec spec{.param = "rimless.mu", .from = 0.05, .to = 0.05, .count = 1};
  const auto header = split_text(sweep_header(), ',');
  const auto records = parse_csv(sweep_row(base, spec, 0) + "\n");
  ASSERT_EQ(records.size(), 1u);
  const auto& row = records[0].fields;
  ASSERT_EQ(row.size(), header.size()) << records[0].text;
  for (std::size_t k = 0; k < header.size(); ++k) {
    if (header[k] == "converged") {
      EXPECT_EQ(row[k], "false");
    }
    if (header[k] == "failure") {
      EXPECT_NE(row[k], "");
    }
    for (const char* empty : {"max_multiplier", "period", "speed", "dissipated_per_cycle"}) {
      if (header[k] == empty) {
        EXPECT_EQ(row[k], "") << empty;
      }
    }
  }
}

// A resumed row is kept only if sweep_row could have written it for its point: the rows written
// (a converged point, and one whose transient fails: a flat slope where the rigid wheel stops)
// pass; the same row under another index, or with one cell damaged, does not.
TEST(Sweep, ARowIsValidOnlyAsItsOwnPointsRow) {
  const Config base = configured({"sim.model=rigid", "rimless.I=0"});
  const SweepSpec spec{.param = "rimless.slope", .from = 0.0, .to = 0.1, .count = 2};
  const auto cells = [](const std::string& row) { return parse_csv(row + "\n").front().fields; };
  const auto failed = cells(sweep_row(base, spec, 0)), walked = cells(sweep_row(base, spec, 1));
  ASSERT_EQ(failed[4], "false");
  ASSERT_EQ(walked[4], "true");
  EXPECT_TRUE(sweep_row_valid(spec, 0, failed));
  EXPECT_TRUE(sweep_row_valid(spec, 1, walked));
  EXPECT_FALSE(sweep_row_valid(spec, 0, walked));  // the value is point 1's
  const std::vector<std::pair<std::size_t, std::string>> damage{{2, "fast"}, {2, ""},    {4, "yes"}, {6, "1.5;x"},
                                                                {7, "0.5"},  {8, "1e"},  {9, "1"},   {11, "0x10"},
                                                                {15, "2.0"}, {15, "-1"}, {15, ""},   {16, "fell over"}};
  for (const auto& [column, text] : damage) {
    auto row = walked;
    row[column] = text;
    EXPECT_FALSE(sweep_row_valid(spec, 1, row)) << "cell " << column << " = '" << text << "'";
  }
  auto fewer = walked;
  fewer.pop_back();
  EXPECT_FALSE(sweep_row_valid(spec, 1, fewer));
  auto no_reason = failed;
  no_reason[16].clear();  // not converged, and no failure named
  EXPECT_FALSE(sweep_row_valid(spec, 0, no_reason));
}

}  // namespace
}  // namespace flexgait::rimless
