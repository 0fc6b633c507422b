#pragma once
/// \file program_build.hpp
/// Which build of flexgait is running, finer than its version: what a campaign's signature names
/// (a resumed campaign must come from the same build, or its rows could mix two programs).
#include <string>

namespace flexgait::campaign {

/// "VERSION (git DESCRIBE)": DESCRIBE is `git describe --always --dirty --abbrev=12` of the source
/// tree when it was built (a dirty tree with the SHA-1 of its `git diff HEAD` appended: two
/// different edits of one commit differ). Outside a git checkout: the version alone (kVersion),
/// so two such builds of one version look alike.
std::string program_build();

}  // namespace flexgait::campaign
