// Attribute interpolation of a batch of fragments (fragment_batch.h) from
// the setup's planes, at offsets (dx[i], dy[i]) from the reference pixel:
// their colours (flat: the provoking vertex's; Gouraud: the colour planes;
// Gouraud in perspective: c/w divided by 1/w with the refined reciprocal),
// depths and fog arguments, through the attribute interpolator's batch form
// and its output rule (README.md, "Triangle setup" and "Colour").
#pragma once

#include <array>
#include <cstdint>

#include "raster/core/fragment_batch.h"
#include "raster/core/triangle_setup.h"
#include "raster/datapath/reciprocal.h"

namespace tessera::raster {

// The interpolation's working arrays, one entry a fragment.
struct InterpolationScratch {
  static constexpr unsigned N = FragmentBatch::CAPACITY;
  std::array<int64_t, N> value;
  std::array<uint32_t, N> output;
  // 1/q, refined, where the perspective needs it: Reciprocal's y and n.
  std::array<uint64_t, N> inv_y;
  std::array<int64_t, N> inv_n;
};

// Packed RGBA8 colours (Rgba8::pack) of `count` fragments.
void interpolated_colors(const TriangleSetup& setup, const int32_t* dx, const int32_t* dy, unsigned count,
                         RecipMethod method, InterpolationScratch& scratch, uint32_t* rgba);
// Depth codes (0.24).
void interpolated_depths(const TriangleSetup& setup, const int32_t* dx, const int32_t* dy, unsigned count,
                         InterpolationScratch& scratch, uint32_t* depth);
// Fog arguments (16.16, saturated to 32 bits): the plane's value, or in
// perspective argument/w divided by q with the refined reciprocal.
void interpolated_fogs(const TriangleSetup& setup, const int32_t* dx, const int32_t* dy, unsigned count,
                       RecipMethod method, InterpolationScratch& scratch, int32_t* argument);

}  // namespace tessera::raster
