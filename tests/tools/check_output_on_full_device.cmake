# Runs PROGRAM (with ARGS) with its standard output on /dev/full and expects it to fail
# with a message that says so (tools/common/guarded_main.h).
separate_arguments(args UNIX_COMMAND "${ARGS}")
get_filename_component(name ${PROGRAM} NAME)
execute_process(COMMAND ${PROGRAM} ${args} OUTPUT_FILE /dev/full ERROR_VARIABLE errors RESULT_VARIABLE status)
if(status EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} exited 0 with its output on /dev/full; stderr: ${errors}")
endif()
string(FIND "${errors}" "${name}: cannot write to standard output" found)
if(found EQUAL -1)
  message(FATAL_ERROR "${PROGRAM} (status ${status}) did not name the failed write; stderr: ${errors}")
endif()
message(STATUS "${PROGRAM} failed with status ${status}, naming the failed write")
