#pragma once

namespace isg::common {

// The project's version (CMake's project(VERSION)): what datasets name as their generator
// ("isg simulate 0.1.0"), so that the same inputs give the same bytes from any build.
inline constexpr const char* kProjectVersion = ISG_PROJECT_VERSION;

// The build this binary is: `git describe --always --dirty --tags` of the checkout it was built
// from (a commit, "-dirty" when the working tree had changes), or kProjectVersion when it was not
// built from a git checkout. Written at every build (common/build_version.cmake); what run folders
// and sweeps record as the build that made them.
const char* buildVersion();

}  // namespace isg::common
