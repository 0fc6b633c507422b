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
  const std::string json =
      R"({"a": 1, "b": 0.1, "c": null, "d": true, "e": "x, y", "f": ["p", "q"], "g": [[0.5, -1], [2, 0]]})";
  EXPECT_EQ(summary_cells(json, {"a", "b", "c", "d", "e", "f", "g", "missing"}), "1,0.1,,true,\"x, y\",p;q,0.5:-1;2:0,");
  // Doubles round-trip: the cell is format_number of the value.
  EXPECT_EQ(summary_cells(R"({"v": 0.30000000000000004})", {"v"}), format_number(0.30000000000000004));
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
  e.run = [](const Config& c, const std::filesystem::path&) -> std::string {
    if (c.real("x") == 3) throw std::runtime_error("diverged");
    return fmt::format(R"({{"sum": {}, "note": null}})", c.real("x") + c.real("y"));
  };
  return e;
}

Config toy_base() { return resolve_config(toy().schema, std::nullopt, {}); }

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
