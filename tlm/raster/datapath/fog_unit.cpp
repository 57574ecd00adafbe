// See fog_unit.h; the arithmetic is common/fog.h's.
#include "raster/datapath/fog_unit.h"

#include "common/fog.h"

namespace tessera::raster {

FogUnitResult fog_unit(FogMode mode, int32_t argument, Rgba8 fragment, Rgba8 fog_color) {
  FogUnitResult r;
  r.factor = fog_factor(mode, argument);
  r.color = Rgba8::unpack(fog_blend(r.factor, fragment.pack(), fog_color.pack()));
  return r;
}

}  // namespace tessera::raster
