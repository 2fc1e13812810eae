# Writes OUTPUT, the definition of isg::common::buildVersion(): `git describe --always --dirty
# --tags` of SOURCE_DIR, or PROJECT_VERSION when that is not a git checkout (or git is missing).
# Run at every build; the file is rewritten only when the version changed, so that nothing is
# recompiled otherwise.
set(version "")
find_program(GIT git)
if(GIT)
  execute_process(COMMAND ${GIT} -C ${SOURCE_DIR} describe --always --dirty --tags
                  OUTPUT_VARIABLE version RESULT_VARIABLE result ERROR_QUIET
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT result EQUAL 0)
    set(version "")
  endif()
endif()
if(version STREQUAL "")
  set(version "${PROJECT_VERSION}")
endif()
set(content "// Written by common/build_version.cmake at build time: the build this binary is.
#include \"common/version.hpp\"

namespace isg::common {

const char* buildVersion() { return \"${version}\"; }

}  // namespace isg::common
")
set(old "")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} old)
endif()
if(NOT old STREQUAL content)
  file(WRITE ${OUTPUT} "${content}")
endif()
