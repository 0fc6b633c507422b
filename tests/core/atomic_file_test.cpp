// Atomic writes: the target holds the old or the new content, never a mixture, and no
// temporary file is left behind on success or failure.
#include "flexgait/core/atomic_file.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "flexgait/core/config.hpp"
#include "temp_dirs.hpp"

namespace flexgait {
namespace {

using testing::fresh_dir;

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

TEST(AtomicFile, DurableWriteIsAtomicAsWell) {
  // That it reaches the disk (fsync) cannot be observed here; its content and leftovers can.
  const auto dir = fresh_dir("durable");
  write_file_durable(dir / "sweep.signature", "old\n");
  write_file_durable(dir / "sweep.signature", "new\n");
  EXPECT_EQ(read_text_file(dir / "sweep.signature"), "new\n");
  EXPECT_EQ(count_entries(dir), 1);
  EXPECT_THROW(write_file_durable(dir / "missing_dir" / "x.txt", "new"), std::system_error);
  EXPECT_EQ(count_entries(dir), 1);
}

TEST(AtomicFile, FailureLeavesTargetUntouched) {
  const auto dir = fresh_dir("fail");
  write_file_atomic(dir / "keep.txt", "intact");
  // A directory in the way: refused (bad usage) before a temporary is made; a missing folder:
  // the temporary cannot be made (a runtime failure).
  std::filesystem::create_directories(dir / "blocked" / "inner");
  EXPECT_THROW(write_file_atomic(dir / "blocked", "new"), UsageError);
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
  }                                    // destroyed without commit: an exception unwound the run
  EXPECT_FALSE(std::filesystem::exists(dir / "log.csv"));
  EXPECT_EQ(count_entries(dir), 0);
}

// The message of the UsageError `write` throws ("" if it throws none).
template <class F>
std::string usage_error_of(F write) {
  try {
    write();
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

bool is_named_pipe(const std::filesystem::path& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
}

// Renaming over a FIFO, a device or a socket replaces the special file itself (as root: the
// system's /dev/null): every writer refuses such a target, before and at commit, and leaves it be.
TEST(OutputTarget, ASpecialFileIsRefusedAndLeftAsItWas) {
  const auto dir = fresh_dir("special");
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
  std::filesystem::create_symlink(dir / "fifo", dir / "link");
  std::string what = usage_error_of([&] { check_output_file(dir / "fifo", "--out"); });
  EXPECT_EQ(what, "--out: " + (dir / "fifo").string() +
                      " is a FIFO (named pipe), not a regular file; allowed: a "
                      "regular file (replaced whole) or a path that does not exist yet");
  EXPECT_NE(usage_error_of([&] { write_file_atomic(dir / "fifo", "x"); }).find("output: "), std::string::npos);
  what = usage_error_of([&] { write_file_durable(dir / "link", "x"); });
  EXPECT_NE(what.find("is a symbolic link to a FIFO"), std::string::npos) << what;
  EXPECT_TRUE(is_named_pipe(dir / "fifo"));
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link"));
  EXPECT_EQ(count_entries(dir), 2);  // no temporary file left
  EXPECT_NE(usage_error_of([&] { check_output_file(dir); }).find("is a directory"), std::string::npos);
  what = usage_error_of([] { write_file_atomic("/dev/null", "x"); });
  EXPECT_NE(what.find("/dev/null is a character device"), std::string::npos) << what;
  struct stat st {};
  ASSERT_EQ(::lstat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  // Allowed: a path that does not exist, a regular file, a dangling link (the rename replaces it).
  std::filesystem::create_symlink(dir / "nowhere", dir / "dangling");
  EXPECT_NO_THROW(check_output_file(dir / "new.csv"));
  EXPECT_NO_THROW(write_file_atomic(dir / "dangling", "y"));
  EXPECT_EQ(read_text_file(dir / "dangling"), "y");
}

TEST(OutputTarget, AFifoAppearingWhileAWriterWritesIsRefusedAtCommit) {
  const auto dir = fresh_dir("late_fifo");
  AtomicFileWriter file(dir / "a.csv");
  file.append("content\n");
  ASSERT_EQ(::mkfifo((dir / "a.csv").c_str(), 0644), 0);
  EXPECT_THROW(file.commit(), UsageError);
  EXPECT_TRUE(is_named_pipe(dir / "a.csv"));
  EXPECT_EQ(count_entries(dir), 1);
}

// The rename itself refuses a special file, with no check before it: what is at the target when
// the rename happens is what counts (no window between a check and the rename).
TEST(OutputTarget, TheRenameNeverReplacesASpecialFileAndReplacesARegularOne) {
  const auto dir = fresh_dir("rename_over");
  const auto make_tmp = [&](const std::string& text) {
    const auto tmp = dir / ".tmp";
    std::ofstream(tmp) << text;
    return tmp;
  };
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
  std::filesystem::create_symlink("fifo", dir / "link");  // relative, as a user's link may be
  for (const char* name : {"fifo", "link"}) {
    const auto tmp = make_tmp("new");
    const std::string what = usage_error_of([&] { rename_over_regular_file(tmp, dir / name); });
    EXPECT_NE(what.find("FIFO (named pipe), not a regular file"), std::string::npos) << name << ": " << what;
    EXPECT_EQ(read_text_file(tmp), "new") << name;  // the caller's file, where it was
    std::filesystem::remove(tmp);
  }
  EXPECT_TRUE(is_named_pipe(dir / "fifo"));
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link"));
  std::filesystem::create_directory(dir / "sub");
  const auto tmp = make_tmp("new");
  EXPECT_THROW(rename_over_regular_file(tmp, dir / "sub"), UsageError);
  EXPECT_TRUE(std::filesystem::is_directory(dir / "sub"));
  std::ofstream(dir / "old.csv") << "old";
  rename_over_regular_file(tmp, dir / "old.csv");  // a regular file is replaced
  EXPECT_EQ(read_text_file(dir / "old.csv"), "new");
  rename_over_regular_file(make_tmp("fresh"), dir / "absent.csv");  // an absent one created
  EXPECT_EQ(read_text_file(dir / "absent.csv"), "fresh");
  std::filesystem::create_symlink(dir / "nowhere", dir / "dangling");
  rename_over_regular_file(make_tmp("y"), dir / "dangling");  // a dangling link replaced, as before
  EXPECT_EQ(read_text_file(dir / "dangling"), "y");
  EXPECT_FALSE(std::filesystem::is_symlink(dir / "dangling"));
  EXPECT_EQ(count_entries(dir), 6);  // fifo, link, sub, old.csv, absent.csv, dangling: nothing left over
}

TEST(OutputTarget, ADirectoryOfResultsHoldsOnlyRegularFilesAndDirectories) {
  const auto dir = fresh_dir("results");
  std::filesystem::create_directories(dir / "runs");
  write_file_atomic(dir / "log.csv", "t\n");
  EXPECT_NO_THROW(check_output_directory(dir, "--out"));
  EXPECT_NO_THROW(check_output_directory(dir / "absent", "--out"));
  EXPECT_NE(usage_error_of([&] {
              check_output_directory(dir / "log.csv", "--out");
            }).find("log.csv: it is a regular file, not a directory"),
            std::string::npos);
  ASSERT_EQ(::mkfifo((dir / "summary.json").c_str(), 0644), 0);
  const std::string what = usage_error_of([&] { check_output_directory(dir, "--out"); });
  EXPECT_EQ(
      what.rfind("--out: cannot use the run directory " + dir.string() + ": it holds summary.json, which is a FIFO", 0),
      0u)
      << what;
}

TEST(ReadTextFile, ReadsAWholeFileOnceAndNothingForAMissingOne) {
  const auto dir = fresh_dir("read");
  const std::string text = std::string(3 << 20, 'a') + "end";
  write_file_atomic(dir / "big", text);
  EXPECT_EQ(read_text_file(dir / "big"), text);
  EXPECT_EQ(read_text_file(dir / "missing"), "");
  write_file_atomic(dir / "empty", "");
  EXPECT_EQ(read_text_file(dir / "empty"), "");
}

TEST(Temporaries, OwnerIsParsedFromTheNamingScheme) {
  EXPECT_EQ(temporary_owner(".log.csv.tmp-4242-a1B2c3"), 4242);
  EXPECT_EQ(temporary_owner(".walk.png.tmp-17-x_y8k2ab"), 17);  // python/atomic_write.py's form
  EXPECT_EQ(temporary_owner("log.csv"), 0);
  EXPECT_EQ(temporary_owner(".log.csv.tmp-XXXXXX"), 0);  // the old scheme, no owner
  EXPECT_EQ(temporary_owner(".log.csv.tmp-12a-b"), 0);
  EXPECT_EQ(temporary_owner(".log.csv.tmp-12-"), 0);
  EXPECT_EQ(temporary_owner(".tmp-1234567890-a"), 0);  // more digits than a pid has
}

TEST(Temporaries, AKilledWritersFileIsRemovedALiveOnesKept) {
  const auto dir = fresh_dir("orphans");
  // A child process starts an atomic write and dies without committing or unwinding (as under
  // kill -9): its temporary file stays behind.
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    AtomicFileWriter file(dir / "log.csv");
    file.append("half a row");
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  AtomicFileWriter live(dir / "events.csv");  // this process's, still being written
  ASSERT_EQ(count_entries(dir), 2);
  EXPECT_EQ(remove_orphaned_temporaries(dir), 1);
  EXPECT_EQ(count_entries(dir), 1);
  EXPECT_TRUE(std::filesystem::exists(live.temporary_path()));
  live.append("a\n");
  live.commit();
  EXPECT_EQ(read_text_file(dir / "events.csv"), "a\n");
}

}  // namespace
}  // namespace flexgait
