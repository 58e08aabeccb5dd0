# Writes the program-version header at build time (run with cmake -P by the
# granasym_program_version target of common/CMakeLists.txt on every build):
# "<project version>+<git describe --always --dirty --tags>" of the source
# tree, or "granasym <project version> (no git)" outside a git checkout or
# without git. The header is rewritten only when its text changes, so an
# unchanged tree recompiles nothing.
#
# Variables: SOURCE_DIR (the project source tree), OUTPUT (the header),
# PROJECT_VERSION, GIT_EXECUTABLE (empty when git was not found).
cmake_minimum_required(VERSION 3.18)

set(version "granasym ${PROJECT_VERSION} (no git)")
if(GIT_EXECUTABLE)
  # Only the project's own checkout counts, not a repository that happens to
  # contain an unpacked source tree.
  execute_process(
    COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE_DIR}" rev-parse --show-toplevel
    RESULT_VARIABLE toplevel_result
    OUTPUT_VARIABLE toplevel
    ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
  get_filename_component(source_real "${SOURCE_DIR}" REALPATH)
  if(toplevel_result EQUAL 0)
    get_filename_component(toplevel_real "${toplevel}" REALPATH)
  endif()
  if(toplevel_result EQUAL 0 AND toplevel_real STREQUAL source_real)
    execute_process(
      COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE_DIR}" describe --always --dirty --tags
      RESULT_VARIABLE describe_result
      OUTPUT_VARIABLE describe
      ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
    if(describe_result EQUAL 0 AND NOT describe STREQUAL "")
      set(version "${PROJECT_VERSION}+${describe}")
    endif()
  endif()
endif()

string(REPLACE "\\" "\\\\" escaped "${version}")
string(REPLACE "\"" "\\\"" escaped "${escaped}")
set(text "// Generated at build time by common/write_program_version.cmake; do not edit.
#pragma once
#define GRANASYM_PROGRAM_VERSION \"${escaped}\"
")
set(old "")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUTPUT}" "${text}")
endif()
