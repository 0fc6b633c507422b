// The build named in a campaign's signature: the version, then the git description of the source
// tree when it was built from a checkout.
#include "flexgait/campaign/program_build.hpp"

#include <gtest/gtest.h>

#include "flexgait/version.hpp"

namespace flexgait::campaign {
namespace {

TEST(ProgramBuild, IsTheVersionThenTheGitDescription) {
  const std::string build = program_build();
  const std::string version = kVersion;
  ASSERT_EQ(build.rfind(version, 0), 0u) << build;
  if (build != version) {  // built from a git checkout: "VERSION (git DESCRIBE)", DESCRIBE not empty
    EXPECT_EQ(build.substr(version.size(), 6), " (git ") << build;
    EXPECT_GT(build.size(), version.size() + 7) << build;
    EXPECT_EQ(build.back(), ')') << build;
  }
  EXPECT_EQ(build, program_build());  // fixed for the life of the program
}

}  // namespace
}  // namespace flexgait::campaign
