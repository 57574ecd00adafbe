# cmake -DBUILD_DIR=... -DCONFIG=... -DSOC_SIM=... -DEXAMPLE_DIR=... -DWORK_DIR=...
#       -DGENERATOR=... -DC_COMPILER=... -DNAME=... -P build_sdk_example.cmake
# Installs the build tree into WORK_DIR/prefix and builds EXAMPLE_DIR, whose
# application is lib<NAME>.so, against it in WORK_DIR/example-build, for a
# test that then runs it (a ctest fixture).
if(NOT DEFINED NAME)
  message(FATAL_ERROR "build_sdk_example.cmake: NAME is not set")
endif()
include(${CMAKE_CURRENT_LIST_DIR}/sdk_example_support.cmake)
install_sdk_and_build_example(${NAME})
message(STATUS "installed SDK in ${prefix}; built ${library}")
