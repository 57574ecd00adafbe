# What the SDK example tests share, included by check_sdk_example.cmake and
# build_sdk_example.cmake: install the build tree and build an example out
# of tree against the installed package, as a user would.

# Runs a command and fails the test with its output unless it succeeds.
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT status EQUAL 0)
    string(JOIN " " command ${ARGN})
    message(FATAL_ERROR "${what} failed (${status}):\n  ${command}\n${out}")
  endif()
endfunction()

# install_sdk_and_build_example(<library name>)
# Needs BUILD_DIR, CONFIG, SOC_SIM, EXAMPLE_DIR, WORK_DIR, GENERATOR and
# C_COMPILER. Empties WORK_DIR, installs BUILD_DIR into WORK_DIR/prefix,
# builds EXAMPLE_DIR in WORK_DIR/example-build and sets `prefix` and
# `library` (the example's lib<name>.so) in the caller's scope.
function(install_sdk_and_build_example name)
  foreach(var BUILD_DIR CONFIG SOC_SIM EXAMPLE_DIR WORK_DIR GENERATOR C_COMPILER)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${CMAKE_CURRENT_LIST_FILE}: ${var} is not set")
    endif()
  endforeach()
  if(NOT EXISTS "${SOC_SIM}")
    message(FATAL_ERROR "soc_sim has not been built (${SOC_SIM}): run `cmake --build ${BUILD_DIR}` first")
  endif()
  set(install_prefix ${WORK_DIR}/prefix)
  set(example_build ${WORK_DIR}/example-build)
  file(REMOVE_RECURSE ${WORK_DIR})
  file(MAKE_DIRECTORY ${WORK_DIR})

  run_step("installing ${BUILD_DIR} into ${install_prefix} (has `cmake --build ${BUILD_DIR}` built everything?)"
           ${CMAKE_COMMAND} --install ${BUILD_DIR} --config ${CONFIG} --prefix ${install_prefix})
  foreach(file bin/soc_sim include/GLES/gl.h include/GLES/glext.h include/KHR/khrplatform.h include/EGL/egl.h
          include/tessera/app.h lib/cmake/tessera/tesseraConfig.cmake
          lib/cmake/tessera/tesseraConfigVersion.cmake lib/cmake/tessera/TesseraApp.cmake)
    if(NOT EXISTS ${install_prefix}/${file})
      message(FATAL_ERROR "the install has no ${file} under ${install_prefix}")
    endif()
  endforeach()

  run_step("configuring ${EXAMPLE_DIR} against the installed SDK"
           ${CMAKE_COMMAND} -S ${EXAMPLE_DIR} -B ${example_build} -G ${GENERATOR}
           -DCMAKE_C_COMPILER=${C_COMPILER} -DCMAKE_BUILD_TYPE=${CONFIG} -DCMAKE_PREFIX_PATH=${install_prefix})
  run_step("building the example" ${CMAKE_COMMAND} --build ${example_build} --config ${CONFIG})
  set(built ${example_build}/lib${name}.so)
  if(NOT EXISTS ${built})
    message(FATAL_ERROR "building the example made no ${built}")
  endif()
  set(prefix ${install_prefix} PARENT_SCOPE)
  set(library ${built} PARENT_SCOPE)
endfunction()
