// The batch entry point of texture_env.h (batch.h).
#include "raster/datapath/texture_env.h"

namespace tessera::raster {

void texture_filter_env_batch(TexEnv mode, const TextureEnvBatchInput& in, unsigned count, const TextureEnvBatch& out,
                              BatchIsa isa) {
  batch_detail::dispatch<TextureEnvKernel>(isa, mode, in, count, out);
}

}  // namespace tessera::raster
