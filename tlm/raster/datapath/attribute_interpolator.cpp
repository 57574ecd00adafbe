// The batch entry point of attribute_interpolator.h (batch.h).
#include "raster/datapath/attribute_interpolator.h"

namespace tessera::raster {

void attribute_batch(const AttributePlane& plane, const int32_t* dx, const int32_t* dy, unsigned count,
                     const AttributeBatch& out, BatchIsa isa) {
  batch_detail::dispatch<AttributeKernel>(isa, plane, dx, dy, count, out);
}

}  // namespace tessera::raster
