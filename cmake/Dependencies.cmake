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

# GTKWave's FST writer and reader (fstapi), the copy Verilator bundles: soc_sim
# --fst. Debian's libfst-dev is OpenFst, an unrelated library of that name,
# and Debian packages GTKWave's fstapi nowhere else. Its own C, built as it
# is, without our warnings.
find_package(ZLIB REQUIRED)
set(TESSERA_FSTAPI_DIR ${VERILATOR_ROOT}/include/gtkwave)
if(NOT EXISTS ${TESSERA_FSTAPI_DIR}/fstapi.c)
  message(FATAL_ERROR "GTKWave's fstapi is not in ${TESSERA_FSTAPI_DIR}: install verilator (scripts/setup.sh)")
endif()
add_library(tessera_fstapi STATIC ${TESSERA_FSTAPI_DIR}/fstapi.c ${TESSERA_FSTAPI_DIR}/fastlz.c
                                  ${TESSERA_FSTAPI_DIR}/lz4.c)
target_include_directories(tessera_fstapi SYSTEM PUBLIC ${TESSERA_FSTAPI_DIR})
target_compile_definitions(tessera_fstapi PRIVATE FST_CONFIG_INCLUDE="fst_config.h")
target_link_libraries(tessera_fstapi PRIVATE ZLIB::ZLIB Threads::Threads)
set_target_properties(tessera_fstapi PROPERTIES POSITION_INDEPENDENT_CODE ON)

# The Python that runs the package under python/ (tessera-sweep, and the run
# report soc_sim --report renders through it): the venv scripts/setup.sh
# makes (Debian's packages plus PyPI's), else the system's python3; soc_sim
# reports a missing package by name when it runs it.
if(EXISTS ${PROJECT_SOURCE_DIR}/build/venv/bin/python3)
  set(tessera_default_python ${PROJECT_SOURCE_DIR}/build/venv/bin/python3)
else()
  find_program(tessera_default_python python3)
endif()
set(TESSERA_PYTHON ${tessera_default_python} CACHE FILEPATH "Python with python/'s dependencies (scripts/setup.sh)")
