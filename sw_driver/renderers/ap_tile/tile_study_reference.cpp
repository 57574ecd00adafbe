#include "renderers/ap_tile/tile_study_reference.h"

namespace tessera::ap_tile {

namespace {

// A 16-bit variable of the program, big-endian in CMEM.
uint16_t get16(const uint8_t* cmem, unsigned at) {
  return static_cast<uint16_t>(cmem[at] << 8 | cmem[at + 1]);
}

void put16(uint8_t* cmem, unsigned at, uint16_t value) {
  cmem[at] = static_cast<uint8_t>(value >> 8);
  cmem[at + 1] = static_cast<uint8_t>(value);
}

bool negative(uint16_t value) {
  return (value & 0x8000u) != 0;
}

// The language's 16 x 8 multiplication of CMEM variables, the array's
// mulm: the signed 16-bit multiplicand times the signed 8-bit multiplier,
// the 24-bit product stored in `product` (high, middle, low), then its low
// 16 bits copied into `result`.
void multiply(const StudyLayout& m, uint8_t* cmem, unsigned multiplicand, unsigned multiplier, unsigned result) {
  const int32_t full =
      int32_t{static_cast<int16_t>(get16(cmem, multiplicand))} * int32_t{static_cast<int8_t>(cmem[multiplier])};
  const auto bits = static_cast<uint32_t>(full);
  cmem[m.product] = static_cast<uint8_t>(bits >> 16);
  cmem[m.product + 1] = static_cast<uint8_t>(bits >> 8);
  cmem[m.product + 2] = static_cast<uint8_t>(bits);
  cmem[result] = cmem[m.product + 1];
  cmem[result + 1] = cmem[m.product + 2];
}

// `variable` -= `step` (16 bits, wrapping).
void step_down(uint8_t* cmem, unsigned variable, unsigned step) {
  put16(cmem, variable, static_cast<uint16_t>(get16(cmem, variable) - get16(cmem, step)));
}

// The walk every stage makes: rows bottom to top; in each, the running
// variables reset from their row variables (which then step by their y
// deltas), the first pixel (x = W - 1) at that value, every other pixel
// after one x step each. `reset(y)` does the row start, `step()` the x
// step, `pixel(x, y)` the pixel's work.
template <class Reset, class Step, class Pixel>
void walk(const StudyLayout& m, Reset&& reset, Step&& step, Pixel&& pixel) {
  for (unsigned y = m.tile_height; y-- > 0;) {
    reset();
    pixel(m.tile_width - 1, y);
    for (unsigned x = m.tile_width - 1; x-- > 0;) {
      step();
      pixel(x, y);
    }
  }
}

void fill(const StudyLayout& m, uint8_t* cmem) {
  for (unsigned y = m.tile_height; y-- > 0;)
    for (unsigned x = m.tile_width; x-- > 0;) cmem[m.pixel(m.we, x, y)] = cmem[m.one];
  for (unsigned k = 0; k < 3; ++k) {
    const unsigned a = m.line_a + 2 * k, b = m.line_b + 2 * k, c = m.line_c + 2 * k;
    // The value at the bottom-right pixel: A x + B y + C with x, y from
    // the counter tables.
    multiply(m, cmem, a, m.xcounter + m.tile_width - 1, m.px);
    multiply(m, cmem, b, m.ycounter + m.tile_height - 1, m.py);
    put16(cmem, m.erow, static_cast<uint16_t>(get16(cmem, c) + get16(cmem, m.px)));
    put16(cmem, m.erow, static_cast<uint16_t>(get16(cmem, m.erow) + get16(cmem, m.py)));
    walk(
        m,
        [&] {
          put16(cmem, m.ev, get16(cmem, m.erow));
          step_down(cmem, m.erow, b);
        },
        [&] { step_down(cmem, m.ev, a); },
        [&](unsigned x, unsigned y) {
          if (negative(get16(cmem, m.ev))) cmem[m.pixel(m.we, x, y)] = 0;
        });
  }
}

void depth(const StudyLayout& m, uint8_t* cmem) {
  put16(cmem, m.zrow, get16(cmem, m.z_start));
  walk(
      m,
      [&] {
        put16(cmem, m.zv, get16(cmem, m.zrow));
        step_down(cmem, m.zrow, m.z_dy);
      },
      [&] { step_down(cmem, m.zv, m.z_dx); },
      [&](unsigned x, unsigned y) {
        const unsigned we = m.pixel(m.we, x, y), hi = m.pixel(m.zb_hi, x, y), lo = m.pixel(m.zb_lo, x, y);
        const uint16_t z = get16(cmem, m.zv);
        const auto buffer = static_cast<uint16_t>(cmem[hi] << 8 | cmem[lo]);
        cmem[m.flag] = cmem[m.xcounter];
        if (z < buffer) cmem[m.flag] = cmem[m.one];
        cmem[we] = static_cast<uint8_t>(cmem[we] & cmem[m.flag]);
        if (cmem[we] != 0) {
          cmem[hi] = static_cast<uint8_t>(z >> 8);
          cmem[lo] = static_cast<uint8_t>(z);
        }
      });
}

void colour(const StudyLayout& m, uint8_t* cmem) {
  for (unsigned k = 0; k < 3; ++k) put16(cmem, m.crow + 2 * k, get16(cmem, m.c_start + 2 * k));
  walk(
      m,
      [&] {
        for (unsigned k = 0; k < 3; ++k) {
          put16(cmem, m.cv + 2 * k, get16(cmem, m.crow + 2 * k));
          step_down(cmem, m.crow + 2 * k, m.c_dy + 2 * k);
        }
      },
      [&] {
        for (unsigned k = 0; k < 3; ++k) step_down(cmem, m.cv + 2 * k, m.c_dx + 2 * k);
      },
      [&](unsigned x, unsigned y) {
        // The integer parts: red and green into the red-green word, blue
        // into its byte.
        cmem[m.rgw] = cmem[m.cv];
        cmem[m.rgw + 1] = cmem[m.cv + 2];
        cmem[m.bw] = cmem[m.cv + 4];
        if (cmem[m.pixel(m.we, x, y)] != 0) {
          cmem[m.pixel(m.rg_hi, x, y)] = cmem[m.rgw];
          cmem[m.pixel(m.rg_lo, x, y)] = cmem[m.rgw + 1];
          cmem[m.pixel(m.b, x, y)] = cmem[m.bw];
        }
      });
}

void texcoord(const StudyLayout& m, uint8_t* cmem) {
  for (unsigned k = 0; k < 2; ++k) put16(cmem, m.strow + 2 * k, get16(cmem, m.st_start + 2 * k));
  walk(
      m,
      [&] {
        for (unsigned k = 0; k < 2; ++k) {
          put16(cmem, m.stv + 2 * k, get16(cmem, m.strow + 2 * k));
          step_down(cmem, m.strow + 2 * k, m.st_dy + 2 * k);
        }
      },
      [&] {
        for (unsigned k = 0; k < 2; ++k) step_down(cmem, m.stv + 2 * k, m.st_dx + 2 * k);
      },
      [&](unsigned x, unsigned y) {
        if (cmem[m.pixel(m.we, x, y)] == 0) return;
        cmem[m.pixel(m.s_hi, x, y)] = cmem[m.stv];
        cmem[m.pixel(m.s_lo, x, y)] = cmem[m.stv + 1];
        cmem[m.pixel(m.t_hi, x, y)] = cmem[m.stv + 2];
        cmem[m.pixel(m.t_lo, x, y)] = cmem[m.stv + 3];
        cmem[m.pixel(m.tid, x, y)] = cmem[m.tex];
      });
}

void clear(const StudyLayout& m, uint8_t* cmem, bool colour_buffer) {
  for (unsigned x = 0; x < m.tile_width; ++x)
    for (unsigned y = 0; y < m.tile_height; ++y)
      if (colour_buffer) {
        cmem[m.pixel(m.rg_hi, x, y)] = cmem[m.clear_rg];
        cmem[m.pixel(m.rg_lo, x, y)] = cmem[m.clear_rg + 1];
        cmem[m.pixel(m.b, x, y)] = cmem[m.clear_b];
        cmem[m.pixel(m.tid, x, y)] = cmem[m.xcounter];
      } else {
        cmem[m.pixel(m.zb_hi, x, y)] = cmem[m.clear_z];
        cmem[m.pixel(m.zb_lo, x, y)] = cmem[m.clear_z + 1];
      }
}

}  // namespace

void run_study_reference(TileStage stage, const StudyLayout& layout, uint8_t* cmem) {
  switch (stage) {
    case TileStage::fill: fill(layout, cmem); break;
    case TileStage::depth: depth(layout, cmem); break;
    case TileStage::colour: colour(layout, cmem); break;
    case TileStage::texcoord: texcoord(layout, cmem); break;
    case TileStage::clear_colour: clear(layout, cmem, true); break;
    case TileStage::clear_depth: clear(layout, cmem, false); break;
  }
}

}  // namespace tessera::ap_tile
