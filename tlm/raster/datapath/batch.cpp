// See batch.h.
#include "raster/datapath/batch.h"

namespace tessera::raster {

std::string_view to_string(BatchIsa isa) {
  switch (isa) {
    case BatchIsa::generic: return "x86-64";
    case BatchIsa::avx2: return "x86-64-v3";
    case BatchIsa::avx512: return "x86-64-v4";
  }
  return "unknown";
}

namespace {

BatchIsa detect_batch_isa() {
#if TESSERA_BATCH_VARIANTS
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4")) return BatchIsa::avx512;
  if (__builtin_cpu_supports("x86-64-v3")) return BatchIsa::avx2;
#endif
  return BatchIsa::generic;
}

}  // namespace

BatchIsa best_batch_isa() {
  static const BatchIsa best = detect_batch_isa();
  return best;
}

const std::vector<BatchIsa>& runnable_batch_isas() {
  static const std::vector<BatchIsa> isas = [] {
    std::vector<BatchIsa> all;
    for (BatchIsa isa : {BatchIsa::generic, BatchIsa::avx2, BatchIsa::avx512})
      if (isa <= best_batch_isa()) all.push_back(isa);
    return all;
  }();
  return isas;
}

}  // namespace tessera::raster
