// The batch entry point of fragment_tests.h (batch.h).
#include "raster/datapath/fragment_tests.h"

namespace tessera::raster {

void run_fragment_tests_batch(const FragmentTestState& state, const FragmentTestBatchInput& in, unsigned count,
                              const FragmentTestBatch& out, BatchIsa isa) {
  batch_detail::dispatch<FragmentTestKernel>(isa, state, in, count, out);
}

}  // namespace tessera::raster
