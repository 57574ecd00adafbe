# Project-wide helpers: warnings, sanitizers, tests and Verilog units.

add_library(tessera_warnings INTERFACE)
# -Wshadow=local is GCC's; clang (the fuzz preset) has no such option.
target_compile_options(tessera_warnings INTERFACE -Wall -Wextra -Wpedantic $<$<CXX_COMPILER_ID:GNU>:-Wshadow=local>
                       $<$<BOOL:${TESSERA_WERROR}>:-Werror>)

set(TESSERA_SANITIZE_TIMEOUT_SCALE 5 CACHE STRING "Factor on every test's timeout in the sanitize build")
if(NOT TESSERA_SANITIZE_TIMEOUT_SCALE MATCHES "^[1-9][0-9]*$")
  message(FATAL_ERROR "TESSERA_SANITIZE_TIMEOUT_SCALE must be a positive integer, not '${TESSERA_SANITIZE_TIMEOUT_SCALE}'")
endif()

if(TESSERA_SANITIZE)
  # SystemC switches coroutine stacks; ASan's use-after-return check mistakes that for
  # use of freed stack memory, so it is compiled out.
  # GCC's "undefined" group leaves out its two float checks. float-cast-overflow
  # (a float converted to an integer type that cannot hold it, NaN included) is
  # undefined behaviour and is enabled. float-divide-by-zero is not: the GL
  # front end divides by values a legal application controls (a viewport of
  # width 0, a point at w = 0, zero attenuation) and relies on IEEE division
  # giving an infinity that its finiteness checks reject (tests/README.md).
  add_compile_options(-fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined,float-cast-overflow --param=asan-use-after-return=0)
  add_link_options(-fsanitize=address,undefined,float-cast-overflow)
endif()

# tessera_block_library(name sources...): a block's library (tlm/).
function(tessera_block_library name)
  add_library(${name} STATIC ${ARGN})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/tlm)
  target_link_libraries(${name} PUBLIC tessera_contract PRIVATE tessera_warnings)
endfunction()

# tessera_add_test(NAME name SOURCES ... LIBS ... LABELS ... [TIMEOUT s] [NO_GTEST_MAIN])
# One executable per module (the SystemC kernel cannot be reset, so each
# executable has one elaboration). GoogleTest provides main() unless the test
# brings its own sc_main.
function(tessera_add_test)
  cmake_parse_arguments(T "NO_GTEST_MAIN" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS;ARGS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest tessera_warnings)
  if(NOT T_NO_GTEST_MAIN)
    target_link_libraries(${T_NAME} PRIVATE GTest::gtest_main)
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 120)
  endif()
  if(TESSERA_SANITIZE)
    # A timeout is a hang guard set for the default (optimised) build. The
    # sanitize build is a Debug build with ASan and UBSan, many times slower
    # (test_cu_array: 4 s against 64 s in a fresh clone), so every guard is
    # scaled there rather than raised test by test (tests/README.md).
    math(EXPR T_TIMEOUT "${T_TIMEOUT} * ${TESSERA_SANITIZE_TIMEOUT_SCALE}")
    # LeakSanitizer's tracer crashes now and then at exit on a loaded
    # machine; the wrapper runs the program again only then (tests/README.md).
    add_test(NAME ${T_NAME} COMMAND ${PROJECT_SOURCE_DIR}/testbench/process/leak_check_run.sh $<TARGET_FILE:${T_NAME}>
                                    ${T_ARGS})
  else()
    add_test(NAME ${T_NAME} COMMAND ${T_NAME} ${T_ARGS})
  endif()
  set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT}
                       ENVIRONMENT "SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1;TESSERA_SOURCE_DIR=${PROJECT_SOURCE_DIR};TESSERA_BINARY_DIR=${PROJECT_BINARY_DIR}")
endfunction()

# The Verilog reference units: their table, generated packages and libraries.
include(RtlUnits)

# tessera_backends(IDS_VAR NAMES_VAR)
# The renderer back ends, in the order of sw_driver/renderers/backends.def,
# the one table of them: their ids (folder, library tessera_backend_<id>,
# test names) and their names (driver.backend, --backend). Changing the
# table reconfigures the build.
function(tessera_backends ids_var names_var)
  set(table ${PROJECT_SOURCE_DIR}/sw_driver/renderers/backends.def)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${table})
  file(STRINGS ${table} lines REGEX "^TESSERA_BACKEND\\(")
  set(ids)
  set(names)
  foreach(line IN LISTS lines)
    if(NOT line MATCHES "^TESSERA_BACKEND\\(([a-z][a-z0-9_]*), \"([a-z][a-z0-9-]*)\", ")
      message(FATAL_ERROR "${table}: cannot read '${line}': expected TESSERA_BACKEND(id, \"name\", ...) on one line, "
                          "id in [a-z0-9_], name in [a-z0-9-]")
    endif()
    list(APPEND ids ${CMAKE_MATCH_1})
    list(APPEND names ${CMAKE_MATCH_2})
  endforeach()
  if(NOT ids)
    message(FATAL_ERROR "${table} lists no back end")
  endif()
  set(${ids_var} ${ids} PARENT_SCOPE)
  set(${names_var} ${names} PARENT_SCOPE)
endfunction()

# tessera_add_array_programs(TARGET lib SOURCES prog.s ... [ASM_OPTIONS --registers 16 ...]
#                            [DEFINES NAME=VALUE ...] [NAME accessor])
# Array programs assembled at build time into the static library `lib`: for
# each prog.s, `ap_asm --emit-cpp prog` writes the definition of
# tessera::ap::programs::prog() and its declaration in the header
# ap_programs/prog.h, on lib's public include path. An assembly error fails
# the build with the source's file:line. ASM_OPTIONS are ap_asm's limits of
# the array the programs must fit (the defaults are array.* defaults);
# DEFINES the constants defined before each source's first line (ap_asm -D,
# for .if); NAME, with one source, the accessor's name instead of the
# source's, so that a source assembled with other DEFINES is another program.
function(tessera_add_array_programs)
  cmake_parse_arguments(P "" "TARGET;NAME" "SOURCES;ASM_OPTIONS;DEFINES" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/${P_TARGET})
  set(generated)
  list(LENGTH P_SOURCES source_count)
  if(P_NAME AND NOT source_count EQUAL 1)
    message(FATAL_ERROR "tessera_add_array_programs(${P_TARGET}): NAME ${P_NAME} needs exactly one source")
  endif()
  set(defines)
  foreach(define IN LISTS P_DEFINES)
    list(APPEND defines -D ${define})
  endforeach()
  foreach(source IN LISTS P_SOURCES)
    get_filename_component(path ${source} ABSOLUTE)
    get_filename_component(name ${source} NAME_WE)
    if(P_NAME)
      set(name ${P_NAME})
    endif()
    # The name the messages and Program::source_name give: relative to the
    # project, so that the image does not depend on where the tree is.
    file(RELATIVE_PATH shown ${PROJECT_SOURCE_DIR} ${path})
    if(shown MATCHES "^\\.\\./")
      set(shown ${path})
    endif()
    set(cpp ${out_dir}/${name}.cpp)
    set(header ${out_dir}/include/ap_programs/${name}.h)
    add_custom_command(OUTPUT ${cpp} ${header}
                       COMMAND ap_asm ${P_ASM_OPTIONS} ${defines} --emit-cpp ${name} ${shown} -o ${cpp} --header ${header}
                       DEPENDS ${path} ap_asm
                       WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                       COMMENT "Assembling the array program ${shown}"
                       VERBATIM)
    list(APPEND generated ${cpp} ${header})
  endforeach()
  file(MAKE_DIRECTORY ${out_dir}/include/ap_programs)
  add_library(${P_TARGET} STATIC ${generated})
  # The generated code includes the contract's program image only, so the
  # program libraries put no part of tlm/ on the include path of the driver
  # that links them.
  target_include_directories(${P_TARGET} PUBLIC ${out_dir}/include)
  target_link_libraries(${P_TARGET} PUBLIC tessera_contract PRIVATE tessera_warnings)
endfunction()
