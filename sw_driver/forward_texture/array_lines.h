// The host's side of resample_lines.s, Eq. 6 on the array with one line per
// CU (README.md, "On the array"), in either of its programs (the factors
// computed, resample_lines; or looked up, resample_lines_lut): what the host
// writes into a CU's CMEM for one line and into every CU for the filter, the
// filter's lookup table, the program with the line's length and the
// filter's width written into its loops, and the pixels made of what a CU
// leaves behind. Plain C++: the device layer moves the blocks
// (DMA or CIU), the tests move them into the functional core.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "array/program.h"
#include "forward_texture/filter.h"
#include "forward_texture/matrix.h"
#include "forward_texture/resample_line.h"

namespace tessera::forward_texture {

// Where resample_lines.s keeps what the host writes and reads (its .var
// names), and its limits (its .const names).
struct ArrayLineLayout {
  // Per line.
  uint16_t num = 0, num_step = 0, den = 0, den_step = 0, tex_hi = 0, tex_lo = 0;
  // The same in every CU. q_hi, q_lo, r_j and two_f: the program computes
  // the factors; slot_hi: it looks them up (table_factors).
  uint16_t offset = 0, q_hi = 0, q_lo = 0, r_j = 0, two_f = 0, slot_hi = 0, zero = 0, ff = 0, c80 = 0, c40 = 0, cc0 = 0,
           none = 0, limit = 0, clamp = 0;
  // Results.
  uint16_t idx_hi = 0, idx_lo = 0, val_hi = 0, val_lo = 0, last_pixel = 0, fin_hi = 0, fin_lo = 0, err = 0;
  int max_texels = 0;  // the longest line
  int max_width = 0;   // the widest filter
  // The program looks the factors up in the shared table (its constant
  // TABLE_FACTORS): any filter, with array.features.lut.
  bool table_factors = false;

  // Throws std::invalid_argument naming a variable the program lacks or
  // whose size differs.
  static ArrayLineLayout of(const ap::Program& program);
};

// The same bytes for every CU: `bytes` at `address`, `address` + 1, ...
struct CmemBlock {
  uint16_t address = 0;
  std::vector<uint8_t> bytes;
};

// One CMEM address of every CU: `per_cu` holds one byte per CU, in CU
// order (what one reshuffling DMA descriptor or one CIU sweep moves).
struct CmemRow {
  uint16_t address = 0;
  std::vector<uint8_t> per_cu;
};

// Empty, or the message naming what the program cannot do: with the
// factors computed, a filter other than the box (the J2210 has no shared
// table, so the program computes the box's factors; the tent's need a
// table); with the factors looked up, a filter whose table (lut_entries)
// does not fit the array's `lut_table_entries` (array.lut.entries, 0 with
// array.features.lut off); a width beyond the program's window, a line
// longer than its CMEM holds.
std::string array_line_error(const ArrayLineLayout& layout, const FilterTable& table, int texel_count,
                             unsigned lut_table_entries = 0);

// The lookup table of the table program for `table`: entry 256 (F - 1 - j)
// + phase holds table.at(phase, j), so the index of slot j's factor is two
// bytes the CU has (F - 1 - j from slot_hi, the phase), and the table is
// the filter's primitive H at the PHASES F positions across its support.
std::vector<uint16_t> lut_entries(const FilterTable& table);

// The program's words with `texel_count` in its texel loop and width - 1 in
// its window loops (array_line_error must be empty).
std::vector<uint64_t> program_for_lines(const ap::Program& program, int texel_count, int width);

// What every CU gets for a filter of `width` (the program's own constants:
// layout.table_factors decides which).
std::vector<CmemBlock> filter_blocks(const ArrayLineLayout& layout, int width);

// A line as the program steps it: left to right. A line whose borders
// decrease (step_borders' last below its first) is given reversed: its
// mapping stepped from the other end, its texels in the other order.
struct ArrayLine {
  LineMapping mapping;  // stepped from the leftmost border
  bool reversed = false;
  LineView texels;                           // in the texture's order
  q16_16 first_border = 0, last_border = 0;  // step_borders' first and last
};

// The line's orientation and end borders, from two divisions on the host.
// False when an end does not divide (the array would flag it too:
// step_borders names the error).
bool orient_line(const LineMapping& mapping, LineView texels, ArrayLine& line);

// The rows that give CU k line k (lines.size() <= cus, all of the same
// length); the CUs past the last line get zeros.
std::vector<CmemRow> line_rows(const ArrayLineLayout& layout, const std::vector<ArrayLine>& lines, unsigned cus);

// The CMEM addresses to read back from every CU for lines of `texel_count`
// texels, in the order scatter_line expects their rows.
std::vector<uint16_t> result_addresses(const ArrayLineLayout& layout, int texel_count, int width);

// The pixels of the line in CU `lane` from the rows read at
// result_addresses: every pixel of `pixels` written, as resample_line
// writes them (0 where no texel reaches). False when the CU flagged an
// error (a border out of range or a texel wider than a pixel): step_borders
// names it.
bool scatter_line(int texel_count, int width, const std::vector<CmemRow>& results, unsigned lane, LineView pixels);

}  // namespace tessera::forward_texture
