// The grid of a campaign: axis parsing (ranges with exact ends, lists as written) and the
// Cartesian product's order (first axis slowest), and the refusals (UsageError).
#include "flexgait/campaign/grid.hpp"

#include <gtest/gtest.h>

#include "flexgait/core/config.hpp"

namespace flexgait::campaign {
namespace {

TEST(GridAxis, RangeHasNEvenlySpacedValuesWithExactEnds) {
  const GridAxis a = parse_grid_axis("rimless.slope=0.1:0.3:3");
  EXPECT_EQ(a.key, "rimless.slope");
  // 0.1 + 0.2 * 1 / 2 = 0.2 in doubles; the last value is B as written, not A + (B - A) rounded.
  EXPECT_EQ(a.values, (std::vector<std::string>{"0.1", "0.2", "0.3"}));
  EXPECT_EQ(parse_grid_axis("k=0.1:0.7:7").values.back(), "0.7");
  EXPECT_EQ(parse_grid_axis("k=0.3:0.9:4").values, (std::vector<std::string>{"0.3", "0.5", "0.7", "0.9"}));
  EXPECT_EQ(parse_grid_axis("k=5:9:1").values, (std::vector<std::string>{"5"}));
}

TEST(GridAxis, ListKeepsTheValuesAsWritten) {
  EXPECT_EQ(parse_grid_axis("control.compensation=off,both").values, (std::vector<std::string>{"off", "both"}));
  EXPECT_EQ(parse_grid_axis("k=1e3").values, (std::vector<std::string>{"1e3"}));
}

TEST(GridAxis, RefusesMalformedAxes) {
  for (const char* bad : {"k", "=1,2", "k=", "k=1,,2", "k=1:2", "k=1:2:3:4", "k=a:2:3", "k=1:nan:3", "k=1:2:0",
                          "k=1:2:2.5", "k=1:2:100001", "k=1:2,3:4"})
    EXPECT_THROW(parse_grid_axis(bad), UsageError) << bad;
}

TEST(Grid, FirstAxisVariesSlowest) {
  const Grid g({parse_grid_axis("a=1,2"), parse_grid_axis("b=x,y,z")});
  ASSERT_EQ(g.size(), 6);
  EXPECT_EQ(g.point(0), (std::vector<std::string>{"1", "x"}));
  EXPECT_EQ(g.point(2), (std::vector<std::string>{"1", "z"}));
  EXPECT_EQ(g.point(3), (std::vector<std::string>{"2", "x"}));
  EXPECT_EQ(g.point(5), (std::vector<std::string>{"2", "z"}));
}

TEST(Grid, RefusesNoAxisARepeatedKeyAndTooManyPoints) {
  EXPECT_THROW(Grid({}), UsageError);
  EXPECT_THROW(Grid({parse_grid_axis("a=1"), parse_grid_axis("a=2")}), UsageError);
  EXPECT_THROW(Grid({parse_grid_axis("a=0:1:1000"), parse_grid_axis("b=0:1:1001")}), UsageError);
}

}  // namespace
}  // namespace flexgait::campaign
