# The Verilog reference units (rtl_models/README.md): their table, the
# SystemVerilog packages generated for them, and their Verilated libraries.

# tessera_rtl_units(PREFIX)
# Reads rtl_models/units.def, the one table of the units, into PREFIX_NAMES
# (in the table's order) and, per unit, PREFIX_<name>_FOLDER, _TWIN,
# _TWIN_LIBRARY, _PACKAGES (a list, empty for none), _PAPER_CELLS and
# _DESCRIPTION. Changing the table reconfigures the build.
function(tessera_rtl_units prefix)
  set(table ${PROJECT_SOURCE_DIR}/rtl_models/units.def)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${table})
  file(STRINGS ${table} lines REGEX "^TESSERA_RTL_UNIT\\(")
  set(names)
  foreach(line IN LISTS lines)
    if(NOT line MATCHES
       "^TESSERA_RTL_UNIT\\(([a-z][a-z0-9_]*), ([a-z]+), \"([^\"]+)\", ([a-z_]+), ([a-z_ ]+), ([0-9]+), \"([^\"]*)\"\\)$")
      message(FATAL_ERROR "${table}: cannot read '${line}': expected TESSERA_RTL_UNIT(name, folder, \"twin\", "
                          "twin_library, packages, paper_cells, \"description\") on one line")
    endif()
    set(name ${CMAKE_MATCH_1})
    list(APPEND names ${name})
    set(${prefix}_${name}_FOLDER ${CMAKE_MATCH_2} PARENT_SCOPE)
    set(${prefix}_${name}_TWIN ${CMAKE_MATCH_3} PARENT_SCOPE)
    set(${prefix}_${name}_TWIN_LIBRARY ${CMAKE_MATCH_4} PARENT_SCOPE)
    set(packages ${CMAKE_MATCH_5})
    set(paper ${CMAKE_MATCH_6})
    set(description "${CMAKE_MATCH_7}")
    separate_arguments(packages)
    list(REMOVE_ITEM packages none)
    set(${prefix}_${name}_PACKAGES ${packages} PARENT_SCOPE)
    set(${prefix}_${name}_PAPER_CELLS ${paper} PARENT_SCOPE)
    set(${prefix}_${name}_DESCRIPTION "${description}" PARENT_SCOPE)
  endforeach()
  if(NOT names)
    message(FATAL_ERROR "${table} lists no unit")
  endif()
  set(${prefix}_NAMES ${names} PARENT_SCOPE)
endfunction()

# tessera_add_sv_package(NAME name_pkg INPUTS file ...)
# A SystemVerilog package generated from the tables the C++ model uses, so
# that no Verilog unit holds a number of its own: cmake/<name_pkg>.cmake
# writes it (run as `cmake -DROOT=<source tree> -DOUT=<file> -P ...`, which
# scripts/synth_report.sh does too) to build/<preset>/rtl_models/<name_pkg>.sv.
# INPUTS are the files it reads, relative to the source tree. The build
# rewrites it when an input or the generator changes (target
# rtl_<name_pkg>); so does configuring, because verilate() runs Verilator
# while configuring to learn the files it makes, and a unit that uses a name
# new in a table would not configure against a stale package.
function(tessera_add_sv_package)
  cmake_parse_arguments(P "" "NAME" "INPUTS" ${ARGN})
  set(generator ${PROJECT_SOURCE_DIR}/cmake/${P_NAME}.cmake)
  set(out ${PROJECT_BINARY_DIR}/rtl_models/${P_NAME}.sv)
  list(TRANSFORM P_INPUTS PREPEND ${PROJECT_SOURCE_DIR}/)
  set(command ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR} -DOUT=${out} -P ${generator})
  set(stale FALSE)
  foreach(input IN LISTS P_INPUTS generator)
    if(NOT EXISTS ${out} OR ${input} IS_NEWER_THAN ${out})
      set(stale TRUE)
    endif()
  endforeach()
  if(stale)
    execute_process(COMMAND ${command} RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "cannot generate ${out} with ${generator}")
    endif()
  endif()
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${command}
    DEPENDS ${P_INPUTS} ${generator}
    COMMENT "Generating ${P_NAME}.sv with cmake/${P_NAME}.cmake"
    VERBATIM)
  add_custom_target(rtl_${P_NAME} DEPENDS ${out})
endfunction()

# Where tessera_add_sv_package writes fixed_function_pkg, for the test that
# reads it (tests/common/test_fixed_function.cpp).
set(TESSERA_FIXED_FUNCTION_PKG ${PROJECT_BINARY_DIR}/rtl_models/fixed_function_pkg.sv)

# tessera_add_rtl_unit(NAME name FOLDER folder LIBS twin_library [PACKAGES name_pkg ...])
# Each Verilog reference unit becomes its own static library rtl_<name>,
# Verilated from rtl_models/<folder>/<name>.sv (top module <name>) after the
# generated PACKAGES (tessera_add_sv_package), and reached only through the
# thin C++ adapter rtl_models/<folder>/<name>_adapter.cpp, on the library's
# public include path.
function(tessera_add_rtl_unit)
  cmake_parse_arguments(U "" "NAME;FOLDER" "LIBS;PACKAGES" ${ARGN})
  set(dir ${PROJECT_SOURCE_DIR}/rtl_models/${U_FOLDER})
  set(target rtl_${U_NAME})
  add_library(${target} STATIC ${dir}/${U_NAME}_adapter.cpp)
  set(package_files)
  foreach(package IN LISTS U_PACKAGES)
    list(APPEND package_files ${PROJECT_BINARY_DIR}/rtl_models/${package}.sv)
    add_dependencies(${target} rtl_${package})
  endforeach()
  verilate(${target}
    PREFIX V${U_NAME}
    TOP_MODULE ${U_NAME}
    SOURCES ${package_files} ${dir}/${U_NAME}.sv ${PROJECT_SOURCE_DIR}/rtl_models/lint_waivers.vlt
    VERILATOR_ARGS --cc --no-timing -Wall -O3)
  target_include_directories(${target} PUBLIC ${dir})
  target_link_libraries(${target} PUBLIC ${U_LIBS})
  # Verilator's generated code is not ours to warn about.
  target_compile_options(${target} PRIVATE -w)
endfunction()
