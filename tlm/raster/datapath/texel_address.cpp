// The batch entry point of texel_address.h (batch.h).
#include "raster/datapath/texel_address.h"

namespace tessera::raster {

void texel_lookup_batch(const TextureState& state, const int32_t* s, const int32_t* t, unsigned count,
                        const TexelBatch& out, BatchIsa isa) {
  batch_detail::dispatch<TexelKernel>(isa, state, s, t, count, out);
}

}  // namespace tessera::raster
