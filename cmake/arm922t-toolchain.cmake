# CMake toolchain file for programs that run on tessera's ISS: the ARM922T
# (ARMv4T, ARM state, no FPU: soft float) with Debian's gcc-arm-none-eabi and
# newlib. Used by the build of the driver and the built-in applications
# (sw_driver/runtime/README.md) and, installed with the SDK, by an
# application of one's own, which find_package(tessera) then builds as an
# ARM executable (cmake/tesseraConfig.cmake.in):
#   cmake -S app -B build -DCMAKE_TOOLCHAIN_FILE=<prefix>/lib/cmake/tessera/arm922t-toolchain.cmake
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
# A bare-metal compiler cannot link a test program without start-up code.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(TESSERA_ARM922T_FLAGS "-mcpu=arm922t -marm -mfloat-abi=soft -ffunction-sections -fdata-sections")
set(CMAKE_C_FLAGS_INIT "${TESSERA_ARM922T_FLAGS}")
# -Wno-psabi: GCC's notes that an ABI detail changed in GCC 7.1, which
# concerns no code mixed with older compilers here.
set(CMAKE_CXX_FLAGS_INIT "${TESSERA_ARM922T_FLAGS} -Wno-psabi")
set(CMAKE_ASM_FLAGS_INIT "-mcpu=arm922t -marm")
# The runtime's crt0.S is the start-up code; unreferenced sections go.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-nostartfiles -Wl,--gc-sections")

# Headers and libraries come from the ARM toolchain's own folders only.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)

# Installed, this file sits beside the package it belongs to: the SDK whose
# ARM archive matches its soc_sim. find_package(tessera) takes that one
# without a CMAKE_PREFIX_PATH (a tessera_DIR given by the user wins).
if(EXISTS ${CMAKE_CURRENT_LIST_DIR}/tesseraConfig.cmake)
  set(tessera_DIR ${CMAKE_CURRENT_LIST_DIR} CACHE PATH "The tessera package of this toolchain file")
endif()
