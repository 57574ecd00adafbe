// See interpolation.h.
#include "raster/core/interpolation.h"

#include <algorithm>

namespace tessera::raster {

namespace {

// Perspective-correct Gouraud colour: c = (c/w) / (1/w) per channel, the
// c/w sum in colour words (16 fraction bits, scaled by the normalised q) and
// q with 24 fraction bits, divided by the refined reciprocal of q into
// colour words and converted by the interpolator's output rule.
Rgba8 perspective_color(const TriangleSetup& ts, int dx, int dy, RecipMethod method) {
  const attribute_sum q = attribute_at(ts.q, dx, dy);
  Reciprocal inv_q;
  refined_reciprocal(uint64_t(std::max<int64_t>(q.raw, 1)), method, inv_q);
  const auto channel = [&](unsigned ch) {
    const int128 c = divide(attribute_at(ts.color[ch], dx, dy).raw, inv_q, false, -int(TEXCOORD_FRACTION_BITS));
    return attribute_to_color(attribute_sum{saturate_word(c)});
  };
  return {channel(0), channel(1), channel(2), channel(3)};
}

}  // namespace

Rgba8 interpolated_color(const TriangleSetup& ts, int dx, int dy, RecipMethod method) {
  if (ts.perspective_color) return perspective_color(ts, dx, dy, method);
  if (ts.flat) return ts.flat_color;
  return {attribute_to_color(attribute_at(ts.color[0], dx, dy)), attribute_to_color(attribute_at(ts.color[1], dx, dy)),
          attribute_to_color(attribute_at(ts.color[2], dx, dy)), attribute_to_color(attribute_at(ts.color[3], dx, dy))};
}

int32_t interpolated_fog(const TriangleSetup& ts, int dx, int dy, RecipMethod method) {
  int128 argument = attribute_at(ts.fog, dx, dy).raw;
  if (ts.perspective_fog) {
    const attribute_sum q = attribute_at(ts.q, dx, dy);
    Reciprocal inv_q;
    refined_reciprocal(uint64_t(std::max<int64_t>(q.raw, 1)), method, inv_q);
    argument = divide(argument, inv_q, false, -int(TEXCOORD_FRACTION_BITS));
  }
  return int32_t(std::clamp<int128>(argument, INT32_MIN, INT32_MAX));
}

unorm24 interpolated_depth(const TriangleSetup& ts, int dx, int dy) {
  return attribute_to_depth(attribute_at(ts.depth, dx, dy));
}

}  // namespace tessera::raster
