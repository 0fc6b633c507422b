// The progress bar off a terminal (a log, as under ctest and CI): one line per tenth reached, in
// order, none skipped twice or repeated, the last at 100 %, nothing after the end; and nothing at
// all when the caller asked for no lines off a terminal.
#include "flexgait/core/progress.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace flexgait {
namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// stderr is captured (a file, not a terminal) before the bar is made: it sees no terminal.
TEST(ProgressBar, OffATerminalOneLinePerTenthReached) {
  testing::internal::CaptureStderr();
  ProgressBar bar(20, "points", 0, true);
  for (int done = 0; done <= 20; ++done) bar.show(done);
  bar.show(20);  // after the end: nothing more
  const std::vector<std::string> out = lines(testing::internal::GetCapturedStderr());
  ASSERT_EQ(out.size(), 11u);
  for (int tenth = 0; tenth <= 10; ++tenth)
    EXPECT_EQ(out[static_cast<std::size_t>(tenth)].substr(0, 6),
              (tenth == 10 ? "100 % " : (tenth == 0 ? "  0 % " : " " + std::to_string(10 * tenth) + " % ")));
  EXPECT_EQ(out.front().find("(0/20 points)"), 6u);
  EXPECT_EQ(out.back().find("(20/20 points)"), 6u);
}

TEST(ProgressBar, JumpsPrintTheTenthReachedOnce) {
  testing::internal::CaptureStderr();
  ProgressBar bar(20, "points", 5, true);  // a resumed run: 5 done before
  bar.show(5);
  bar.show(15);
  bar.show(14);  // a late report of less: nothing
  bar.show(20);
  const std::vector<std::string> out = lines(testing::internal::GetCapturedStderr());
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].substr(0, 15), " 20 % (5/20 poi");
  EXPECT_EQ(out[1].substr(0, 16), " 70 % (15/20 poi");
  EXPECT_EQ(out[2].substr(0, 16), "100 % (20/20 poi");
}

TEST(ProgressBar, NothingOffATerminalUnlessAsked) {
  testing::internal::CaptureStderr();
  ProgressBar bar(3, "s");
  for (int done = 0; done <= 3; ++done) bar.show(done);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace flexgait
