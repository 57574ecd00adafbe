// The batch entry point of fog_unit.h (batch.h).
#include "raster/datapath/fog_unit.h"

namespace tessera::raster {

void fog_unit_batch(FogMode mode, Rgba8 fog_color, const int32_t* argument, const uint32_t* fragment, unsigned count,
                    const FogBatch& out, BatchIsa isa) {
  batch_detail::dispatch<FogKernel>(isa, mode, fog_color, argument, fragment, count, out);
}

}  // namespace tessera::raster
