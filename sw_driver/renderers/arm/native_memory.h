// A PixelMemory over a plain byte array: the arm core running natively, with
// no time. It charges nothing but counts what the core declares (calls,
// elements and bytes loaded and stored, units of each row of the cost table), so tests and
// tools can see the work a frame takes without the host model.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "renderers/arm/pixel_memory.h"

namespace tessera::arm {

class NativeMemory : public PixelMemory {
 public:
  struct Counters {
    uint64_t load_calls = 0, load_elements = 0, load_bytes = 0;
    uint64_t store_calls = 0, store_elements = 0, store_bytes = 0;
    std::array<uint64_t, costs::HOST_COST_COUNT> units{};  // per row of the cost table
  };

  // An address space of `size` bytes starting at address `base`, zeroed.
  explicit NativeMemory(size_t size, uint32_t base = 0);

  // Throw std::out_of_range when the declared access leaves the address space.
  const uint8_t* load(uint32_t address, unsigned size, unsigned count) override;
  uint8_t* store(uint32_t address, unsigned size, unsigned count) override;
  void charge(HostCost cost, uint64_t units) override;

  // Direct access for set-up and inspection: not counted.
  uint8_t* at(uint32_t address, size_t bytes = 1);
  uint32_t base() const { return m_base; }
  size_t size() const { return m_bytes.size(); }

  const Counters& counters() const { return m_counters; }
  uint64_t units(HostCost cost) const { return m_counters.units[static_cast<size_t>(cost)]; }
  void reset_counters() { m_counters = {}; }

 private:
  uint8_t* checked(uint32_t address, uint64_t bytes);

  uint32_t m_base;
  std::vector<uint8_t> m_bytes;
  Counters m_counters;
};

}  // namespace tessera::arm
