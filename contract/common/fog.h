// The fixed-point fog arithmetic, written once for every renderer: the arm
// and raster back ends, the rasterizer's fog unit (tlm/raster/datapath/
// fog_unit.h, whose Verilog twin rtl_models/raster/fog_unit.sv computes the
// same bits) and whatever back end fogs next. OpenGL ES 1.1, section 3.8
// "Fog": C = f Cf + (1 - f) Cfog on R, G and B; alpha is not fogged.
//
// The fog argument. Each mode's factor is a function of one number that is
// linear in the fog coordinate c (the eye distance, |z_eye|), so the
// renderers interpolate that number instead of c and the per-fragment work
// is only the function, as Mesa's fixed-function fog does it (its optimized
// fog parameters: d / ln 2 and d / sqrt(ln 2)):
//     linear  a = (end - c) / (end - start)  f = clamp(a, 0, 1)
//     exp     a = d c / ln 2                 f = 2^-a          (= e^-dc)
//     exp2    a = d c / sqrt(ln 2)           f = 2^-(a^2)      (= e^-(dc)^2)
// a is signed 16.16 fixed point in an int32_t (renderers/common/fog.h
// converts a vertex's c to it, saturating at the int32 range).
//
// The factor f is an 8-bit code, 255 = no fog. Linear rounds clamp(a, 0, 1)
// * 255 to nearest. The exponential modes take x = max(a, 0) (exp) or x =
// min(max(a, 0), 4)^2 truncated to 16.16 (exp2; 2^-9 already rounds to 0):
// 2^-x = 2^-frac(x) >> floor(x), with 2^-frac(x) from the 256-entry table of
// fog_exp2_table.def (unsigned 0.16, entry i = 2^-x at the midpoint of
// [i/256, (i+1)/256), indexed by the top 8 fraction bits of x), shifted
// right by floor(x) (truncating; 0 from 16 on), and rounded once to 8 bits:
// f = (m * 255 + 2^15) >> 16. Error: f is within 0.84 of the exact 255 * 2^-x
// for every x (tests/common/test_fog.cpp measures the bound exhaustively):
// at most 255 * ln 2 / 512 = 0.35 from taking the midpoint, the rest the
// final rounding.
//
// The blend: each of R, G, B is (f Cf + (255 - f) Cfog) / 255 rounded to
// nearest exactly (x <= 65025, the divider of texture_env.h and blending).
// A mode code without an entry (3) applies no fog: f = 255.
#pragma once

#include <algorithm>
#include <cstdint>

#include "common/fixed_function.h"

namespace tessera {

inline constexpr int FOG_FRACTION_BITS = 16;
inline constexpr int FOG_TABLE_INDEX_BITS = 8;
inline constexpr uint32_t FOG_TABLE_ENTRIES = 1u << FOG_TABLE_INDEX_BITS;
inline constexpr int32_t FOG_ONE = 1 << FOG_FRACTION_BITS;
// exp2 squares at most 4.0: 4^2 = 16 shifts every table entry to 0.
inline constexpr int32_t FOG_EXP2_ARGUMENT_LIMIT = 4 * FOG_ONE;

// Unsigned 0.16 entries held in 32 bits: a batch of fragments reads the
// table with one vector gather, which has no 16-bit form.
struct FogExp2Table {
  uint32_t entry[FOG_TABLE_ENTRIES];
};
inline constexpr FogExp2Table FOG_EXP2 = {{
#define TESSERA_FOG_EXP2(index, value) (value),
#include "common/fog_exp2_table.def"
}};
inline constexpr const uint32_t (&FOG_EXP2_TABLE)[FOG_TABLE_ENTRIES] = FOG_EXP2.entry;

// 255 * 2^-x as an 8-bit code, x unsigned 16.16. The shift by floor(x) is
// cut at 16, where every 16-bit table entry is already 0, so that there is
// no branch for floor(x) >= 16.
constexpr uint8_t fog_exp2_negative(uint32_t x) {
  const uint32_t whole = x >> FOG_FRACTION_BITS;
  const uint32_t index = (x >> (FOG_FRACTION_BITS - FOG_TABLE_INDEX_BITS)) & (FOG_TABLE_ENTRIES - 1);
  const uint32_t mantissa = FOG_EXP2.entry[index] >> (whole < 16 ? whole : 16);
  return static_cast<uint8_t>((mantissa * 255 + (1u << (FOG_FRACTION_BITS - 1))) >> FOG_FRACTION_BITS);
}

// The fog factor of the fog argument (16.16) in `mode`, 0..255. The linear
// factor and the exponential one (of x = a for exp, a^2 for exp2: one table
// read either way) are both computed and the mode's code selects by masks,
// without a branch: the rasterizer's fog unit runs it on a batch of
// fragments, which the compiler then vectorises (tlm/raster/datapath/
// batch.h).
constexpr uint8_t fog_factor(FogMode mode, int32_t argument) {
  const uint32_t positive = argument < 0 ? 0u : static_cast<uint32_t>(argument);
  const uint32_t a = std::min<uint32_t>(positive, FOG_ONE);
  const uint32_t linear = (a * 255 + (1u << (FOG_FRACTION_BITS - 1))) >> FOG_FRACTION_BITS;
  const uint64_t b = std::min<uint32_t>(positive, FOG_EXP2_ARGUMENT_LIMIT);
  const auto square = static_cast<uint32_t>((b * b) >> FOG_FRACTION_BITS);
  const uint32_t code = static_cast<uint32_t>(mode);
  const uint32_t exponential = fog_exp2_negative(code == code_of(FogMode::exp2) ? square : positive);
  const auto pick = [code](uint32_t mode_code, uint32_t factor) { return (code == mode_code ? 0xffu : 0u) & factor; };
  return static_cast<uint8_t>(pick(code_of(FogMode::linear), linear) | pick(code_of(FogMode::exp), exponential) |
                              pick(code_of(FogMode::exp2), exponential) | (code > code_of(FogMode::exp2) ? 0xffu : 0u));
}

// The fogged colour: RGB of `rgba` (r | g << 8 | b << 16 | a << 24) towards
// `fog_rgba`'s by 1 - f/255; alpha stays.
constexpr uint32_t fog_blend(uint8_t factor, uint32_t rgba, uint32_t fog_rgba) {
  uint32_t out = rgba & 0xff000000u;
  for (int ch = 0; ch < 3; ++ch) {
    const uint32_t c = (rgba >> (8 * ch)) & 0xff, fog = (fog_rgba >> (8 * ch)) & 0xff;
    const uint32_t x = factor * c + (255u - factor) * fog + 128;
    out |= ((x + (x >> 8)) >> 8) << (8 * ch);
  }
  return out;
}

}  // namespace tessera
