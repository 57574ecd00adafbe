// The batch entry point of blend_logic_op.h (batch.h).
#include "raster/datapath/blend_logic_op.h"

namespace tessera::raster {

void blend_logic_op_batch(const BlendState& state, const uint32_t* src, const uint32_t* dst, unsigned count,
                          uint32_t* out, BatchIsa isa) {
  batch_detail::dispatch<BlendKernel>(isa, state, src, dst, count, out);
}

}  // namespace tessera::raster
