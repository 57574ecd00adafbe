# The ARM sub-build (TESSERA_TARGET_ISS, with cmake/arm922t-toolchain.cmake):
# the host's software cross-compiled for the ISS. The main build starts it
# (sw_driver/CMakeLists.txt) and hands it what only a native build can
# make: the array assembler (TESSERA_AP_ASM), the linker script generated
# from the memory map (TESSERA_LINKER_SCRIPT) and the folders of the
# header-only libraries the driver uses (TESSERA_HEADER_DIRS: nlohmann/json,
# glm, tinyobjloader). Those folders are Debian's /usr/include, which the
# ARM compiler must not search whole (its C library is newlib's), so each
# library is reached through a link of its own. It also names the SDK's
# archive this build makes (TESSERA_ARM_LIBRARY).
enable_language(ASM)
include(Tessera)

foreach(variable TESSERA_AP_ASM TESSERA_LINKER_SCRIPT TESSERA_HEADER_DIRS TESSERA_ARM_LIBRARY)
  if(NOT ${variable})
    message(FATAL_ERROR "the ARM sub-build needs ${variable} from the main build")
  endif()
endforeach()

set(links ${CMAKE_BINARY_DIR}/host_headers)
file(MAKE_DIRECTORY ${links})
foreach(entry nlohmann glm tiny_obj_loader.h)
  foreach(dir IN LISTS TESSERA_HEADER_DIRS)
    if(EXISTS ${dir}/${entry} AND NOT EXISTS ${links}/${entry})
      file(CREATE_LINK ${dir}/${entry} ${links}/${entry} SYMBOLIC)
    endif()
  endforeach()
  if(NOT EXISTS ${links}/${entry})
    message(FATAL_ERROR "the ARM sub-build found no ${entry} in ${TESSERA_HEADER_DIRS}")
  endif()
endforeach()
add_library(tessera_host_headers INTERFACE)
target_include_directories(tessera_host_headers SYSTEM INTERFACE ${links})
add_library(nlohmann_json::nlohmann_json ALIAS tessera_host_headers)
add_library(glm::glm ALIAS tessera_host_headers)
add_library(tessera_tinyobjloader STATIC ${PROJECT_SOURCE_DIR}/sw_driver/runtime/tinyobjloader.cpp)
target_link_libraries(tessera_tinyobjloader PUBLIC tessera_host_headers)
add_library(tinyobjloader::tinyobjloader ALIAS tessera_tinyobjloader)

add_executable(ap_asm IMPORTED)
set_target_properties(ap_asm PROPERTIES IMPORTED_LOCATION ${TESSERA_AP_ASM})

# The HostApi of the ISS (contract/host/host_api.h): plain loads and stores.
add_compile_definitions(TESSERA_HOST_ISS)

add_subdirectory(contract)
add_subdirectory(sw_driver)
