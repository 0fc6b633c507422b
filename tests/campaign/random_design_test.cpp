// Random draws of a campaign: parsing and refusals; the draw a pure function of (seed, sample,
// key) with the moments of a uniform variable; the value text exact and inside [A, B]; and a
// campaign crossing the draws with a grid axis (header, rows, the same draws at every grid point,
// a random end outside its key's domain refused before anything runs).
#include "flexgait/campaign/random_design.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "flexgait/campaign/campaign.hpp"
#include "flexgait/core/config.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait::campaign {
namespace {

TEST(RandomAxis, ParsesARangeAndRefusesTheRest) {
  const RandomAxis a = parse_random_axis("disturbance.push.force_y=-200:200");
  EXPECT_EQ(a.key, "disturbance.push.force_y");
  EXPECT_EQ(a.low, -200);
  EXPECT_EQ(a.high, 200);
  for (const char* bad : {"k", "=1:2", "k=", "k=1", "k=1:2:3", "k=a:2", "k=1:inf", "k=2:1", "k=1:1"})
    EXPECT_THROW(parse_random_axis(bad), UsageError) << bad;
  EXPECT_THROW(RandomDesign({parse_random_axis("k=0:1")}, 0, 1), UsageError);       // no samples
  EXPECT_THROW(RandomDesign({parse_random_axis("k=0:1")}, 100001, 1), UsageError);  // too many
  EXPECT_THROW(RandomDesign({}, 5, 1), UsageError);                                 // samples, no key
  EXPECT_THROW(RandomDesign({parse_random_axis("k=0:1"), parse_random_axis("k=2:3")}, 5, 1), UsageError);
}

// 20000 draws of two keys: mean 1/2 and variance 1/12 of a uniform variable, and no correlation
// between keys or between successive samples. The draws are fixed by the seed (no flakiness); the
// tolerances are 5 standard errors of each estimate for independent uniforms: mean
// sqrt(1/12/n) = 0.0020, variance sqrt(1/180/n) = 0.00053, correlation 1/sqrt(n) = 0.0071.
TEST(RandomDesign, DrawsHaveTheMomentsOfIndependentUniforms) {
  const int n = 20000;
  const RandomDesign d({parse_random_axis("a=0:1"), parse_random_axis("b=0:1")}, n, 42);
  double mean = 0, square = 0, cross = 0, lag = 0;
  for (int s = 0; s < n; ++s) {
    const double u = d.uniform(s, 0), v = d.uniform(s, 1);
    ASSERT_TRUE(u >= 0 && u < 1) << u;
    mean += u / n;
    square += u * u / n;
    cross += (u - 0.5) * (v - 0.5) / n * 12;
    if (s > 0) lag += (u - 0.5) * (d.uniform(s - 1, 0) - 0.5) / (n - 1) * 12;
  }
  EXPECT_NEAR(mean, 0.5, 5 * 0.0020);
  EXPECT_NEAR(square - mean * mean, 1.0 / 12, 5 * 0.00053);
  EXPECT_NEAR(cross, 0, 5 * 0.0071);
  EXPECT_NEAR(lag, 0, 5 * 0.0071);
}

TEST(RandomDesign, ValueIsAFunctionOfSeedSampleAndKeyAlone) {
  const RandomDesign d({parse_random_axis("a=-3:5"), parse_random_axis("b=0.1:0.2")}, 10, 7);
  const RandomDesign same({parse_random_axis("a=-3:5"), parse_random_axis("b=0.1:0.2")}, 99, 7);
  const RandomDesign other({parse_random_axis("a=-3:5"), parse_random_axis("b=0.1:0.2")}, 10, 8);
  for (int s = 0; s < 10; ++s)
    for (std::size_t k = 0; k < 2; ++k) {
      const std::string v = d.value(s, k);
      EXPECT_EQ(v, same.value(s, k));  // the number of samples does not change a draw
      EXPECT_NE(v, other.value(s, k));
      const double x = *parse_finite_number(v);
      EXPECT_EQ(format_number(x), v);  // the text reads back to the same double
      EXPECT_EQ(x, d.axes()[k].low + (d.axes()[k].high - d.axes()[k].low) * d.uniform(s, k));
      EXPECT_TRUE(x >= d.axes()[k].low && x <= d.axes()[k].high) << v;
    }
  EXPECT_EQ(d.sample_axis().key, "sample");
  EXPECT_EQ(d.sample_axis().values.back(), "9");
}

// A toy experiment whose summary echoes its keys.
Experiment echo() {
  Schema s;
  s.add(real_param("x", "1", "", "grid key", 0, 100)).add(real_param("y", "1", "", "drawn key", 0, 100));
  Experiment e{"echo", "summary.json", s, {}, {}, {"y"}, {}};
  e.set = [](Config& c, const std::string& k, const std::string& v, const std::string& origin) { c.set(k, v, origin); };
  e.check = [](const Config&) {};
  e.run = [](const Config& c, const std::filesystem::path&) { return nlohmann::ordered_json{{"y", c.real("y")}}; };
  return e;
}

TEST(RandomDesign, CampaignCrossesTheDrawsWithTheGridAndRunsEachDraw) {
  const RandomDesign d({parse_random_axis("y=10:20")}, 3, 5);
  const Config base = resolve_config(echo().schema, std::nullopt, {});
  const Campaign c(echo(), base, Grid({parse_grid_axis("x=1,2"), d.sample_axis()}), d);
  ASSERT_EQ(c.size(), 6);
  EXPECT_EQ(c.header(), "x,sample,y,y,error");  // the drawn y, then the summary's y
  for (int i = 0; i < 6; ++i) {
    const std::string drawn = d.value(i % 3, 0);
    EXPECT_EQ(c.row(i), fmt::format("{},{},{},{},", i < 3 ? 1 : 2, i % 3, drawn, drawn));  // the run saw the draw
  }
  EXPECT_NE(c.signature().find("random y=10:20\nsamples 3 seed 5\n"), std::string::npos) << c.signature();
  // An end outside the key's domain [0, 100] is refused, naming the option.
  const RandomDesign wide({parse_random_axis("y=-1:20")}, 3, 5);
  try {
    const Campaign bad(echo(), base, Grid({parse_grid_axis("x=1"), wide.sample_axis()}), wide);
    FAIL() << "y = -1 passed";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--random y"), std::string::npos) << e.what();
  }
  // The sample axis must be the grid's last.
  EXPECT_THROW(Campaign(echo(), base, Grid({d.sample_axis(), parse_grid_axis("x=1,2")}), d), UsageError);
}

}  // namespace
}  // namespace flexgait::campaign
