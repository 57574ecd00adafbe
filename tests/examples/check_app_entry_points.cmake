# cmake -DSOC_SIM=... -DWITH_MAIN=... -DWITH_BOTH=... -DWITHOUT_ENTRY=... -DWORK_DIR=... -P check_app_entry_points.cmake
# Which function soc_sim calls in an application library: tessera_app_main
# when there is one, else main (an ordinary program, with the arguments
# after "--"); with neither, a usage error (status 2) naming both.
foreach(var SOC_SIM WITH_MAIN WITH_BOTH WITHOUT_ENTRY WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_app_entry_points.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT EXISTS "${SOC_SIM}")
  message(FATAL_ERROR "soc_sim has not been built (${SOC_SIM}): build the project first")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

set(failures "")
# check(<library> <expected status> <text the output must contain> [app arguments...])
function(check library status text)
  execute_process(COMMAND ${SOC_SIM} --app ${library} --frames 1 --out ${WORK_DIR}/out --force -- ${ARGN}
                  RESULT_VARIABLE actual OUTPUT_VARIABLE output ERROR_VARIABLE output)
  string(FIND "${output}" "${text}" found)
  if(NOT actual EQUAL status OR found EQUAL -1)
    set(failures "${failures}--app ${library}: exit status ${actual} (want ${status}), output must contain "
                 "'${text}':\n${output}\n" PARENT_SCOPE)
  endif()
endfunction()

check(${WITH_MAIN} 0 "main ran with 2 argument(s): --sides 5" --sides 5)
check(${WITH_BOTH} 0 "tessera_app_main ran")
check(${WITHOUT_ENTRY} 2 "exports neither tessera_app_main nor main")
if(failures)
  message(FATAL_ERROR "${failures}")
endif()
