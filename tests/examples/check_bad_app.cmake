# cmake -DSOC_SIM=... -DLIBRARY_WITHOUT_ENTRY=... -DWORK_DIR=... -P check_bad_app.cmake
# soc_sim --app with a library that has no entry point, a file that is
# not a library and a path that does not exist: each must exit with status 2
# and name the file.
foreach(var SOC_SIM LIBRARY_WITHOUT_ENTRY WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_bad_app.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT EXISTS "${SOC_SIM}")
  message(FATAL_ERROR "soc_sim has not been built (${SOC_SIM}): build the project first")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

set(not_a_library ${WORK_DIR}/not_a_library.so)
file(WRITE ${not_a_library} "plain text, not an ELF file\n")
set(missing ${WORK_DIR}/missing/libmissing.so)

set(failures "")
foreach(app IN ITEMS ${LIBRARY_WITHOUT_ENTRY} ${not_a_library} ${missing})
  execute_process(COMMAND ${SOC_SIM} --app ${app} --frames 1 --out ${WORK_DIR}/out --quiet
                  RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
  string(FIND "${output}" "${app}" named)
  if(NOT status EQUAL 2 OR named EQUAL -1)
    string(APPEND failures "--app ${app}: exit status ${status} (want 2), message names the file: "
                           "${named} (-1 = no)\n${output}\n")
  endif()
endforeach()
if(failures)
  message(FATAL_ERROR "${failures}")
endif()
