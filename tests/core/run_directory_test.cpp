// The output folder of one run (core/run_directory.hpp): made with its parents (a file in the way is
// a usage error), files written inside it atomically, the `complete` marker written only when the
// scope that made it ends normally, and config.yaml with the resolved configuration.
#include "flexgait/core/run_directory.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <optional>
#include <stdexcept>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/version.hpp"
#include "temp_dirs.hpp"

namespace flexgait {
namespace {

using testing::fresh_dir;

TEST(RunDirectory, CreatesNestedDirectoryAndRejectsAFile) {
  const auto dir = fresh_dir("rundir");
  RunDirectory run(dir / "x" / "y");
  run.write("summary.json", "{}\n");
  EXPECT_EQ(read_text_file(dir / "x" / "y" / "summary.json"), "{}\n");
  write_file_atomic(dir / "plain", "file");
  EXPECT_THROW(RunDirectory(dir / "plain"), UsageError);  // a bad --out is bad usage: exit 2
}

TEST(RunDirectory, CompleteOnlyWhenItsScopeEndsNormally) {
  const auto dir = fresh_dir("complete");
  {
    RunDirectory run(dir / "ok");
    run.write("summary.json", "{}\n");
    EXPECT_FALSE(run_directory_complete(run.path()));  // still being written
  }
  EXPECT_TRUE(run_directory_complete(dir / "ok"));
  {
    RunDirectory again(dir / "ok");  // written again: not complete until it is done
    EXPECT_FALSE(run_directory_complete(dir / "ok"));
  }
  EXPECT_TRUE(run_directory_complete(dir / "ok"));
  try {
    RunDirectory run(dir / "failed");
    run.write("config.yaml", "a: 1\n");
    throw std::runtime_error("the run failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(run_directory_complete(dir / "failed"));
  EXPECT_TRUE(std::filesystem::exists(dir / "failed" / "config.yaml"));
}

TEST(RunDirectory, MovedFromMarksNothing) {
  const auto dir = fresh_dir("moved");
  auto make = [&] { return std::optional<RunDirectory>(RunDirectory(dir / "run")); };
  std::optional<RunDirectory> run = make();
  EXPECT_FALSE(run_directory_complete(dir / "run"));  // the moved-from temporary wrote nothing
  run.reset();
  EXPECT_TRUE(run_directory_complete(dir / "run"));
}

TEST(RunDirectory, ConfigYamlIsTheResolvedConfigurationUnderItsHeader) {
  const auto dir = fresh_dir("config");
  Schema schema;
  ParamSpec spec;
  spec.key = "a.b";
  spec.fallback = "1.5";
  spec.doc = "a number";
  schema.add(spec);
  const Config config = resolve_config(schema, std::nullopt, {"a.b=2.25"});
  {
    const RunDirectory run(dir / "run");
    run.write_config(config);
  }
  const std::string text = read_text_file(dir / "run" / "config.yaml");
  EXPECT_EQ(text, std::string("# resolved configuration, flexgait ") + kVersion + "\n" + config.to_yaml());
  EXPECT_NE(text.find("2.25"), std::string::npos);
}

TEST(RunDirectory, ALeftOverTemporaryOfADeadWriterIsRemovedOnReuse) {
  const auto dir = fresh_dir("reuse");
  std::filesystem::create_directories(dir / "run");
  // The temporary file of a writer that has exited (a child process, reaped) is removed.
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) ::_exit(0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  const auto orphan = dir / "run" / (".log.csv.tmp-" + std::to_string(child) + "-abcdef");
  write_file_atomic(orphan, "half");
  { const RunDirectory run(dir / "run"); }
  EXPECT_FALSE(std::filesystem::exists(orphan));
  EXPECT_TRUE(run_directory_complete(dir / "run"));
}

}  // namespace
}  // namespace flexgait
