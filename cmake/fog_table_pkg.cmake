# Writes the SystemVerilog package fog_table_pkg, the RTL's view of
# contract/common/fog_exp2_table.def (the fog unit's 2^-x table, the one copy): a
# function fog_exp2_entry(index) whose case items are the table's entries, so
# that rtl_models/raster/fog_unit.sv holds no number of its own. Run at build
# time (tessera_add_sv_package in cmake/RtlUnits.cmake, target
# rtl_fog_table_pkg) and by scripts/synth_report.sh:
#
#   cmake -DROOT=<source tree> -DOUT=fog_table_pkg.sv -P cmake/fog_table_pkg.cmake
#
# Entries are lines TESSERA_FOG_EXP2(index, value), index 0..255 in order,
# value 0..65535; any other line that starts with TESSERA_ stops the script.
if(NOT ROOT OR NOT OUT)
  message(FATAL_ERROR "usage: cmake -DROOT=<source tree> -DOUT=<fog_table_pkg.sv> -P fog_table_pkg.cmake")
endif()
set(DEF "${ROOT}/contract/common/fog_exp2_table.def")

file(STRINGS "${DEF}" lines)
set(items "")
set(expected 0)
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^TESSERA_")
    continue()
  endif()
  if(NOT line MATCHES "^TESSERA_FOG_EXP2\\(([0-9]+), ([0-9]+)\\)$")
    message(FATAL_ERROR "${DEF}: not an entry the package generator can read: ${line}")
  endif()
  if(NOT CMAKE_MATCH_1 EQUAL expected)
    message(FATAL_ERROR "${DEF}: entry ${CMAKE_MATCH_1} where entry ${expected} was due")
  endif()
  if(CMAKE_MATCH_2 GREATER 65535)
    message(FATAL_ERROR "${DEF}: entry ${CMAKE_MATCH_1} (${CMAKE_MATCH_2}) does not fit 16 bits")
  endif()
  string(APPEND items "      8'd${CMAKE_MATCH_1}: fog_exp2_entry = 16'd${CMAKE_MATCH_2};\n")
  math(EXPR expected "${expected} + 1")
endforeach()
if(NOT expected EQUAL 256)
  message(FATAL_ERROR "${DEF}: ${expected} entries, 256 expected")
endif()

set(sv "// Generated from contract/common/fog_exp2_table.def by cmake/fog_table_pkg.cmake:\n")
string(APPEND sv "// do not edit. The fog unit's table: entry i = round(2^16 * 2^-((i + 1/2) / 256)).\n")
string(APPEND sv "package fog_table_pkg;\n\n")
string(APPEND sv "  function automatic logic [15:0] fog_exp2_entry(input logic [7:0] index);\n")
string(APPEND sv "    unique case (index)\n${items}")
string(APPEND sv "      default: fog_exp2_entry = 16'd0;\n")
string(APPEND sv "    endcase\n  endfunction\n\nendpackage\n")
file(WRITE "${OUT}" "${sv}")
