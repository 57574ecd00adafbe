// How the arm renderer's core reaches its buffers and textures. The same
// core runs natively (plain arrays, no time) and on the host model, where
// every load and store it declares is charged through the data cache, the
// write buffer and the bus. Accesses are declared per span of consecutive
// elements so that the simulated version can account for them per cache
// line instead of per element.
#pragma once

#include <cstdint>

#include "costs/host_cost.h"
#include "host/host_api.h"

namespace tessera::arm {

using costs::HostCost;

class PixelMemory {
 public:
  virtual ~PixelMemory() = default;
  // `count` loads of `size` bytes each at consecutive addresses from
  // `address`; returns a pointer to the first element's bytes in memory,
  // valid until the next call.
  virtual const uint8_t* load(uint32_t address, unsigned size, unsigned count) = 0;
  // `count` stores of `size` bytes each, consecutive from `address`;
  // returns where the caller writes them (valid until the next call).
  virtual uint8_t* store(uint32_t address, unsigned size, unsigned count) = 0;
  // Charges `units` of a row of the host's measured cost table.
  virtual void charge(HostCost cost, uint64_t units = 1) = 0;
};

}  // namespace tessera::arm
