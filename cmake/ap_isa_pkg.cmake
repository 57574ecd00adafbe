# Writes the SystemVerilog package ap_isa_pkg, the RTL's view of the array
# processor's instruction set: the opcodes of contract/array/isa/ap_isa.def, the
# conditions of ap_cond.def and the neighbour directions of the Direction enum
# in ap_isa.h, each as an enum type whose values are the codes the C++
# decoder uses, so that no Verilog unit holds an encoding of its own. Run at
# build time (tessera_add_sv_package in cmake/RtlUnits.cmake, target
# rtl_ap_isa_pkg) and by scripts/synth_report.sh:
#
#   cmake -DROOT=<source tree> -DOUT=ap_isa_pkg.sv -P cmake/ap_isa_pkg.cmake
#
# A value is Op<Mnemonic> (OpAdd, OpMulm, OpAdd16), Cond<Name> (CondHi) or
# Direction<Name> (DirectionLeft). A line that starts with TESSERA_AP_OP or
# TESSERA_AP_COND and does not parse stops the script, so a malformed entry
# cannot be skipped.
if(NOT ROOT OR NOT OUT)
  message(FATAL_ERROR "usage: cmake -DROOT=<source tree> -DOUT=<ap_isa_pkg.sv> -P ap_isa_pkg.cmake")
endif()
set(ISA_DIR "${ROOT}/contract/array/isa")

# The instruction word's field widths (ap_isa.h): a 6-bit opcode, a 3-bit
# condition, a 2-bit direction.
set(opcode_bits 6)
set(cond_bits 3)
set(direction_bits 2)

function(upper_camel name out)
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

# The lines of a file as a list. The descriptions hold semicolons, which
# CMake lists would split on: they travel as a placeholder, put back when the
# package is written.
function(read_lines file out)
  file(READ "${file}" content)
  string(REPLACE ";" "@SEMICOLON@" content "${content}")
  string(REPLACE "\n" ";" content "${content}")
  set(${out} "${content}" PARENT_SCOPE)
endfunction()

# Appends one enum typedef to `sv`: names, codes and comments are lists.
function(append_enum sv_var type bits names codes comments)
  list(LENGTH names count)
  set(sv "${${sv_var}}")
  string(APPEND sv "  localparam int unsigned ${type}Bits = ${bits};\n")
  string(APPEND sv "  typedef enum logic [${type}Bits-1:0] {\n")
  math(EXPR last "${count} - 1")
  foreach(index RANGE ${last})
    list(GET names ${index} name)
    list(GET codes ${index} code)
    list(GET comments ${index} comment)
    set(comma ",")
    if(index EQUAL last)
      set(comma " ")
    endif()
    string(APPEND sv "    ${type}${name} = ${bits}'d${code}${comma}  // ${comment}\n")
  endforeach()
  string(TOLOWER "${type}" lower)
  string(APPEND sv "  } ${lower}_e;\n")
  set(${sv_var} "${sv}" PARENT_SCOPE)
endfunction()

# Opcodes. Hex codes become decimal, and each must fit the opcode field.
read_lines("${ISA_DIR}/ap_isa.def" lines)
set(op_names "")
set(op_codes "")
set(op_comments "")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^TESSERA_AP_OP\\(")
    continue()
  endif()
  if(NOT line MATCHES "^TESSERA_AP_OP\\(([a-z][a-z0-9]*), +0x([0-9a-fA-F]+), +([a-z]+), +([a-z]+), +([0-9]+), +\"([^\"]*)\", +([a-z_]+), +\"(.*)\"\\)$")
    message(FATAL_ERROR "${ISA_DIR}/ap_isa.def: not an entry the package generator can read: ${line}")
  endif()
  set(mnemonic "${CMAKE_MATCH_1}")
  math(EXPR code "0x${CMAKE_MATCH_2}")
  set(comment "${mnemonic} (${CMAKE_MATCH_3}, ${CMAKE_MATCH_4}): ${CMAKE_MATCH_8}")
  if(NOT CMAKE_MATCH_7 STREQUAL "none")
    string(APPEND comment " [array.features.${CMAKE_MATCH_7}]")
  endif()
  if(code GREATER_EQUAL 64)
    message(FATAL_ERROR "${ISA_DIR}/ap_isa.def: opcode ${mnemonic} = ${code} does not fit ${opcode_bits} bits")
  endif()
  upper_camel("${mnemonic}" name)
  list(APPEND op_names "${name}")
  list(APPEND op_codes "${code}")
  list(APPEND op_comments "${comment}")
endforeach()
if(NOT op_names)
  message(FATAL_ERROR "${ISA_DIR}/ap_isa.def: no TESSERA_AP_OP entry")
endif()

read_lines("${ISA_DIR}/ap_cond.def" lines)
set(cond_names "")
set(cond_codes "")
set(cond_comments "")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^TESSERA_AP_COND\\(")
    continue()
  endif()
  if(NOT line MATCHES "^TESSERA_AP_COND\\(([a-z]+), +([0-9]+), +\"(.*)\"\\)$")
    message(FATAL_ERROR "${ISA_DIR}/ap_cond.def: not an entry the package generator can read: ${line}")
  endif()
  if(CMAKE_MATCH_2 GREATER_EQUAL 8)
    message(FATAL_ERROR "${ISA_DIR}/ap_cond.def: condition ${CMAKE_MATCH_1} does not fit ${cond_bits} bits")
  endif()
  upper_camel("${CMAKE_MATCH_1}" name)
  list(APPEND cond_names "${name}")
  list(APPEND cond_codes "${CMAKE_MATCH_2}")
  list(APPEND cond_comments "${CMAKE_MATCH_3}")
endforeach()
if(NOT cond_names)
  message(FATAL_ERROR "${ISA_DIR}/ap_cond.def: no TESSERA_AP_COND entry")
endif()

# The directions have no .def of their own: they are the one-line enum
# `enum class Direction : uint8_t { left = 0, ... };` of ap_isa.h.
file(STRINGS "${ISA_DIR}/ap_isa.h" direction_line REGEX "^enum class Direction : uint8_t {.*};$")
list(LENGTH direction_line direction_lines)
if(NOT direction_lines EQUAL 1)
  message(FATAL_ERROR "${ISA_DIR}/ap_isa.h: expected one line 'enum class Direction : uint8_t { name = code, ... };'")
endif()
string(REGEX MATCH "[{][^}]*[}]" body "${direction_line}")
string(REGEX REPLACE "^[{] *" "" body "${body}")
string(REGEX REPLACE " *[}]$" "" body "${body}")
string(REPLACE ", " ";" entries "${body}")
set(direction_names "")
set(direction_codes "")
set(direction_comments "")
foreach(entry IN LISTS entries)
  if(NOT entry MATCHES "^([a-z]+) = ([0-9]+)$")
    message(FATAL_ERROR "${ISA_DIR}/ap_isa.h: cannot read the direction '${entry}'")
  endif()
  upper_camel("${CMAKE_MATCH_1}" name)
  list(APPEND direction_names "${name}")
  list(APPEND direction_codes "${CMAKE_MATCH_2}")
  list(APPEND direction_comments "the neighbour ${CMAKE_MATCH_1} (row 0 at the top, column 0 at the left)")
endforeach()

set(sv "// Generated from contract/array/isa/ap_isa.def, ap_cond.def and ap_isa.h by\n")
string(APPEND sv "// cmake/ap_isa_pkg.cmake: do not edit. The array processor's opcodes,\n")
string(APPEND sv "// conditions and neighbour directions, the same codes as the C++ decoder's.\n")
string(APPEND sv "package ap_isa_pkg;\n\n")
append_enum(sv "Op" "${opcode_bits}" "${op_names}" "${op_codes}" "${op_comments}")
string(APPEND sv "\n")
append_enum(sv "Cond" "${cond_bits}" "${cond_names}" "${cond_codes}" "${cond_comments}")
string(APPEND sv "\n")
append_enum(sv "Direction" "${direction_bits}" "${direction_names}" "${direction_codes}" "${direction_comments}")
string(APPEND sv "\nendpackage\n")
string(REPLACE "@SEMICOLON@" ";" sv "${sv}")
file(WRITE "${OUT}" "${sv}")
