#include "renderers/arm/native_memory.h"

#include <cinttypes>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace tessera::arm {

NativeMemory::NativeMemory(size_t size, uint32_t base) : m_base(base), m_bytes(size, 0) {}

uint8_t* NativeMemory::checked(uint32_t address, uint64_t bytes) {
  const uint64_t offset = uint64_t(address) - m_base;
  if (address < m_base || offset + bytes > m_bytes.size()) {
    throw std::out_of_range("NativeMemory: access of " + std::to_string(bytes) + " bytes at 0x" + [&] {
      char text[16];
      std::snprintf(text, sizeof text, "%08" PRIx32, address);
      return std::string(text);
    }() + " is outside the address space");
  }
  return m_bytes.data() + offset;
}

const uint8_t* NativeMemory::load(uint32_t address, unsigned size, unsigned count) {
  ++m_counters.load_calls;
  m_counters.load_elements += count;
  m_counters.load_bytes += uint64_t(size) * count;
  return checked(address, uint64_t(size) * count);
}

uint8_t* NativeMemory::store(uint32_t address, unsigned size, unsigned count) {
  ++m_counters.store_calls;
  m_counters.store_elements += count;
  m_counters.store_bytes += uint64_t(size) * count;
  return checked(address, uint64_t(size) * count);
}

void NativeMemory::charge(HostCost cost, uint64_t units) {
  const auto index = static_cast<size_t>(cost);
  if (index < m_counters.units.size()) m_counters.units[index] += units;
}

uint8_t* NativeMemory::at(uint32_t address, size_t bytes) {
  return checked(address, bytes);
}

}  // namespace tessera::arm
