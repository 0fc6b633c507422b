// Atomic writes: the target holds the old or the new content, never a mixture, and no
// temporary file is left behind on success or failure.
#include "flexgait/core/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "flexgait/core/run_directory.hpp"

namespace flexgait {
namespace {

std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("flexgait_atomic_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

int count_entries(const std::filesystem::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, WritesAndReplacesWithoutLeftovers) {
  const auto dir = fresh_dir("replace");
  write_file_atomic(dir / "a.csv", "old\n");
  write_file_atomic(dir / "a.csv", std::string(1 << 20, 'x'));
  EXPECT_EQ(read_text_file(dir / "a.csv"), std::string(1 << 20, 'x'));
  EXPECT_EQ(count_entries(dir), 1);
}

TEST(AtomicFile, FailureLeavesTargetUntouched) {
  const auto dir = fresh_dir("fail");
  write_file_atomic(dir / "keep.txt", "intact");
  // A directory in the way of the rename: the write fails and the temporary is removed.
  std::filesystem::create_directories(dir / "blocked" / "inner");
  EXPECT_THROW(write_file_atomic(dir / "blocked", "new"), std::system_error);
  EXPECT_THROW(write_file_atomic(dir / "missing_dir" / "x.txt", "new"), std::system_error);
  EXPECT_EQ(read_text_file(dir / "keep.txt"), "intact");
  EXPECT_EQ(count_entries(dir), 2);  // keep.txt and blocked/
}

TEST(AtomicFile, AppendIsDurableAndCumulative) {
  const auto dir = fresh_dir("append");
  append_file_durable(dir / "rows.csv", "a\n");
  append_file_durable(dir / "rows.csv", "b\n");
  EXPECT_EQ(read_text_file(dir / "rows.csv"), "a\nb\n");
}

TEST(AtomicFileWriter, TargetAppearsWholeAtCommitOnly) {
  const auto dir = fresh_dir("pieces");
  write_file_atomic(dir / "log.csv", "old\n");
  {
    AtomicFileWriter file(dir / "log.csv");
    file.append("a\n");
    file.append("b\n");
    // Until commit the target keeps its old content and the pieces are in the temporary file.
    EXPECT_EQ(read_text_file(dir / "log.csv"), "old\n");
    EXPECT_EQ(read_text_file(file.temporary_path()), "a\nb\n");
    file.commit();
    EXPECT_THROW(file.append("c\n"), std::logic_error);
  }
  EXPECT_EQ(read_text_file(dir / "log.csv"), "a\nb\n");
  EXPECT_EQ(count_entries(dir), 1);
}

TEST(AtomicFileWriter, AbandonedWriteLeavesNothing) {
  const auto dir = fresh_dir("abandon");
  {
    AtomicFileWriter file(dir / "log.csv");
    file.append("half a row");
    EXPECT_EQ(count_entries(dir), 1);  // the temporary file
  }  // destroyed without commit: an exception unwound the run
  EXPECT_FALSE(std::filesystem::exists(dir / "log.csv"));
  EXPECT_EQ(count_entries(dir), 0);
}

TEST(RunDirectory, CreatesNestedDirectoryAndRejectsAFile) {
  const auto dir = fresh_dir("rundir");
  RunDirectory run(dir / "x" / "y");
  run.write("summary.json", "{}\n");
  EXPECT_EQ(read_text_file(dir / "x" / "y" / "summary.json"), "{}\n");
  write_file_atomic(dir / "plain", "file");
  EXPECT_THROW(RunDirectory(dir / "plain"), UsageError);  // a bad --out is bad usage: exit 2
}

}  // namespace
}  // namespace flexgait
