// The batch entry point of edge_function.h (batch.h).
#include "raster/datapath/edge_function.h"

namespace tessera::raster {

q10_4 edge_span(const Edge& e, unsigned px, unsigned py, unsigned count, q5_16 recip, const EdgeSpan& out,
                BatchIsa isa) {
  batch_detail::dispatch<EdgeSpanKernel>(isa, e, px, py, count, recip, out);
  return edge_l1_length(e);
}

}  // namespace tessera::raster
