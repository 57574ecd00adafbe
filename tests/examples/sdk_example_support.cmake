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

# The files every install must have: soc_sim, the SDK's headers, the CMake
# package and the ARM side (the built-in applications for host.model=iss,
# the toolchain file, the archive and the linker script).
set(TESSERA_INSTALLED_FILES
    bin/soc_sim bin/arm922t/tessera_apps.elf include/GLES/gl.h include/GLES/glext.h include/KHR/khrplatform.h
    include/EGL/egl.h include/tessera/app.h include/tessera/roi.h lib/cmake/tessera/tesseraConfig.cmake
    lib/cmake/tessera/tesseraConfigVersion.cmake lib/cmake/tessera/TesseraApp.cmake
    lib/cmake/tessera/arm922t-toolchain.cmake lib/tessera/arm922t/libtessera_arm922t.a
    lib/tessera/arm922t/tessera_arm922t.ld)

# install_sdk(<prefix>)
# Needs BUILD_DIR, CONFIG and SOC_SIM. Installs BUILD_DIR into <prefix> and
# checks that every file of TESSERA_INSTALLED_FILES is there.
function(install_sdk install_prefix)
  foreach(var BUILD_DIR CONFIG SOC_SIM)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${CMAKE_CURRENT_LIST_FILE}: ${var} is not set")
    endif()
  endforeach()
  if(NOT EXISTS "${SOC_SIM}")
    message(FATAL_ERROR "soc_sim has not been built (${SOC_SIM}): run `cmake --build ${BUILD_DIR}` first")
  endif()
  run_step("installing ${BUILD_DIR} into ${install_prefix} (has `cmake --build ${BUILD_DIR}` built everything?)"
           ${CMAKE_COMMAND} --install ${BUILD_DIR} --config ${CONFIG} --prefix ${install_prefix})
  foreach(file IN LISTS TESSERA_INSTALLED_FILES)
    if(NOT EXISTS ${install_prefix}/${file})
      message(FATAL_ERROR "the install has no ${file} under ${install_prefix}")
    endif()
  endforeach()
endfunction()

# build_example(<name> <prefix> <build folder> [<toolchain file>])
# Needs EXAMPLE_DIR, GENERATOR and CONFIG, and C_COMPILER for a native
# build. Builds EXAMPLE_DIR against the SDK installed in <prefix>: natively
# into lib<name>.so, or with the toolchain file into <name>.elf, which is
# then found through the toolchain file alone (no CMAKE_PREFIX_PATH). Sets
# `built` in the caller's scope to the application's path.
function(build_example name install_prefix build_dir)
  set(toolchain ${ARGN})
  if(toolchain)
    set(options -DCMAKE_TOOLCHAIN_FILE=${toolchain})
    set(file ${build_dir}/${name}.elf)
  else()
    set(options -DCMAKE_C_COMPILER=${C_COMPILER} -DCMAKE_PREFIX_PATH=${install_prefix})
    set(file ${build_dir}/lib${name}.so)
  endif()
  run_step("configuring ${EXAMPLE_DIR} against the installed SDK"
           ${CMAKE_COMMAND} -S ${EXAMPLE_DIR} -B ${build_dir} -G ${GENERATOR} -DCMAKE_BUILD_TYPE=${CONFIG} ${options})
  run_step("building the example" ${CMAKE_COMMAND} --build ${build_dir} --config ${CONFIG})
  if(NOT EXISTS ${file})
    message(FATAL_ERROR "building the example made no ${file}")
  endif()
  set(built ${file} PARENT_SCOPE)
endfunction()

# install_sdk_and_build_example(<library name>)
# Needs BUILD_DIR, CONFIG, SOC_SIM, EXAMPLE_DIR, WORK_DIR, GENERATOR and
# C_COMPILER. Empties WORK_DIR, installs BUILD_DIR into WORK_DIR/prefix,
# builds EXAMPLE_DIR in WORK_DIR/example-build and sets `prefix` and
# `library` (the example's lib<name>.so) in the caller's scope.
function(install_sdk_and_build_example name)
  foreach(var EXAMPLE_DIR WORK_DIR GENERATOR C_COMPILER)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${CMAKE_CURRENT_LIST_FILE}: ${var} is not set")
    endif()
  endforeach()
  file(REMOVE_RECURSE ${WORK_DIR})
  file(MAKE_DIRECTORY ${WORK_DIR})
  install_sdk(${WORK_DIR}/prefix)
  build_example(${name} ${WORK_DIR}/prefix ${WORK_DIR}/example-build)
  set(prefix ${WORK_DIR}/prefix PARENT_SCOPE)
  set(library ${built} PARENT_SCOPE)
endfunction()
