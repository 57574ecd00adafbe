# The ARM sub-build, started from the main (native) build: the driver, the
# back ends and the built-in applications cross-compiled for the ARM922T
# with the bare-metal runtime into bin/arm922t/tessera_apps.elf, which
# soc_sim runs with host.model=iss (sw_driver/runtime/README.md), and the
# SDK's archive for applications of one's own, arm922t/libtessera_arm922t.a
# (installed by cmake/Install.cmake with the linker script). It is a
# separate CMake project (ExternalProject: one project has one compiler),
# configured from this source tree with TESSERA_TARGET_ISS
# (cmake/Arm922tTarget.cmake) and handed what only the native build makes.
find_program(TESSERA_ARM_CXX arm-none-eabi-g++)
if(NOT TESSERA_ARM_CXX)
  message(FATAL_ERROR "arm-none-eabi-g++ not found: run scripts/setup.sh (gcc-arm-none-eabi, "
                      "libnewlib-arm-none-eabi, libstdc++-arm-none-eabi-newlib)")
endif()

# The linker script, generated from contract/soc/memory_map.def and
# contract/soc/software_layout.h.
add_executable(tessera_ld_script ${PROJECT_SOURCE_DIR}/sw_driver/runtime/write_linker_script.cpp)
target_link_libraries(tessera_ld_script PRIVATE tessera_contract tessera_warnings)
set(TESSERA_LINKER_SCRIPT ${PROJECT_BINARY_DIR}/arm922t/tessera_arm922t.ld)
add_custom_command(OUTPUT ${TESSERA_LINKER_SCRIPT}
                   COMMAND tessera_ld_script ${TESSERA_LINKER_SCRIPT}
                   DEPENDS tessera_ld_script
                   COMMENT "Generating the ARM922T linker script from the memory map")
add_custom_target(tessera_linker_script DEPENDS ${TESSERA_LINKER_SCRIPT})

# The header-only libraries' folders, as the native build found them.
find_path(TESSERA_JSON_HEADERS nlohmann/json.hpp REQUIRED)
find_path(TESSERA_GLM_HEADERS glm/glm.hpp REQUIRED)
find_path(TESSERA_TINYOBJ_HEADERS tiny_obj_loader.h REQUIRED)
string(JOIN "|" header_dirs ${TESSERA_JSON_HEADERS} ${TESSERA_GLM_HEADERS} ${TESSERA_TINYOBJ_HEADERS})

set(TESSERA_ARM_LIBRARY ${PROJECT_BINARY_DIR}/arm922t/libtessera_arm922t.a)
include(ExternalProject)
ExternalProject_Add(tessera_arm922t
  SOURCE_DIR ${PROJECT_SOURCE_DIR}
  BINARY_DIR ${PROJECT_BINARY_DIR}/arm922t/build
  LIST_SEPARATOR "|"
  CMAKE_ARGS -DCMAKE_TOOLCHAIN_FILE=${PROJECT_SOURCE_DIR}/cmake/arm922t-toolchain.cmake
             -DTESSERA_TARGET_ISS=ON
             -DCMAKE_BUILD_TYPE=RelWithDebInfo
             -DTESSERA_WERROR=${TESSERA_WERROR}
             -DTESSERA_AP_ASM=$<TARGET_FILE:ap_asm>
             -DTESSERA_LINKER_SCRIPT=${TESSERA_LINKER_SCRIPT}
             -DTESSERA_HEADER_DIRS=${header_dirs}
             -DTESSERA_ELF_DIR=${PROJECT_BINARY_DIR}/bin/arm922t
             -DTESSERA_ARM_LIBRARY=${TESSERA_ARM_LIBRARY}
  BUILD_ALWAYS ON
  BUILD_BYPRODUCTS ${TESSERA_ARM_LIBRARY}
  INSTALL_COMMAND ""
  DEPENDS ap_asm tessera_linker_script)
# soc_sim runs what it builds.
set(TESSERA_BUILTIN_ISS_IMAGE ${PROJECT_BINARY_DIR}/bin/arm922t/tessera_apps.elf)
set(TESSERA_CLUSTER_ISS_IMAGE ${PROJECT_BINARY_DIR}/bin/arm922t/tessera_cluster_node.elf)
