# Writes OUT, a header with FLEXGAIT_GIT_DESCRIBE: `git describe --always --dirty --abbrev=12` of
# SOURCE_DIR (a work tree with uncommitted changes also gets the first 12 hex digits of the SHA-1
# of `git diff HEAD`, so two different edits of one commit differ), or "" outside a git checkout
# or without git. Run at every build (cmake -P, target flexgait_git_describe in
# src/flexgait/campaign/CMakeLists.txt); OUT is rewritten only when the text changes, so an
# unchanged tree rebuilds nothing.
set(describe "")
find_program(GIT git)
if(GIT)
  execute_process(COMMAND "${GIT}" -C "${SOURCE_DIR}" describe --always --dirty --abbrev=12
                  OUTPUT_VARIABLE describe RESULT_VARIABLE status OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT status EQUAL 0)
    set(describe "")
  elseif(describe MATCHES "-dirty$")
    execute_process(COMMAND "${GIT}" -C "${SOURCE_DIR}" diff HEAD --no-ext-diff --no-color
                    OUTPUT_VARIABLE diff ERROR_QUIET)
    string(SHA1 diff_hash "${diff}")
    string(SUBSTRING "${diff_hash}" 0 12 diff_hash)
    set(describe "${describe}.${diff_hash}")
  endif()
endif()
set(text "#pragma once\n/// \\file git_describe.hpp  Generated at build time by cmake/git_describe.cmake.\n#define FLEXGAIT_GIT_DESCRIBE \"${describe}\"\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
else()
  set(old "")
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
