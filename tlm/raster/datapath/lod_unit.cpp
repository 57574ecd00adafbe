// The batch entry point of lod_unit.h (batch.h).
#include "raster/datapath/lod_unit.h"

namespace tessera::raster {

void lod_unit_batch(TexFilter min_filter, TexFilter mag_filter, TexMipmap mipmap, unsigned last_level,
                    const uint32_t* rho, unsigned count, const LodBatch& out, BatchIsa isa) {
  batch_detail::dispatch<LodKernel>(isa, min_filter, mag_filter, mipmap, last_level, rho, count, out);
}

}  // namespace tessera::raster
