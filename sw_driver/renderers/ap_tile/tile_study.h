// The host's view of the study's program (ap_tile_study.s, README.md "The
// study's program"): where its variables are in a CU's CMEM, read from the
// program, and a pass's record as the program lays it out. Plain C++.
#pragma once

#include <cstdint>

#include "array/program.h"
#include "renderers/ap_tile/tile_setup.h"

namespace tessera::ap_tile {

struct StudyLayout {
  unsigned tile_width = 0, tile_height = 0;
  // Planes of tile_width * tile_height bytes; element (x, y) at
  // plane + tile_height * x + y, y the row from the top.
  uint16_t rg_hi = 0, rg_lo = 0, b = 0, zb_hi = 0, zb_lo = 0, we = 0;
  uint16_t s_hi = 0, s_lo = 0, t_hi = 0, t_lo = 0, tid = 0;
  // The record, written before every pass (16-bit values big-endian).
  uint16_t line_a = 0, line_b = 0, line_c = 0, z_start = 0, z_dx = 0, z_dy = 0;
  uint16_t c_start = 0, c_dx = 0, c_dy = 0, st_start = 0, st_dx = 0, st_dy = 0, tex = 0;
  uint16_t record_first = 0, record_bytes = 0;
  // The constants the host writes once, and the clear values.
  uint16_t xpos = 0, ypos = 0, one = 0, ff = 0, xcounter = 0, ycounter = 0;
  uint16_t clear_rg = 0, clear_b = 0, clear_z = 0;
  // The program's own variables.
  uint16_t product = 0, px = 0, py = 0, erow = 0, ev = 0, zrow = 0, zv = 0, flag = 0;
  uint16_t crow = 0, cv = 0, rgw = 0, bw = 0, strow = 0, stv = 0;
  // Bytes of CMEM the program declares: one past its last variable.
  unsigned cmem_bytes = 0;

  unsigned pixel(uint16_t plane, unsigned x, unsigned y) const { return plane + tile_height * x + y; }

  // Throws std::invalid_argument naming a variable the program lacks or
  // sizes differently, or a record that is not contiguous.
  static StudyLayout of(const ap::Program& program);
};

// Bytes of CMEM `program` declares: one past the end of its last variable.
unsigned cmem_extent(const ap::Program& program);

// Writes `record` as the program lays it out: layout.record_bytes bytes,
// the first at CMEM address layout.record_first. A record with live false
// is written as line 0 = 0 x + 0 y - 1, which no pixel is inside, and
// zeros (the study's program has no live flag: the lines decide).
void encode_study_record(const StudyRecord& record, const StudyLayout& layout, uint8_t* bytes);

}  // namespace tessera::ap_tile
