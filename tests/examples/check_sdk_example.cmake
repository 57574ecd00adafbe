# cmake -DBUILD_DIR=... -DCONFIG=... -DSOC_SIM=... -DEXAMPLE_DIR=... -DWORK_DIR=...
#       -DGENERATOR=... -DC_COMPILER=... -P check_sdk_example.cmake
# Installs the build tree into WORK_DIR/prefix, builds EXAMPLE_DIR against
# it in WORK_DIR/mine-build and runs it on the installed soc_sim: two frames
# that differ, and a bad argument reported by the application with status 2.
foreach(var BUILD_DIR CONFIG SOC_SIM EXAMPLE_DIR WORK_DIR GENERATOR C_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_sdk_example.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT EXISTS "${SOC_SIM}")
  message(FATAL_ERROR "soc_sim has not been built (${SOC_SIM}): run `cmake --build ${BUILD_DIR}` first")
endif()

set(prefix ${WORK_DIR}/prefix)
set(example_build ${WORK_DIR}/mine-build)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# Runs a command and fails the test with its output unless it succeeds.
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT status EQUAL 0)
    string(JOIN " " command ${ARGN})
    message(FATAL_ERROR "${what} failed (${status}):\n  ${command}\n${out}")
  endif()
endfunction()

run_step("installing ${BUILD_DIR} into ${prefix} (has `cmake --build ${BUILD_DIR}` built everything?)"
         ${CMAKE_COMMAND} --install ${BUILD_DIR} --config ${CONFIG} --prefix ${prefix})
foreach(file bin/soc_sim include/GLES/gl.h include/GLES/glext.h include/KHR/khrplatform.h include/EGL/egl.h
        include/tessera/app.h
        lib/cmake/tessera/tesseraConfig.cmake lib/cmake/tessera/tesseraConfigVersion.cmake
        lib/cmake/tessera/TesseraApp.cmake)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "the install has no ${file} under ${prefix}")
  endif()
endforeach()

run_step("configuring ${EXAMPLE_DIR} against the installed SDK"
         ${CMAKE_COMMAND} -S ${EXAMPLE_DIR} -B ${example_build} -G ${GENERATOR}
         -DCMAKE_C_COMPILER=${C_COMPILER} -DCMAKE_BUILD_TYPE=${CONFIG} -DCMAKE_PREFIX_PATH=${prefix})
run_step("building the example" ${CMAKE_COMMAND} --build ${example_build} --config ${CONFIG})
set(library ${example_build}/libmine.so)
if(NOT EXISTS ${library})
  message(FATAL_ERROR "building the example made no ${library}")
endif()

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
