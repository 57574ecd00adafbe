# recip_table: CSV of the reciprocal unit's result and relative error for
# every operand (scripts/plot_reciprocal_error.py plots it). Included from
# testbench/CMakeLists.txt.
add_executable(recip_table ${CMAKE_CURRENT_LIST_DIR}/recip_table.cpp)
target_link_libraries(recip_table PRIVATE tessera_raster_datapath CLI11::CLI11 tessera_warnings)
