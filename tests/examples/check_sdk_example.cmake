# cmake -DBUILD_DIR=... -DCONFIG=... -DSOC_SIM=... -DEXAMPLE_DIR=... -DWORK_DIR=...
#       -DGENERATOR=... -DC_COMPILER=... -P check_sdk_example.cmake
# Installs the build tree into WORK_DIR/prefix, builds EXAMPLE_DIR against
# it in WORK_DIR/example-build and runs it on the installed soc_sim: two
# frames that differ, and a bad argument reported by the application with
# status 2.
include(${CMAKE_CURRENT_LIST_DIR}/sdk_example_support.cmake)
install_sdk_and_build_example(mine)

set(out ${WORK_DIR}/out)
execute_process(COMMAND ${prefix}/bin/soc_sim --app ${library} --frames 2 --out ${out} --quiet
                RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the installed soc_sim running libmine.so exited with ${status}, not 0:\n${output}")
endif()
file(GLOB frames ${out}/frame_*.png)
list(LENGTH frames count)
if(NOT count EQUAL 2)
  message(FATAL_ERROR "expected 2 frames in ${out}, found ${count}: ${frames}")
endif()
# The PNG writer stores no time stamp, so equal pixels give equal files.
file(SHA256 ${out}/frame_0000.png first)
file(SHA256 ${out}/frame_0001.png second)
if(first STREQUAL second)
  message(FATAL_ERROR "the shape does not turn: ${out}/frame_0000.png and frame_0001.png are the same image")
endif()

execute_process(COMMAND ${prefix}/bin/soc_sim --app ${library} --frames 2 --out ${WORK_DIR}/out-bad --quiet
                        -- --sides 1
                RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT status EQUAL 2)
  message(FATAL_ERROR "soc_sim running libmine.so with --sides 1 exited with ${status}, not 2:\n${output}")
endif()
if(NOT output MATCHES "mine: --sides must be a number from 3 to 64, not '1'")
  message(FATAL_ERROR "soc_sim running libmine.so with --sides 1 did not print the application's message:\n${output}")
endif()
message(STATUS "installed SDK in ${prefix}; libmine.so drew 2 different frames and rejected --sides 1")
