# cmake -DPREFIX=... -DCONFIG=... -DEXAMPLE_DIR=... -DNAME=... -DWORK_DIR=... -DGENERATOR=...
#       -DC_COMPILER=... -DFRAMES=... -DBACKENDS=a|b|... [-DBAD_ARGUMENTS=... -DBAD_MESSAGE=...]
#       [-DROI_ARGUMENTS=... -DROI_FIRST=... -DROI_LAST=... -DROI_CHECK=... -DPYTHON=...]
#       -P check_sdk_example_arm.cmake
# Builds EXAMPLE_DIR against the SDK installed in PREFIX twice, natively
# (lib<NAME>.so) and with the installed ARM922T toolchain file (<NAME>.elf),
# runs both on the installed soc_sim for FRAMES frames on each back end of
# BACKENDS and checks that the ELF ran on the ISS and drew the native
# library's frames, byte for byte.
# With BAD_ARGUMENTS (the application's, separated by spaces), the ELF
# given them must exit with status 2 and print BAD_MESSAGE.
include(${CMAKE_CURRENT_LIST_DIR}/sdk_example_support.cmake)
foreach(var PREFIX CONFIG EXAMPLE_DIR NAME WORK_DIR GENERATOR C_COMPILER FRAMES BACKENDS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_sdk_example_arm.cmake: ${var} is not set")
  endif()
endforeach()
set(soc_sim ${PREFIX}/bin/soc_sim)
if(NOT EXISTS ${soc_sim})
  message(FATAL_ERROR "no SDK in ${PREFIX}: the fixture sdk_arm_install installs it")
endif()
string(REPLACE "|" ";" BACKENDS "${BACKENDS}")
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

build_example(${NAME} ${PREFIX} ${WORK_DIR}/native)
set(library ${built})
build_example(${NAME} ${PREFIX} ${WORK_DIR}/arm ${PREFIX}/lib/cmake/tessera/arm922t-toolchain.cmake)
set(elf ${built})

# The PNG writer stores no time stamp, so equal pixels give equal files.
function(compare_frames native_dir arm_dir)
  foreach(dir ${native_dir} ${arm_dir})
    file(GLOB frames RELATIVE ${dir} ${dir}/frame_*.png)
    list(LENGTH frames count)
    if(NOT count EQUAL FRAMES)
      message(FATAL_ERROR "expected ${FRAMES} frames in ${dir}, found ${count}: ${frames}")
    endif()
  endforeach()
  set(differ "")
  foreach(png IN LISTS frames)
    if(NOT EXISTS ${native_dir}/${png})
      message(FATAL_ERROR "the native run drew no ${native_dir}/${png}")
    endif()
    file(SHA256 ${native_dir}/${png} native)
    file(SHA256 ${arm_dir}/${png} arm)
    if(NOT native STREQUAL arm)
      list(APPEND differ ${png})
    endif()
  endforeach()
  if(differ)
    message(FATAL_ERROR "${elf} on the ISS drew frames other than ${library}'s: ${differ} "
                        "(${arm_dir} against ${native_dir})")
  endif()
endfunction()

foreach(backend IN LISTS BACKENDS)
  foreach(kind native arm)
    if(kind STREQUAL "native")
      set(app ${library})
    else()
      set(app ${elf})
    endif()
    set(out ${WORK_DIR}/out-${backend}-${kind})
    execute_process(COMMAND ${soc_sim} --app ${app} --backend ${backend} --frames ${FRAMES} --out ${out} --quiet
                    RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "soc_sim --app ${app} --backend ${backend} exited with ${status}, not 0:\n${output}")
    endif()
  endforeach()
  # The ELF's run was the ISS's: its statistics count the core's instructions.
  file(READ ${WORK_DIR}/out-${backend}-arm/stats.json stats)
  string(JSON instructions ERROR_VARIABLE error GET "${stats}" stats host iss instructions)
  if(error OR NOT instructions GREATER 0)
    message(FATAL_ERROR "${WORK_DIR}/out-${backend}-arm/stats.json has no instructions of the ISS "
                        "(stats.host.iss.instructions: ${instructions} ${error}): did ${elf} run on the ISS?")
  endif()
  compare_frames(${WORK_DIR}/out-${backend}-native ${WORK_DIR}/out-${backend}-arm)
endforeach()

if(DEFINED BAD_ARGUMENTS)
  separate_arguments(arguments UNIX_COMMAND "${BAD_ARGUMENTS}")
  execute_process(COMMAND ${soc_sim} --app ${elf} --frames 1 --out ${WORK_DIR}/out-bad --quiet -- ${arguments}
                  RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
  string(FIND "${output}" "${BAD_MESSAGE}" found)
  if(NOT status EQUAL 2 OR found EQUAL -1)
    message(FATAL_ERROR "soc_sim --app ${elf} -- ${BAD_ARGUMENTS}: status ${status} (want 2), "
                        "'${BAD_MESSAGE}' printed: ${found} (-1 = no)\n${output}")
  endif()
endif()
# With ROI_ARGUMENTS (the application's, separated by spaces, marking frames
# ROI_FIRST to ROI_LAST - 1 as its region of interest) and ROI_CHECK (a
# Python script run by PYTHON): the library and the ELF each marked it, on
# the first back end, and stats.json's roi says so (ROI_CHECK's checks).
if(DEFINED ROI_ARGUMENTS)
  separate_arguments(arguments UNIX_COMMAND "${ROI_ARGUMENTS}")
  list(GET BACKENDS 0 backend)
  foreach(app ${library} ${elf})
    get_filename_component(kind ${app} LAST_EXT)
    set(out ${WORK_DIR}/out-roi${kind})
    execute_process(COMMAND ${soc_sim} --app ${app} --backend ${backend} --frames ${FRAMES} --out ${out} --quiet
                            -- ${arguments}
                    RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "soc_sim --app ${app} -- ${ROI_ARGUMENTS} exited with ${status}, not 0:\n${output}")
    endif()
    execute_process(COMMAND ${PYTHON} ${ROI_CHECK} ${out}/stats.json ${ROI_FIRST} ${ROI_LAST}
                    RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "the region of interest of soc_sim --app ${app} -- ${ROI_ARGUMENTS}:\n${output}")
    endif()
    message(STATUS "${output}")
  endforeach()
endif()
message(STATUS "${elf} on the ISS drew the ${FRAMES} frames of ${library} on ${BACKENDS}")
