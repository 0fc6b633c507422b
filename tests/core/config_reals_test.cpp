// A list of real numbers as one configuration value (ParamType::Reals, e.g. analysis.energy.mu):
// flow YAML `[a, b]` from a file and after --set, each value within the key's bounds, the list
// never empty; to_yaml writes it back so that it reads the same; a bad value names key[i].
#include <unistd.h>  // getpid: a file of this process alone (work trees run tests at once)

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/record.hpp"

namespace flexgait {
namespace {

struct Grid {
  std::vector<double> mus{0.6, 0.105};
  int count = 3;
  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("grid.mu", s.mus, {.doc = "friction coefficients", .bounds = closed(0, 2)});
    v("grid.count", s.count, {.doc = "points", .bounds = closed(1, 10)});
  }
};

std::string error_of(const std::vector<std::string>& sets) {
  try {
    resolve_config(schema_of<Grid>(), std::nullopt, sets);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ConfigError";
  return {};
}

TEST(ConfigReals, DefaultIsTheRecordsMemberAndReadsBack) {
  const Schema schema = schema_of<Grid>();
  ASSERT_NE(schema.find("grid.mu"), nullptr);
  EXPECT_EQ(schema.find("grid.mu")->type, ParamType::Reals);
  EXPECT_EQ(schema.find("grid.mu")->fallback, "[0.6, 0.105]");
  const Config c = resolve_config(schema, std::nullopt, {});
  EXPECT_EQ(record_from_config<Grid>(c).mus, (std::vector<double>{0.6, 0.105}));
}

TEST(ConfigReals, SetReachesTheRecord) {
  const Config c = resolve_config(schema_of<Grid>(), std::nullopt, {"grid.mu=[0.2, 1e-1,2]"});
  EXPECT_EQ(record_from_config<Grid>(c).mus, (std::vector<double>{0.2, 0.1, 2.0}));
  EXPECT_EQ(c.origin("grid.mu"), "--set");
}

TEST(ConfigReals, FileListAndYamlRoundTrip) {
  const auto file =
      std::filesystem::temp_directory_path() / ("flexgait_config_reals_test_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(file) << "grid:\n  mu:\n    - 0.3\n    - 0.25\n";
  const Config c = resolve_config(schema_of<Grid>(), file, {});
  EXPECT_EQ(c.reals("grid.mu"), (std::vector<double>{0.3, 0.25}));
  // The resolved configuration, written and read again, holds the same values (bit for bit:
  // format_value writes the shortest text that round-trips).
  std::ofstream(file) << c.to_yaml();
  const Config again = resolve_config(schema_of<Grid>(), file, {});
  EXPECT_EQ(again.reals("grid.mu"), c.reals("grid.mu"));
  std::filesystem::remove(file);
}

TEST(ConfigReals, BadInputNamesTheKey) {
  EXPECT_NE(error_of({"grid.mu=[0.2,3]"}).find("--set: key 'grid.mu[1]' = '3': out of range"), std::string::npos);
  EXPECT_NE(error_of({"grid.mu=[0.2,,0.3]"}).find("key 'grid.mu[1]' = '': not a number"), std::string::npos);
  EXPECT_NE(error_of({"grid.mu=[nan]"}).find("key 'grid.mu[0]' = 'nan'"), std::string::npos);
  EXPECT_NE(error_of({"grid.mu=[]"}).find("key 'grid.mu' = '[]': an empty list"), std::string::npos);
  const std::string scalar = error_of({"grid.mu=0.2"});
  EXPECT_NE(scalar.find("key 'grid.mu' = '0.2': not a list in brackets; allowed: a list [a, b, ...] of one or more "
                        "values, each a finite real number in [0, 2]"),
            std::string::npos)
      << scalar;
  // A key of one value refuses a list from a file, as before.
  EXPECT_NE(error_of({"grid.count=[1, 2]"}).find("grid.count"), std::string::npos);
}

}  // namespace
}  // namespace flexgait
