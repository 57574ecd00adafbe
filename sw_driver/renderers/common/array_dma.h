// How an array back end (ap-tile, ap-pixel) talks to CMEM: through the
// host's CIU accesses (the J2210's way) or through the system/array DMA
// (tlm/dma/README.md) when the SoC has one (dma.enabled=true), with its
// broadcast write when dma.broadcast=true. And the traffic the array's data
// lines carried either way, the study's "values written per triangle".
// Header-only: the back end that uses it links the device drivers.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "config/config.h"
#include "device/app_environment.h"
#include "device/dma_driver.h"
#include "renderers/common/host_time.h"

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
// broadcast byte is one whatever the number of CUs that latch it; and the
// DMA descriptors the back end ran (0 through the CIU).
struct ArrayTraffic {
  uint64_t values_written = 0, values_read = 0, dma_descriptors = 0;

  ArrayTraffic& operator+=(const ArrayTraffic& other) {
    values_written += other.values_written;
    values_read += other.values_read;
    dma_descriptors += other.dma_descriptors;
    return *this;
  }
};

// The traffic as counters <prefix>.values_written, values_read, dma_descriptors.
inline void publish_traffic(ActivityCounters& counters, const std::string& prefix, const ArrayTraffic& traffic) {
  counters
      .counter(prefix + ".values_written",
               "bytes the array's data lines carried into CMEM (CIU word 4, reshuffled byte 1, broadcast byte once)")
      .value = traffic.values_written;
  counters
      .counter(prefix + ".values_read",
               "bytes the array's data lines carried out of CMEM (CIU word 4, reshuffled byte 1)")
      .value = traffic.values_read;
  counters.counter(prefix + ".dma_descriptors", "system/array DMA descriptors the back end ran (0 without the DMA)")
      .value = traffic.dma_descriptors;
}

// The traffic's running totals for FrameFigures.
inline void add_traffic(FrameFigures::Figures& totals, const ArrayTraffic& traffic) {
  totals.emplace_back("values_written", static_cast<double>(traffic.values_written));
  totals.emplace_back("values_read", static_cast<double>(traffic.values_read));
  totals.emplace_back("dma_descriptors", static_cast<double>(traffic.dma_descriptors));
}

// This frame's values written per triangle (0 without a triangle), from the
// running totals of triangles (the figure "triangles") and of the traffic,
// before FrameFigures::emit.
inline double values_written_per_triangle(const FrameFigures& figures, uint64_t triangles,
                                          const ArrayTraffic& traffic) {
  const double drawn = figures.change("triangles", static_cast<double>(triangles));
  const double written = figures.change("values_written", static_cast<double>(traffic.values_written));
  return drawn > 0 ? written / drawn : 0.0;
}

}  // namespace tessera::renderers
