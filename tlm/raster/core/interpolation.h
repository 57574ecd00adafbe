// Attribute interpolation of one fragment from the setup's planes, at the
// offset (dx, dy) from the reference pixel: its colour (flat: the provoking
// vertex's; Gouraud: the colour planes; Gouraud in perspective: c/w divided
// by 1/w with the refined reciprocal) and its depth, through the attribute
// interpolator's output rule (README.md, "Triangle setup" and "Colour").
#pragma once

#include "raster/core/triangle_setup.h"
#include "raster/datapath/fixed_point.h"
#include "raster/datapath/reciprocal.h"

namespace tessera::raster {

Rgba8 interpolated_color(const TriangleSetup& setup, int dx, int dy, RecipMethod method);
unorm24 interpolated_depth(const TriangleSetup& setup, int dx, int dy);
// The fog argument (16.16, saturated to 32 bits): the plane's value, or in
// perspective argument/w divided by q with the refined reciprocal.
int32_t interpolated_fog(const TriangleSetup& setup, int dx, int dy, RecipMethod method);

}  // namespace tessera::raster
