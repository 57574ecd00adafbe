# Fails when a C or C++ source of the repository differs from what
# clang-format makes of it (.clang-format at the root). Run as
#   cmake -DCLANG_FORMAT=clang-format-14 -DSOURCE_DIR=<repo> -P check_format.cmake
# The files are those git tracks; outside a git checkout, every source
# under the project's own folders.
find_program(GIT git)
if(GIT AND EXISTS ${SOURCE_DIR}/.git)
  execute_process(COMMAND ${GIT} ls-files -- *.c *.cpp *.h WORKING_DIRECTORY ${SOURCE_DIR}
                  OUTPUT_VARIABLE listed OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "git ls-files failed in ${SOURCE_DIR}")
  endif()
  string(REPLACE "\n" ";" files "${listed}")
else()
  set(files)
  foreach(folder tlm sw_driver tools bench tests testbench rtl_models examples fuzz)
    file(GLOB_RECURSE found RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/${folder}/*.c ${SOURCE_DIR}/${folder}/*.cpp
         ${SOURCE_DIR}/${folder}/*.h)
    list(APPEND files ${found})
  endforeach()
endif()
list(LENGTH files count)
if(count EQUAL 0)
  message(FATAL_ERROR "no sources found under ${SOURCE_DIR}")
endif()
# One clang-format process for every file (one per file cost minutes on a
# loaded machine): its diagnostics name each file it would change.
execute_process(COMMAND ${CLANG_FORMAT} --dry-run -Werror ${files} WORKING_DIRECTORY ${SOURCE_DIR}
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE diagnostics)
set(unformatted)
if(NOT status EQUAL 0)
  string(REGEX MATCHALL "[^\n]+:[0-9]+:[0-9]+: error: code should be clang-formatted" lines "${diagnostics}")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE ":[0-9]+:[0-9]+: error: .*" "" file "${line}")
    list(APPEND unformatted ${file})
  endforeach()
  list(REMOVE_DUPLICATES unformatted)
  if(NOT unformatted)
    message(FATAL_ERROR "${CLANG_FORMAT} failed (status ${status}):\n${diagnostics}")
  endif()
endif()
if(unformatted)
  list(JOIN unformatted "\n  " shown)
  message(FATAL_ERROR "not formatted as .clang-format asks (fix: ${CLANG_FORMAT} -i <file>):\n  ${shown}")
endif()
message(STATUS "${count} files formatted as .clang-format asks")
