# cmake -DBUILD_DIR=... -DCONFIG=... -DSOC_SIM=... -DPREFIX=... -P install_sdk.cmake
# Installs the build tree into PREFIX (emptied first), for the tests that
# then build examples against it (a ctest fixture).
include(${CMAKE_CURRENT_LIST_DIR}/sdk_example_support.cmake)
if(NOT DEFINED PREFIX)
  message(FATAL_ERROR "install_sdk.cmake: PREFIX is not set")
endif()
file(REMOVE_RECURSE ${PREFIX})
install_sdk(${PREFIX})
message(STATUS "installed the SDK in ${PREFIX}")
