# Every external dependency is found here, once, and exposed as a target.
find_package(PkgConfig REQUIRED)

# SystemC ships only pkg-config files on Debian.
pkg_check_modules(SYSTEMC REQUIRED IMPORTED_TARGET systemc)
pkg_check_modules(TLM REQUIRED IMPORTED_TARGET tlm)
add_library(tessera_systemc INTERFACE)
target_link_libraries(tessera_systemc INTERFACE PkgConfig::SYSTEMC PkgConfig::TLM)
# Both SystemC and TLM-2.0 put their headers in /usr/include; the TLM utilities
# live under tlm_utils/, reached as <tlm_utils/...>.

# OpenImageIO's CMake config needs packages we do not otherwise use;
# its pkg-config file does not.
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
# libpng: soc_sim writes its PNG frames through it alone (tools/frame_writer/png_writer.h).
pkg_check_modules(PNG REQUIRED IMPORTED_TARGET libpng)

# Unicorn (QEMU's CPU emulation as a library): the reference the ISS runs
# in lock-step with in its tests.
pkg_check_modules(UNICORN REQUIRED IMPORTED_TARGET unicorn)

find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(GTest REQUIRED)
find_package(Threads REQUIRED)
find_package(glm REQUIRED)
find_package(verilator REQUIRED HINTS $ENV{VERILATOR_ROOT} /usr/share/verilator)
