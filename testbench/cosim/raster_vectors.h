// Random vectors of the rasterizer's datapath units, the one copy that the
// cosim tests (tests/rtl_models/raster/) and bench_rtl (bench/) both draw
// from, so that the benchmark times the distributions the tests check.
//
// A unit's vectors come in two parts, as its batch form takes them: a state
// (or plane, or span) that a batch of lanes shares, and the lanes. Each
// generator draws from the caller's std::mt19937_64 in a fixed order, so a
// seed gives the same vectors on every machine. Where a code has no entry in
// contract/common/fixed_function.def, the generators draw it too (the ALL_*
// arrays end with such a code): the RTL and the C++ twin must agree on it.
#pragma once

#include <array>
#include <cstdint>
#include <random>

#include "raster/datapath/attribute_interpolator.h"
#include "raster/datapath/blend_logic_op.h"
#include "raster/datapath/edge_function.h"
#include "raster/datapath/fog_unit.h"
#include "raster/datapath/fragment_tests.h"
#include "raster/datapath/lod_unit.h"
#include "raster/datapath/reciprocal.h"
#include "raster/datapath/texel_address.h"
#include "raster/datapath/texture_combiner.h"
#include "raster/datapath/texture_env.h"

namespace tessera::raster {

using VectorRng = std::mt19937_64;

// ---------------------------------------------------------------------------
// Reciprocal unit: an operand of 0 .. RECIP_OPERAND_MAX (0 has no
// reciprocal and is flagged). The cosim test takes every 16-bit operand
// instead.
uint16_t random_reciprocal_operand(VectorRng& rng);

// ---------------------------------------------------------------------------
// Edge function: `pixels` pixels along row py from px, within the RTL's
// 9-bit pixel ports (the span ends at pixel 511 at most). Half of the spans
// use a short edge near their first pixel, so that the distance and the
// coverage leave their clamps, with the exact reciprocal of |dx| + |dy| (as
// the reciprocal unit would roughly deliver); the other half a random edge
// and a random reciprocal.
struct EdgeSpanVector {
  Edge edge;
  unsigned px = 0, py = 0;
  q5_16 recip;
};
EdgeSpanVector random_edge_span(VectorRng& rng, unsigned pixels);

// ---------------------------------------------------------------------------
// Attribute interpolator: a plane of every kind code (3: undefined) whose
// words have random magnitudes (1 to 40 bits), so the conversions are seen
// inside their range as well as clamped; offsets anywhere in -512..511.
struct PixelOffset {
  int32_t dx = 0, dy = 0;
};
AttributePlane random_attribute_plane(VectorRng& rng);
PixelOffset random_pixel_offset(VectorRng& rng);

// ---------------------------------------------------------------------------
// Fragment tests: every enable, function and operation (and the stencil
// operation code 7, which has no entry and keeps); a quarter of the
// fragments compare equal depths and half of them an alpha equal to the
// reference, which random values never would.
extern const std::array<CompareFunc, 8> ALL_COMPARE_FUNCS;
extern const std::array<StencilOp, 7> ALL_STENCIL_OPS;
FragmentTestState random_fragment_test_state(VectorRng& rng);
FragmentTestInput random_fragment(VectorRng& rng, const FragmentTestState& state);

// ---------------------------------------------------------------------------
// Blend and logic op: every factor (and code 15, which acts as ZERO),
// mostly blending (it has the arithmetic), an eighth logic ops, a quarter
// with a colour mask; colours at random.
extern const std::array<BlendFactor, 12> ALL_BLEND_FACTORS;
struct ColourPair {
  uint32_t src = 0, dst = 0;
};
BlendState random_blend_state(VectorRng& rng);
ColourPair random_colour_pair(VectorRng& rng);

// ---------------------------------------------------------------------------
// Texel address: textures of 1 to 512 texels a side, both wraps and
// filters, any base; coordinates mostly within a few repetitions (where the
// wrap and clamp decisions happen), an eighth across the whole 15.16 range.
struct TexCoords {
  int32_t s = 0, t = 0;  // q15_16 raw
};
TextureState random_texture_state(VectorRng& rng);
TexCoords random_tex_coords(VectorRng& rng);

// ---------------------------------------------------------------------------
// Texture filter and environment: REPLACE, MODULATE, DECAL and code 3 (the
// combiner's BLEND: the fragment passes); four texels, two weights and the
// fragment at random.
extern const std::array<TexEnv, 4> ALL_TEXTURE_ENV_MODES;
struct TextureEnvLane {
  std::array<uint32_t, 4> texel{};
  uint8_t weight_s = 0, weight_t = 0;
  uint32_t fragment = 0;
};
TexEnv random_texture_env_mode(VectorRng& rng);
TextureEnvLane random_texture_env_lane(VectorRng& rng);

// ---------------------------------------------------------------------------
// Fog: every mode code (3: no fog) with a fog colour; arguments over the
// whole signed 16.16 range half the time, within the table's reach (-1 to
// 31) the other half.
extern const std::array<FogMode, 4> ALL_FOG_MODES;
struct FogUnitState {
  FogMode mode = FogMode::linear;
  Rgba8 colour;
};
struct FogLane {
  int32_t argument = 0;  // q15_16 raw
  uint32_t fragment = 0;
};
FogUnitState random_fog_state(VectorRng& rng);
FogLane random_fog_lane(VectorRng& rng);

// ---------------------------------------------------------------------------
// LOD unit: a state is an 8-bit code, min filter (bit 0), mag filter (bit
// 1), mipmap (bits 2-3) and last level (bits 4-7), so that 256 codes are
// every state; rho of every magnitude equally often (a random rho shifted
// right by 0..31).
struct LodState {
  TexFilter min = TexFilter::nearest, mag = TexFilter::nearest;
  TexMipmap mipmap = TexMipmap::none;
  unsigned last_level = 0;

  static LodState from_code(unsigned code);
};
constexpr unsigned LOD_STATES = 256;
LodState random_lod_state(VectorRng& rng);
uint32_t random_lod_rho(VectorRng& rng);

// ---------------------------------------------------------------------------
// Texture combiner: a unit's state as the RTL's ports take it (codes and
// combiner words, reserved bits included, so that every source, operand and
// scale code is drawn); half the states take COMBINE, the rest any
// environment code; colours at random.
struct CombinerState {
  uint32_t env = 0, base_format = 0;  // codes, those without an entry included
  Rgba8 env_color;
  uint32_t rgb_word = 0, alpha_word = 0;

  // The same state as the C++ twin takes it.
  TextureUnitEnv unit() const;
};
struct CombinerLane {
  uint32_t primary = 0, previous = 0, texel = 0;
};
CombinerState random_combiner_state(VectorRng& rng);
CombinerLane random_combiner_lane(VectorRng& rng);

}  // namespace tessera::raster
