#include "renderers/ap_tile/tile_reference.h"

namespace tessera::ap_tile {

namespace {

uint16_t get16(const uint8_t* at) {
  return static_cast<uint16_t>(at[0] << 8 | at[1]);
}

uint32_t get24(const uint8_t* at) {
  return uint32_t{at[0]} << 16 | uint32_t{at[1]} << 8 | at[2];
}

void fill(const CmemLayout& m, uint8_t* cmem) {
  const unsigned last = m.tile_height - 1;
  for (unsigned l = last + 1; l-- > 0;) {
    uint16_t e[3];
    for (unsigned k = 0; k < 3; ++k) {
      // mul keeps 24 bits; the program adds the low 16 to e0.
      const int product = static_cast<int16_t>(get16(cmem + m.edv + 2 * k)) * static_cast<int8_t>(cmem[m.yc + l]);
      e[k] = static_cast<uint16_t>(get16(cmem + m.e0 + 2 * k) + static_cast<uint16_t>(product));
    }
    for (unsigned x = m.tile_width; x-- > 0;) {
      const bool inside =
          (cmem[m.live] & 0x80) != 0 && (e[0] & 0x8000) == 0 && (e[1] & 0x8000) == 0 && (e[2] & 0x8000) == 0;
      cmem[m.pixel(m.we, x, l)] = inside ? 0xff : 0x00;
      for (unsigned k = 0; k < 3; ++k) e[k] = static_cast<uint16_t>(e[k] + get16(cmem + m.edu + 2 * k));
    }
  }
}

void depth(const CmemLayout& m, uint8_t* cmem) {
  uint32_t row = get24(cmem + m.z0);
  const uint32_t du = get24(cmem + m.zdu), dv = get24(cmem + m.zdv);
  const bool lequal = cmem[m.zlequal] != 0;
  for (unsigned l = m.tile_height; l-- > 0;) {
    uint32_t z = row;
    for (unsigned x = m.tile_width; x-- > 0;) {
      const unsigned we = m.pixel(m.we, x, l), hi = m.pixel(m.zhi, x, l), lo = m.pixel(m.zlo, x, l);
      const uint8_t enable = cmem[we];
      const auto z16 = static_cast<uint16_t>(z >> 8);
      const auto buffer = static_cast<uint16_t>(cmem[hi] << 8 | cmem[lo]);
      const bool pass = buffer > z16 || (lequal && buffer == z16);
      // The program keeps the enable's bits: (we & pass) | (we & zoff).
      const uint8_t kept = static_cast<uint8_t>(((enable & 0x80) != 0 && pass ? 0xff : 0x00) | (enable & cmem[m.zoff]));
      cmem[we] = kept;
      if ((kept & cmem[m.zwrite] & 0x80) != 0) {
        cmem[hi] = static_cast<uint8_t>(z16 >> 8);
        cmem[lo] = static_cast<uint8_t>(z16);
      }
      z = (z + du) & 0xffffffu;
    }
    row = (row + dv) & 0xffffffu;
  }
}

void colour(const CmemLayout& m, uint8_t* cmem) {
  uint16_t row[3], du[3], dv[3];
  for (unsigned k = 0; k < 3; ++k) {
    row[k] = get16(cmem + m.c0 + 2 * k);
    du[k] = get16(cmem + m.cdu + 2 * k);
    dv[k] = get16(cmem + m.cdv + 2 * k);
  }
  for (unsigned l = m.tile_height; l-- > 0;) {
    uint16_t c[3] = {row[0], row[1], row[2]};
    for (unsigned x = m.tile_width; x-- > 0;) {
      if ((cmem[m.pixel(m.we, x, l)] & 0x80) != 0) {
        const unsigned r = c[0] >> 8, g = c[1] >> 8, b = c[2] >> 8;
        cmem[m.pixel(m.chi, x, l)] = static_cast<uint8_t>(((r << 3) & 0xff) | (g >> 3));
        cmem[m.pixel(m.clo, x, l)] = static_cast<uint8_t>(((g << 5) & 0xff) | b);
      }
      for (unsigned k = 0; k < 3; ++k) c[k] = static_cast<uint16_t>(c[k] + du[k]);
    }
    for (unsigned k = 0; k < 3; ++k) row[k] = static_cast<uint16_t>(row[k] + dv[k]);
  }
}

void texcoord(const CmemLayout& m, uint8_t* cmem) {
  uint16_t row[2], du[2], dv[2];
  for (unsigned k = 0; k < 2; ++k) {
    row[k] = get16(cmem + m.st0 + 2 * k);
    du[k] = get16(cmem + m.stdu + 2 * k);
    dv[k] = get16(cmem + m.stdv + 2 * k);
  }
  for (unsigned l = m.tile_height; l-- > 0;) {
    uint16_t st[2] = {row[0], row[1]};
    for (unsigned x = m.tile_width; x-- > 0;) {
      if ((cmem[m.pixel(m.we, x, l)] & 0x80) != 0) {
        cmem[m.pixel(m.shi, x, l)] = static_cast<uint8_t>(st[0] >> 8);
        cmem[m.pixel(m.slo, x, l)] = static_cast<uint8_t>(st[0]);
        cmem[m.pixel(m.thi, x, l)] = static_cast<uint8_t>(st[1] >> 8);
        cmem[m.pixel(m.tlo, x, l)] = static_cast<uint8_t>(st[1]);
        cmem[m.pixel(m.tid, x, l)] = cmem[m.tex];
      }
      for (unsigned k = 0; k < 2; ++k) st[k] = static_cast<uint16_t>(st[k] + du[k]);
    }
    for (unsigned k = 0; k < 2; ++k) row[k] = static_cast<uint16_t>(row[k] + dv[k]);
  }
}

void clear(const CmemLayout& m, uint8_t* cmem, bool colour_buffer) {
  for (unsigned x = 0; x < m.tile_width; ++x)
    for (unsigned l = 0; l < m.tile_height; ++l)
      if (colour_buffer) {
        cmem[m.pixel(m.chi, x, l)] = cmem[m.clear_c];
        cmem[m.pixel(m.clo, x, l)] = cmem[m.clear_c + 1];
        cmem[m.pixel(m.tid, x, l)] = cmem[m.zero];
      } else {
        cmem[m.pixel(m.zhi, x, l)] = cmem[m.clear_z];
        cmem[m.pixel(m.zlo, x, l)] = cmem[m.clear_z + 1];
      }
}

}  // namespace

const char* stage_entry(TileStage stage) {
  switch (stage) {
    case TileStage::fill: return "fill";
    case TileStage::depth: return "depth";
    case TileStage::colour: return "colour";
    case TileStage::texcoord: return "texcoord";
    case TileStage::clear_colour: return "clear_colour";
    case TileStage::clear_depth: return "clear_depth";
  }
  return "?";
}

void run_reference(TileStage stage, const CmemLayout& layout, uint8_t* cmem) {
  switch (stage) {
    case TileStage::fill: fill(layout, cmem); break;
    case TileStage::depth: depth(layout, cmem); break;
    case TileStage::colour: colour(layout, cmem); break;
    case TileStage::texcoord: texcoord(layout, cmem); break;
    case TileStage::clear_colour: clear(layout, cmem, true); break;
    case TileStage::clear_depth: clear(layout, cmem, false); break;
  }
}

void run_reference_pass(const CmemLayout& layout, uint8_t* cmem) {
  for (TileStage stage : {TileStage::fill, TileStage::depth, TileStage::colour, TileStage::texcoord})
    run_reference(stage, layout, cmem);
}

}  // namespace tessera::ap_tile
