// A campaign's cells and checks: the summary flattened under its own keys (null empty, lists by ';',
// pairs by ':', text quoted as CSV needs, a missing key empty), every point checked before anything
// runs (the offending point named), a failing run a row with its reason, and the signature holding
// the program's build, experiment, axes and base configuration.
#include "flexgait/campaign/campaign.hpp"
#include "flexgait/campaign/program_build.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "flexgait/core/text.hpp"

namespace flexgait::campaign {
namespace {

TEST(SummaryCells, FlattensUnderTheSummarysKeys) {
  const auto json = nlohmann::ordered_json::parse(
      R"({"a": 1, "b": 0.1, "c": null, "d": true, "e": "x, y", "f": ["p", "q"], "g": [[0.5, -1], [2, 0]]})");
  EXPECT_EQ(summary_cells(json, {"a", "b", "c", "d", "e", "f", "g", "missing"}),
            "1,0.1,,true,\"x, y\",p;q,0.5:-1;2:0,");
  // Doubles round-trip: the cell is format_number of the value.
  EXPECT_EQ(summary_cells(nlohmann::ordered_json::parse(R"({"v": 0.30000000000000004})"), {"v"}),
            format_number(0.30000000000000004));
}

// A two-key experiment whose run fails for x = 3 and whose check refuses x + y > 10.
Experiment toy() {
  Schema s;
  s.add(real_param("x", "1", "", "first", 0, 100)).add(real_param("y", "1", "", "second", 0, 100));
  Experiment e{"toy", "summary.json", s, {}, {}, {"sum", "note"}, {}};
  e.set = [](Config& c, const std::string& k, const std::string& v, const std::string& origin) { c.set(k, v, origin); };
  e.check = [](const Config& c) {
    if (c.real("x") + c.real("y") > 10) throw ConfigError("y", c.origin("y") + ": x + y > 10");
  };
  e.run = [](const Config& c, const std::filesystem::path&) {
    if (c.real("x") == 3) throw std::runtime_error("diverged");
    return nlohmann::ordered_json{{"sum", c.real("x") + c.real("y")}, {"note", nullptr}};
  };
  return e;
}

Config toy_base() {
  return resolve_config(toy().schema, std::nullopt, {});
}

TEST(Campaign, RowsHoldAxesMetricsAndTheErrorOfAFailedPoint) {
  const Campaign c(toy(), toy_base(), Grid({parse_grid_axis("x=2,3"), parse_grid_axis("y=0:1:2")}));
  EXPECT_EQ(c.size(), 4);
  EXPECT_EQ(c.header(), "x,y,sum,note,error");
  EXPECT_EQ(c.row(1), "2,1,3,,");
  EXPECT_EQ(c.row(2), "3,0,,,diverged");  // the failing point keeps its row
}

TEST(Campaign, ChecksEveryPointBeforeAnythingRuns) {
  try {
    const Campaign c(toy(), toy_base(), Grid({parse_grid_axis("x=2,9"), parse_grid_axis("y=1,2")}));
    FAIL() << "x = 9, y = 2 passed the check";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "y");
    EXPECT_NE(std::string(e.what()).find("--grid point 3 (x=9, y=2)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Campaign(toy(), toy_base(), Grid({parse_grid_axis("x=1,-1")})), ConfigError);
  EXPECT_THROW(Campaign(toy(), toy_base(), Grid({parse_grid_axis("z=1")})), ConfigError);
}

// toy() with an alias "both" that sets x and y to one value (as rimless.mu sets mu_s and mu_k).
Experiment toy_with_alias() {
  Experiment e = toy();
  e.set = [](Config& c, const std::string& k, const std::string& v, const std::string& origin) {
    if (k != "both") return c.set(k, v, origin);
    c.set("x", v, origin);
    c.set("y", v, origin);
  };
  return e;
}

std::string usage_error_of(const Config& base, std::vector<GridAxis> axes) {
  try {
    Campaign(toy_with_alias(), base, Grid(std::move(axes)));
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(Campaign, AxesThatSetTheSameKeyAreRefused) {
  const Config base = toy_base();
  EXPECT_EQ(usage_error_of(base, {parse_grid_axis("y=1,2"), parse_grid_axis("both=3,4")}),
            "--grid y and --grid both both set y (--grid y sets y; --grid both sets x and y); give only one of them");
  EXPECT_EQ(usage_error_of(base, {parse_grid_axis("x=1,2"), parse_grid_axis("y=3,4")}), "");
  // A --set of a key an axis sets would be replaced at every point; a file's value is the base.
  const Config set = resolve_config(toy().schema, std::nullopt, {"x=2"});
  EXPECT_EQ(usage_error_of(set, {parse_grid_axis("both=1,2")}),
            "--set x and --grid both both set x: the axis's values would replace the --set value at every point; "
            "give only one of them");
  EXPECT_EQ(usage_error_of(set, {parse_grid_axis("y=1,2")}), "");
  Config from_file = toy_base();
  from_file.set("x", "2", "base.yaml:1");
  EXPECT_EQ(usage_error_of(from_file, {parse_grid_axis("x=1,2")}), "");
}

TEST(Campaign, AResumedRowMustHoldItsPointsValuesAndCellsOfTheirTypes) {
  Experiment e = toy();
  e.metric_types = {"real", ""};
  const Campaign c(e, toy_base(), Grid({parse_grid_axis("x=2,3"), parse_grid_axis("y=0:1:2")}));
  const auto cells = [](const std::string& row) {
    std::vector<std::string> out = parse_csv(row + "\n").front().fields;
    return out;
  };
  EXPECT_TRUE(c.row_valid(1, cells(c.row(1))));
  EXPECT_TRUE(c.row_valid(2, cells(c.row(2))));   // a failed point: its reason, no metric
  EXPECT_FALSE(c.row_valid(0, cells(c.row(1))));  // another point's values
  EXPECT_FALSE(c.row_valid(1, cells("2,1,abc,,")));
  EXPECT_FALSE(c.row_valid(1, cells("2,1,nan,,")));
  EXPECT_FALSE(c.row_valid(1, cells("2,1,1e999,,")));
  EXPECT_FALSE(c.row_valid(1, cells("2,1,3,,diverged")));  // metrics and an error
  EXPECT_TRUE(c.row_valid(1, cells("2,1,3,any text,")));   // a column of unknown type
  EXPECT_FALSE(c.row_valid(1, cells("2,1,3,")));
}

TEST(MetricCells, EachTypesText) {
  EXPECT_TRUE(metric_cell_valid("real", "-1.5e-3"));
  EXPECT_FALSE(metric_cell_valid("real", "inf"));
  EXPECT_TRUE(metric_cell_valid("integer", "-12"));
  EXPECT_FALSE(metric_cell_valid("integer", "1.0"));
  EXPECT_FALSE(metric_cell_valid("integer", "-"));
  EXPECT_TRUE(metric_cell_valid("boolean", "false"));
  EXPECT_FALSE(metric_cell_valid("boolean", "yes"));
  EXPECT_TRUE(metric_cell_valid("list of real", "0.5;-1;2"));
  EXPECT_FALSE(metric_cell_valid("list of real", "0.5;;2"));
  EXPECT_TRUE(metric_cell_valid("real", ""));  // null
  EXPECT_TRUE(metric_cell_valid("text", "x, y"));
}

TEST(Campaign, SignatureChangesWithAxesAndBase) {
  const Config base = toy_base();
  const Campaign a(toy(), base, Grid({parse_grid_axis("x=1,2")}));
  const Campaign b(toy(), base, Grid({parse_grid_axis("x=1,3")}));
  Config other = base;
  other.set("y", "2");
  const Campaign d(toy(), other, Grid({parse_grid_axis("x=1,2")}));
  EXPECT_EQ(a.signature(), Campaign(toy(), base, Grid({parse_grid_axis("x=1:2:2")})).signature());
  EXPECT_NE(a.signature(), b.signature());
  EXPECT_NE(a.signature(), d.signature());
  // The build comes first: a campaign of another build (another commit, another edit) is another campaign.
  EXPECT_EQ(a.signature().rfind("flexgait " + program_build() + "\ncampaign toy\n", 0), 0u) << a.signature();
}

}  // namespace
}  // namespace flexgait::campaign
