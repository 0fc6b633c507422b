// A configuration file read with limits (core/config_file.hpp): every refusal is a
// ConfigError naming the file and, where there is one, the line.
#include "flexgait/core/config_file.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "flexgait/core/config.hpp"

namespace flexgait {
namespace {

// The ConfigError message of parsing `text` as "f.yaml" ("" and a test failure if none is thrown).
std::string error_of(const std::string& text) {
  try {
    parse_config_yaml(text, "f.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ConfigError for:\n" << text;
  return "";
}

#define EXPECT_REFUSED(text, needle) EXPECT_NE(error_of(text).find(needle), std::string::npos) << error_of(text)

TEST(ConfigFile, EntriesInFileOrderWithTheirLines) {
  const auto e = parse_config_yaml("model:\n  K: 5\n  legs: &n 7\nrun.steps: *n\n", "f.yaml");
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0].key, "model.K");
  EXPECT_EQ(e[0].text, "5");
  EXPECT_EQ(e[0].origin, "f.yaml:2");
  EXPECT_EQ(e[2].key, "run.steps");
  EXPECT_EQ(e[2].text, "7");  // an alias to a scalar is its value
  EXPECT_EQ(e[2].origin, "f.yaml:4");
  EXPECT_TRUE(parse_config_yaml("", "f.yaml").empty());
  EXPECT_TRUE(parse_config_yaml("# only a comment\n", "f.yaml").empty());
  EXPECT_TRUE(parse_config_yaml("---\n...\n", "f.yaml").empty());
}

TEST(ConfigFile, RecursiveAliasIsRefused) {  // overflowed the stack
  EXPECT_REFUSED("a: &a\n  b: *a\n", "f.yaml:2: a recursive alias");
  EXPECT_REFUSED("a: &a [1, *a]\n", "recursive alias");
}

TEST(ConfigFile, AliasBombIsRefused) {  // 783 bytes expanded to 3.3 GB
  std::string text = "l0: &l0 {a: 1, b: 1}\n";
  for (int i = 1; i <= 20; ++i) text += fmt::format("l{}: &l{} {{a: *l{}, b: *l{}}}\n", i, i, i - 1, i - 1);
  EXPECT_REFUSED(text, "aliases expand to more than");
}

TEST(ConfigFile, DuplicateKeysAreRefused) {  // the last one silently won
  EXPECT_REFUSED("a: 1\nb: 2\na: 3\n", "f.yaml:3: key 'a' given twice (first at line 1)");
  EXPECT_REFUSED("a:\n  b: 1\na.b: 2\n", "f.yaml:3: key 'a.b' given twice (first at f.yaml:2)");
}

TEST(ConfigFile, ExtraDocumentsAreRefused) {  // were ignored
  EXPECT_REFUSED("a: 1\n---\nb: 2\n", "f.yaml:2: a second YAML document");
  EXPECT_REFUSED("a: 1\n---\n", "second YAML document");
}

TEST(ConfigFile, ComplexAndNullKeysAreRefused) {  // yaml-cpp's text, exit 1, no file name
  EXPECT_REFUSED("? [a, b]\n: 1\n", "f.yaml:1: a key must be a plain name, not a list");
  EXPECT_REFUSED("{a: 1}: 2\n", "a key must be a plain name, not a mapping");
  EXPECT_REFUSED("~: 1\n", "a key must be a plain name, not null");
  EXPECT_REFUSED("a: &x {b: 1}\n*x : 2\n", "not a mapping");
}

TEST(ConfigFile, DepthIsLimited) {
  std::string text;
  for (int i = 0; i < 40; ++i) text += std::string(2 * static_cast<std::size_t>(i), ' ') + "k:\n";
  text += std::string(80, ' ') + "v: 1\n";
  EXPECT_REFUSED(text, "nested deeper than 32 levels");
  EXPECT_REFUSED(std::string(100000, '[') + std::string(100000, ']'), "f.yaml:1:");
}

TEST(ConfigFile, ValuesMustBeSingleAndPresent) {
  // A list is one entry, as flow YAML, aliases expanded; its key's type decides (config.cpp refuses
  // it for a key of one value: "must be a single value, not a list").
  const auto list = parse_config_yaml("a:\n  - &p {t: 1, f: [0, 'x, y']}\n  - *p\n", "f.yaml");
  ASSERT_EQ(list.size(), 1u);
  EXPECT_TRUE(list[0].list);
  EXPECT_EQ(list[0].text, "[{t: 1, f: [0, \"x, y\"]}, {t: 1, f: [0, \"x, y\"]}]");
  EXPECT_EQ(list[0].origin, "f.yaml:2");
  const auto items = parse_list_text(list[0].text);
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[1][1].values, (std::vector<std::string>{"0", "x, y"}));
  EXPECT_REFUSED("a:\n", "key 'a' has no value");
  EXPECT_REFUSED("- 1\n", "the top level must be a mapping");
  EXPECT_REFUSED("a: [1\n", "YAML syntax error");
}

class ConfigFileOnDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::temp_directory_path() /
        ("flexgait_config_file_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string error_of_file(const std::filesystem::path& p) {
    try {
      read_config_file(p);
    } catch (const ConfigError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no ConfigError for " << p;
    return "";
  }
  std::filesystem::path dir_;
};

TEST_F(ConfigFileOnDisk, NonRegularFilesAreRefusedUnopened) {
  EXPECT_NE(error_of_file(dir_).find("is a directory"), std::string::npos);
  const auto fifo = dir_ / "fifo.yaml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(error_of_file(fifo).find("fifo.yaml: is not a regular file"), std::string::npos);  // blocked forever
  EXPECT_NE(error_of_file(dir_ / "none.yaml").find("no such file"), std::string::npos);
}

TEST_F(ConfigFileOnDisk, SizeIsLimited) {  // 50 MB of duplicate keys took 3.8 GB
  const auto big = dir_ / "big.yaml";
  std::ofstream(big) << "a: 1\n# " << std::string(kMaxConfigBytes, 'x') << "\n";
  EXPECT_NE(error_of_file(big).find("big.yaml: larger than 1048576 bytes"), std::string::npos) << error_of_file(big);
  const auto ok = dir_ / "ok.yaml";
  std::ofstream(ok) << "a: 1\n";
  EXPECT_EQ(read_config_file(ok).size(), 1u);
}

}  // namespace
}  // namespace flexgait
