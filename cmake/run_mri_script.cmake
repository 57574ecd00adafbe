# Runs an ar MRI script (`ar -M < SCRIPT`, which reads it from standard input
# only) in the current folder, failing on any message from ar:
#
#   cmake -DAR=<ar> -DSCRIPT=<script> -P run_mri_script.cmake
#
# Used by the ARM sub-build to merge the SDK's archive
# (sw_driver/runtime/CMakeLists.txt).
foreach(variable AR SCRIPT)
  if(NOT ${variable})
    message(FATAL_ERROR "run_mri_script.cmake: ${variable} is not set")
  endif()
endforeach()
execute_process(COMMAND ${AR} -M INPUT_FILE ${SCRIPT} RESULT_VARIABLE status OUTPUT_VARIABLE output
                ERROR_VARIABLE output)
# ar reports a syntax error in the script with status 0.
if(NOT status EQUAL 0 OR output)
  message(FATAL_ERROR "${AR} -M < ${SCRIPT} failed (${status}):\n${output}")
endif()
