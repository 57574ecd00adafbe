// How an array back end (ap-tile, ap-pixel) talks to CMEM: through the
// host's CIU accesses (the J2210's way) or through the system/array DMA
// (tlm/dma/README.md) when the SoC has one (dma.enabled=true), with its
// broadcast write when dma.broadcast=true. And the traffic the array's data
// lines carried either way, the study's "values written per triangle".
// Header-only: the back end that uses it links the device drivers.
#pragma once

#include <cstdint>
#include <stdexcept>

#include "config/config.h"
#include "device/app_environment.h"
#include "device/dma_driver.h"

namespace tessera::renderers {

struct DmaUse {
  bool enabled = false;    // the DMA moves the back end's CMEM data
  bool broadcast = false;  // and writes values common to every CU once, by broadcast
};

// The run's configuration says whether the SoC has the DMA (dma.enabled;
// no configuration: it has none) and whether to broadcast (dma.broadcast);
// the DMA's ID register must agree. Without a DMA the back end never
// touches its registers, so its bus traffic is what it was before the DMA.
inline DmaUse dma_use(AppEnvironment& env, DmaDriver& dma) {
  DmaUse use;
  if (env.config == nullptr || !env.config->get_bool("dma.enabled")) return use;
  if (!dma.present())
    throw std::runtime_error("dma.enabled=true, but the DMA's ID register does not read as the DMA's");
  use.enabled = true;
  use.broadcast = env.config->get_bool("dma.broadcast");
  return use;
}

// Bytes the array's data lines carried into and out of CMEM: a CIU word is
// four (one per CU of its group), a reshuffled element byte is one, and a
// broadcast byte is one whatever the number of CUs that latch it.
struct ArrayTraffic {
  uint64_t values_written = 0, values_read = 0;
};

}  // namespace tessera::renderers
