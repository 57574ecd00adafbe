// The batch entry point of texture_combiner.h (batch.h).
#include "raster/datapath/texture_combiner.h"

namespace tessera::raster {

void texture_combiner_batch(const TextureUnitEnv& unit, const uint32_t* primary, const uint32_t* previous,
                            const uint32_t* texel, unsigned count, uint32_t* out, BatchIsa isa) {
  batch_detail::dispatch<TextureCombinerKernel>(isa, unit, primary, previous, texel, count, out);
}

}  // namespace tessera::raster
