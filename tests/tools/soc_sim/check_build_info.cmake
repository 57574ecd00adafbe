# cmake/write_build_info.cmake: the commit of a checkout as `git describe
# --always --dirty` gives it, "unknown" outside a checkout (even inside
# another repository, as this scratch folder in the build tree is) and
# without git, and no rewrite when nothing changed (so a build recompiles
# nothing). Run with -DSCRIPT=... -DSOURCE_DIR=... -DWORK_DIR=... and
# -DGIT_EXECUTABLE=... (empty when git is missing).
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/not_a_checkout)
set(header ${WORK_DIR}/values.h)

function(write_info source git)
  execute_process(COMMAND ${CMAKE_COMMAND} -DGIT_EXECUTABLE=${git} -DSOURCE_DIR=${source} -DVERSION=1.2.3
                          -DOUTPUT=${header} -P ${SCRIPT} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "write_build_info.cmake failed with status ${status}")
  endif()
endfunction()

function(expect_commit expected)
  file(READ ${header} text)
  if(NOT text MATCHES "#define TESSERA_BUILD_VERSION \"1.2.3\"")
    message(FATAL_ERROR "no version 1.2.3 in:\n${text}")
  endif()
  if(NOT text MATCHES "#define TESSERA_BUILD_COMMIT \"${expected}\"")
    message(FATAL_ERROR "expected commit '${expected}' in:\n${text}")
  endif()
endfunction()

write_info(${WORK_DIR}/not_a_checkout "${GIT_EXECUTABLE}")
expect_commit(unknown)
write_info(${SOURCE_DIR} "")
expect_commit(unknown)

set(expected unknown)
if(GIT_EXECUTABLE AND EXISTS ${SOURCE_DIR}/.git)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} describe --always --dirty OUTPUT_VARIABLE expected
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
endif()
write_info(${SOURCE_DIR} "${GIT_EXECUTABLE}")
expect_commit("${expected}")

# The same text again: the file keeps its time stamp (one-second resolution).
file(TIMESTAMP ${header} before "%s")
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1)
write_info(${SOURCE_DIR} "${GIT_EXECUTABLE}")
file(TIMESTAMP ${header} after "%s")
if(NOT before STREQUAL after)
  message(FATAL_ERROR "the header was rewritten although nothing changed (${before} -> ${after})")
endif()
message(STATUS "build info: commit '${expected}', 'unknown' outside a checkout, no rewrite without a change")
