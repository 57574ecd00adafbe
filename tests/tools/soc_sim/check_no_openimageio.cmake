# soc_sim writes its PNG frames through libpng alone and must not load
# OpenImageIO, whose ~260 shared libraries cost every run about 0.3 s and
# 95 MiB before anything is simulated (issue 13, item 5). The dynamic
# loader lists what a run loads (LD_TRACE_LOADED_OBJECTS, as ldd does);
# libpng must be among them (proof that the list is the real one) and no
# OpenImageIO library. Run with -DSOC_SIM=...
execute_process(COMMAND ${CMAKE_COMMAND} -E env LD_TRACE_LOADED_OBJECTS=1 ${SOC_SIM} --list-apps
                OUTPUT_VARIABLE loaded ERROR_VARIABLE errors RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "listing what soc_sim loads failed with status ${status}: ${errors}")
endif()
if(NOT loaded MATCHES "libpng")
  message(FATAL_ERROR "soc_sim does not load libpng, or the loader's list is not what this test expects:\n${loaded}")
endif()
if(loaded MATCHES "OpenImageIO")
  string(REGEX MATCHALL "[^\n]*OpenImageIO[^\n]*" lines "${loaded}")
  message(FATAL_ERROR "soc_sim loads OpenImageIO (link tessera_png_writer, not tessera_frame_writer):\n${lines}")
endif()
