// A campaign table reduced over axes: each group's points and errors counted, a true/false metric's
// fraction and a numeric one's mean, min and max over the group's finite cells (a failed point in
// no statistic), text and list metrics left out, groups in grid order; bad keys refused.
#include "flexgait/campaign/reduction.hpp"

#include <gtest/gtest.h>

#include "flexgait/core/config.hpp"

namespace flexgait::campaign {
namespace {

Grid two_by_three() {
  return Grid({parse_grid_axis("a=1,2"), parse_grid_axis("seed=1:3:3")});
}

// index, a, seed | fell, x, gait, list | error
const char* kTable =
    "index,a,seed,fell,x,gait,list,error\n"
    "0,1,1,true,0.5,stick,1;2,\n"
    "1,1,2,false,1.5,\"slip, stick\",3;4,\n"
    "2,1,3,false,nan,stick,5;6,\n"
    "3,2,1,,,,,diverged\n"
    "4,2,2,true,-2,stick,,\n"
    "5,2,3,true,4,stick,,\n";

TEST(Reduction, OverTheSeedsGivesRatesAndStatisticsPerValueOfTheOtherAxis) {
  // a = 1: 3 points, fell 1 of 3, x over the finite 0.5 and 1.5 (nan counts in no statistic);
  // a = 2: the failed point is counted as an error and in nothing else: fell 2 of 2, x in {-2, 4}.
  EXPECT_EQ(reduce_campaign_table(two_by_three(), {"seed"}, kTable),
            "a,points,errors,fell_fraction,x_mean,x_min,x_max\n"
            "1,3,0,0.3333333333333333,1,0.5,1.5\n"
            "2,3,1,1,1,-2,4\n");
}

TEST(Reduction, OverTheFirstAxisKeepsTheSecondsOrder) {
  EXPECT_EQ(reduce_campaign_table(two_by_three(), {"a"}, kTable),
            "seed,points,errors,fell_fraction,x_mean,x_min,x_max\n"
            "1,2,1,1,0.5,0.5,0.5\n"
            "2,2,0,0.5,-0.25,-2,1.5\n"
            "3,2,0,0.5,4,4,4\n");
}

TEST(Reduction, OverEveryAxisGivesOneRowAndOverNoneTheTableItself) {
  EXPECT_EQ(reduce_campaign_table(two_by_three(), {"seed", "a"}, kTable),
            "points,errors,fell_fraction,x_mean,x_min,x_max\n"
            "6,1,0.6,1,-2,4\n");
  // Nothing reduced: each group one point; an empty statistic is an empty cell.
  const std::string none = reduce_campaign_table(two_by_three(), {}, kTable);
  EXPECT_NE(none.find("\n1,3,1,0,0,,,\n"), std::string::npos) << none;  // x = nan alone
  EXPECT_NE(none.find("\n2,1,1,1,,,,\n"), std::string::npos) << none;   // the failed point
}

TEST(Reduction, RefusesKeysThatAreNotAxesAndTablesThatAreNotTheGrids) {
  EXPECT_THROW(check_reduction(two_by_three(), {"b"}), UsageError);
  EXPECT_THROW(check_reduction(two_by_three(), {"a", "a"}), UsageError);
  try {
    check_reduction(two_by_three(), {"rimless.mu"});
    FAIL() << "rimless.mu passed as an axis";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "--reduce: 'rimless.mu' is not an axis of the campaign; allowed: a, seed");
  }
  EXPECT_THROW(reduce_campaign_table(two_by_three(), {"a"}, "index,a,seed,error\n0,1,1,\n"), std::runtime_error);
}

}  // namespace
}  // namespace flexgait::campaign
