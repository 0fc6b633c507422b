#include "flexgait/campaign/program_build.hpp"

#include "flexgait/git_describe.hpp"  // generated at build time (cmake/git_describe.cmake)
#include "flexgait/version.hpp"

namespace flexgait::campaign {

std::string program_build() {
  const std::string describe = FLEXGAIT_GIT_DESCRIBE;
  return describe.empty() ? std::string(kVersion) : std::string(kVersion) + " (git " + describe + ")";
}

}  // namespace flexgait::campaign
