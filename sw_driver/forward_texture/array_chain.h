// The host's side of resample_chain.s, Eq. 6 after van Sinten's own mapping
// (README.md, "On the array: the chain"): one line per CU row, each CU of a
// row a different texel border of a block of columns - 1, the window's sums
// passed down the row's chain, the row's column 0 the relay that carries
// the last column's window into the next round. What the host writes into
// the CUs and the lookup table, the program with the rounds and the
// filter's width written into its loops, and the pixels made of what the
// CUs leave behind. Plain C++ like array_lines.h.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "array/program.h"
#include "forward_texture/array_lines.h"
#include "forward_texture/filter.h"

namespace tessera::forward_texture {

// Where resample_chain.s keeps what the host writes and reads, and its limits.
struct ArrayChainLayout {
  // Per CU.
  uint16_t num = 0, num_step = 0, den = 0, den_step = 0, prev_hi = 0, prev_lo = 0, cur_hi = 0, cur_lo = 0, texel_cu = 0,
           relay = 0, started = 0;
  // The same in every CU.
  uint16_t offset = 0, slots = 0, zero = 0, ff = 0, c80 = 0, c7f = 0, c40 = 0, cc0 = 0, none = 0, limit = 0, clamp = 0;
  // Results.
  uint16_t idx_hi = 0, idx_lo = 0, val_hi = 0, val_lo = 0, err = 0, fin_hi = 0, fin_lo = 0, pixel = 0;
  int max_rounds = 0;  // the most rounds a run holds
  int max_width = 0;   // the widest filter

  // Throws std::invalid_argument naming a variable the program lacks or
  // whose size differs.
  static ArrayChainLayout of(const ap::Program& program);
};

// The array the chain runs on: its grid, and the lookup table's size.
struct ChainGeometry {
  unsigned columns = 24;
  unsigned rows = 4;
  unsigned lut_entries = 0;
  unsigned cus() const { return columns * rows; }
  // Borders a row takes per round: every column but the relay.
  int borders_per_round() const { return static_cast<int>(columns) - 1; }
  // Rounds for a line of `texel_count` texels (its texel_count + 1 borders).
  int rounds(int texel_count) const { return texel_count / borders_per_round() + 1; }
};

// Empty, or the message naming what the program cannot do: a width beyond
// its window, a table that does not fit the lookup table, a line longer than
// its rounds hold.
std::string array_chain_error(const ArrayChainLayout& layout, const ChainGeometry& geometry, const FilterTable& table,
                              int texel_count);

// The program's words with rounds - 1 in its round loop and width - 1 in its
// window loops (array_chain_error must be empty).
std::vector<uint64_t> program_for_chain(const ap::Program& program, int rounds, int width);

// The lookup table's entries: entry 256 j + phase is table.at(phase, j).
std::vector<uint16_t> chain_lut(const FilterTable& table);

// What every CU gets for a filter of `width`.
std::vector<CmemBlock> chain_filter_blocks(const ArrayChainLayout& layout, int width);

// The rows that give CU row r line r (lines.size() <= geometry.rows, all
// of the same length, oriented by orient_line); the rows past the last line
// get zeros.
std::vector<CmemRow> chain_rows(const ArrayChainLayout& layout, const ChainGeometry& geometry,
                                const std::vector<ArrayLine>& lines);

// The pixels of the line in CU row `row`, read through `cmem(cu, address)`
// after the run: every pixel of `pixels` written, as resample_line writes
// them (0 where no texel reaches). False when a CU flagged an error on one
// of the line's borders: step_borders names it.
bool gather_chain_line(const ArrayChainLayout& layout, const ChainGeometry& geometry, int texel_count, int width,
                       unsigned row, const std::function<uint8_t(unsigned cu, uint16_t address)>& cmem,
                       LineView pixels);

}  // namespace tessera::forward_texture
