# Install rules: soc_sim and its tools, and the SDK for out-of-tree
# applications (the GL ES/EGL headers, <tessera/app.h>, the CMake package
# `tessera`, see cmake/tesseraConfig.cmake.in and examples/mine, and the
# ARM922T's toolchain file and libraries for applications on the ISS).
# Included at the end of the top-level CMakeLists.txt, once every target
# exists. Everything installed is built by a plain `cmake --build` or is a
# source file.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(TESSERA_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/tessera)

set(tessera_installed_programs soc_sim)
foreach(tool recip_table render_compare ap_asm iss_run)
  if(TARGET ${tool})
    list(APPEND tessera_installed_programs ${tool})
  endif()
endforeach()
# The programs link only static project libraries and system ones; a
# dependency found outside the system directories keeps its folder in the
# installed RPATH instead of failing at run time.
set_target_properties(${tessera_installed_programs} PROPERTIES INSTALL_RPATH_USE_LINK_PATH ON)
install(TARGETS ${tessera_installed_programs} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

set(tessera_sdk_headers ${PROJECT_SOURCE_DIR}/sw_driver/include)
install(DIRECTORY ${tessera_sdk_headers}/GLES ${tessera_sdk_headers}/EGL ${tessera_sdk_headers}/KHR
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
install(FILES ${tessera_sdk_headers}/tessera/app.h ${tessera_sdk_headers}/tessera/roi.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tessera)

# The ARM side (sw_driver/runtime/README.md): the built-in applications
# cross-compiled, where soc_sim looks for them with host.model=iss (beside
# itself, in arm922t/), and what an application of one's own links to run
# on the ISS: the archive of the driver, the back ends and the runtime, and
# the linker script, used through the package with the toolchain file.
install(FILES ${TESSERA_BUILTIN_ISS_IMAGE} ${TESSERA_CLUSTER_ISS_IMAGE} DESTINATION ${CMAKE_INSTALL_BINDIR}/arm922t)
set(TESSERA_ARM922T_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/tessera/arm922t)
install(FILES ${TESSERA_ARM_LIBRARY} ${TESSERA_LINKER_SCRIPT} DESTINATION ${TESSERA_ARM922T_INSTALL_DIR})

# Paths in the package are relative to the prefix it is found in, so an
# installed tree can be moved (`cmake --install build --prefix P` works for
# any P).
set(TESSERA_SOC_SIM_INSTALL_PATH ${CMAKE_INSTALL_BINDIR}/soc_sim)
get_filename_component(TESSERA_LINKER_SCRIPT_NAME ${TESSERA_LINKER_SCRIPT} NAME)
get_filename_component(TESSERA_ARM_LIBRARY_NAME ${TESSERA_ARM_LIBRARY} NAME)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/tesseraConfig.cmake.in
  ${PROJECT_BINARY_DIR}/tesseraConfig.cmake
  INSTALL_DESTINATION ${TESSERA_INSTALL_CMAKEDIR}
  PATH_VARS CMAKE_INSTALL_INCLUDEDIR TESSERA_SOC_SIM_INSTALL_PATH TESSERA_ARM922T_INSTALL_DIR)
# ARCH_INDEPENDENT, since the package serves two architectures: natively
# the one soc_sim is built for (applications are loaded into its process),
# which tesseraConfig.cmake checks itself, and the ARM922T's with the
# toolchain file.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/tesseraConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion ARCH_INDEPENDENT)
install(FILES ${PROJECT_BINARY_DIR}/tesseraConfig.cmake ${PROJECT_BINARY_DIR}/tesseraConfigVersion.cmake
              ${CMAKE_CURRENT_LIST_DIR}/TesseraApp.cmake ${CMAKE_CURRENT_LIST_DIR}/arm922t-toolchain.cmake
        DESTINATION ${TESSERA_INSTALL_CMAKEDIR})
