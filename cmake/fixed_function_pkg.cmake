# Writes the SystemVerilog package fixed_function_pkg, the RTL's view of
# contract/common/fixed_function.def: per table a localparam with the width of its
# field and an enum type whose values are the table's hardware codes, so that
# no Verilog unit holds a number of its own. Run at build time
# (tessera_add_sv_package in cmake/RtlUnits.cmake, target
# rtl_fixed_function_pkg) and by scripts/synth_report.sh:
#
#   cmake -DROOT=<source tree> -DOUT=fixed_function_pkg.sv -P cmake/fixed_function_pkg.cmake
#
# A table opens with TESSERA_FIXED_FUNCTION(Type, sv_name, bits, "unknown")
# and its entries are the lines of the macro TESSERA_<SV_NAME>(name, code,
# gl_enum, ..., "description"). The enum is <sv_name>_e and a value is
# <Type><Name> (and_reverse -> LogicOpAndReverse). Any other line that starts
# with TESSERA_ stops the script, so a malformed entry cannot be skipped.
if(NOT ROOT OR NOT OUT)
  message(FATAL_ERROR "usage: cmake -DROOT=<source tree> -DOUT=<fixed_function_pkg.sv> -P fixed_function_pkg.cmake")
endif()
set(DEF "${ROOT}/contract/common/fixed_function.def")

# and_reverse -> AndReverse; a trailing underscore (and_) is dropped.
function(upper_camel name out)
  string(REGEX REPLACE "_$" "" name "${name}")
  string(REPLACE "_" ";" parts "${name}")
  set(result "")
  foreach(part IN LISTS parts)
    string(SUBSTRING "${part}" 0 1 first)
    string(SUBSTRING "${part}" 1 -1 rest)
    string(TOUPPER "${first}" first)
    string(APPEND result "${first}${rest}")
  endforeach()
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

file(STRINGS "${DEF}" lines)
set(tables "")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^TESSERA_")
    continue()
  endif()
  if(line MATCHES "^TESSERA_FIXED_FUNCTION\\(([A-Za-z]+), ([a-z_]+), ([0-9]+), \"([^\"]*)\"\\)$")
    set(table "${CMAKE_MATCH_2}")
    list(APPEND tables "${table}")
    set(type_${table} "${CMAKE_MATCH_1}")
    set(bits_${table} "${CMAKE_MATCH_3}")
    set(unknown_${table} "${CMAKE_MATCH_4}")
    set(entries_${table} "")
    string(TOUPPER "${table}" macro_${table})
  elseif(line MATCHES "^TESSERA_([A-Z_]+)\\(([a-z][a-z0-9_]*), ([0-9]+), (0x[0-9A-Fa-f]+), ([a-z, ]*)\"([^\"]*)\"\\)$")
    set(macro "${CMAKE_MATCH_1}")
    if(NOT table OR NOT macro STREQUAL macro_${table})
      message(FATAL_ERROR "${DEF}: TESSERA_${macro} outside its table: ${line}")
    endif()
    upper_camel("${CMAKE_MATCH_2}" name)
    list(APPEND entries_${table} "${name}")
    set(code_${table}_${name} "${CMAKE_MATCH_3}")
    set(gl_${table}_${name} "${CMAKE_MATCH_4}")
    set(description_${table}_${name} "${CMAKE_MATCH_6}")
  else()
    message(FATAL_ERROR "${DEF}: not an entry the package generator can read: ${line}")
  endif()
endforeach()
if(NOT tables)
  message(FATAL_ERROR "${DEF}: no TESSERA_FIXED_FUNCTION table")
endif()

set(sv "// Generated from contract/common/fixed_function.def by cmake/fixed_function_pkg.cmake:\n")
string(APPEND sv "// do not edit. The hardware codes of the rasterizer's fixed-function state,\n")
string(APPEND sv "// the same numbers the C++ model, the driver and the state blocks use.\n")
string(APPEND sv "package fixed_function_pkg;\n")
foreach(table IN LISTS tables)
  set(type "${type_${table}}")
  set(bits "${bits_${table}}")
  list(LENGTH entries_${table} count)
  if(count EQUAL 0)
    message(FATAL_ERROR "${DEF}: table ${type} has no entries")
  endif()
  string(APPEND sv "\n  // ${type}: ${count} codes in a ${bits}-bit field, ${unknown_${table}}.\n")
  string(APPEND sv "  localparam int unsigned ${type}Bits = ${bits};\n")
  string(APPEND sv "  typedef enum logic [${type}Bits-1:0] {\n")
  set(index 0)
  foreach(name IN LISTS entries_${table})
    math(EXPR index "${index} + 1")
    set(comma ",")
    if(index EQUAL count)
      set(comma " ")
    endif()
    string(APPEND sv "    ${type}${name} = ${bits}'d${code_${table}_${name}}${comma}  "
                     "// GL ${gl_${table}_${name}}: ${description_${table}_${name}}\n")
  endforeach()
  string(APPEND sv "  } ${table}_e;\n")
endforeach()
string(APPEND sv "\nendpackage\n")
file(WRITE "${OUT}" "${sv}")
