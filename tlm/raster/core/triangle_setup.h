// Triangle setup: twice the signed area and its refined reciprocal, the
// edges oriented clockwise with their EASA reciprocals from the unit, and
// the plane equations of depth, colour and the perspective texture
// coordinates in the attribute interpolator's words (README.md, "Triangle
// setup"): everything the traversal and the shading take from a triangle.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "raster/core/command_decoder.h"
#include "raster/core/draw_state.h"
#include "raster/core/refined_reciprocal.h"
#include "raster/datapath/attribute_interpolator.h"
#include "raster/datapath/edge_function.h"

namespace tessera::raster {

constexpr unsigned TEXCOORD_FRACTION_BITS = 24;  // texcoord_attr, also the q (1/w) plane
constexpr int64_t ATTRIBUTE_WORD_MAX = (int64_t{1} << 39) - 1;

// Saturated to the interpolator's signed 40-bit words (in 64 bits where the
// value fits, which a batch loop vectorises).
inline int64_t saturate_word(int128 v) {
  return int64_t(std::clamp<int128>(v, -ATTRIBUTE_WORD_MAX - 1, ATTRIBUTE_WORD_MAX));
}
inline int64_t saturate_word(int64_t v) {
  return std::clamp<int64_t>(v, -ATTRIBUTE_WORD_MAX - 1, ATTRIBUTE_WORD_MAX);
}

struct TriangleSetup {
  std::array<Edge, 3> edges;
  std::array<q5_16, 3> edge_recip;  // EASA: 1/(|dx| + |dy|) from the reciprocal unit
  std::array<AttributePlane, 4> color;
  AttributePlane depth;
  AttributePlane s, t, q;    // s/w, t/w, 1/w, normalised (README.md, "Texture coordinates")
  int ref_x = 0, ref_y = 0;  // the pixel the planes' start values belong to
  bool flat = false;
  // Gouraud colour seen in perspective: `color` holds c/w (normalised like
  // q) and each pixel divides by q, as GL interpolates (README.md, "Colour").
  bool perspective_color = false;
  Rgba8 flat_color;
  // With fog: the fog argument's plane, in 16.16 words; in perspective it
  // holds argument/w (normalised like q) and each pixel divides by q, as
  // for the colours (README.md, "Fog").
  AttributePlane fog;
  bool perspective_fog = false;
  // With StateFlag::texture_units: each unit's s/w and t/w planes, set up
  // like s and t (unit 0's are s and t themselves).
  std::array<AttributePlane, MAX_TEXTURE_UNITS> unit_s, unit_t;
};

// false: the triangle cannot be drawn and is skipped (zero area, an edge the
// unit refuses, texturing without usable texture coordinates).
bool set_up_triangle(const TriangleVertices& vertices, const DrawState& state, RecipMethod method,
                     TriangleSetup& setup);

}  // namespace tessera::raster
