// The batch entry point of attribute_interpolator.h (batch.h).
#include "raster/datapath/attribute_interpolator.h"

namespace tessera::raster {

void attribute_span(const AttributePlane& plane, int dx, int dy, unsigned count, const AttributeSpan& out,
                    BatchIsa isa) {
  batch_detail::dispatch<AttributeSpanKernel>(isa, plane, dx, dy, count, out);
}

}  // namespace tessera::raster
