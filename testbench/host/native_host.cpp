#include "host/native_host.h"

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "display/display_regs.h"
#include "soc/memory_map.h"

namespace tessera::bench {

namespace regs = display_regs;

namespace {

bool inside(const memory_map::Region& region, uint32_t address, uint64_t bytes) {
  return address >= region.base && uint64_t{address} - region.base + bytes <= region.size;
}

std::string hex(uint32_t address) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08x", address);
  return text;
}

}  // namespace

NativeHost::NativeHost(uint32_t memory_bytes, const NativeDisplay& display)
    : m_memory(memory_bytes), m_display(display) {}

uint8_t* NativeHost::memory_at(uint32_t address, uint64_t bytes) {
  if (address >= memory_map::sysmem.base && uint64_t{address} - memory_map::sysmem.base + bytes <= m_memory.size())
    return m_memory.data() + (address - memory_map::sysmem.base);
  if (inside(memory_map::display_port, address, bytes)) return nullptr;
  throw BusError("native host: no memory at " + hex(address), address);
}

uint32_t NativeHost::read_display_reg(uint32_t offset) const {
  switch (offset) {
    case regs::WIDTH: return m_display.width;
    case regs::HEIGHT: return m_display.height;
    case regs::FORMAT: return static_cast<uint32_t>(m_display.format);
    case regs::MODE: return m_display.dma ? 1 : 0;
    case regs::IRQ_STATUS: return regs::IRQ_SWAP_DONE | regs::IRQ_FRAME_PRESENTED;
    case regs::FRAMES: return static_cast<uint32_t>(m_present_times.size());
    default: return 0;
  }
}

void NativeHost::write_display_reg(uint32_t offset) {
  if (offset == (m_display.dma ? regs::SWAP : regs::PRESENT)) {
    m_present_times.push_back(Clock::now());
    timespec cpu{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu);
    m_present_cpu_seconds.push_back(static_cast<double>(cpu.tv_sec) + static_cast<double>(cpu.tv_nsec) * 1e-9);
  }
}

uint64_t NativeHost::read(uint32_t address, unsigned bytes) {
  if (inside(memory_map::display_regs, address, bytes))
    return read_display_reg(address - memory_map::display_regs.base);
  const uint8_t* data = memory_at(address, bytes);
  if (!data) throw BusError("native host: the display port is write-only: " + hex(address), address);
  uint64_t value = 0;
  std::memcpy(&value, data, bytes);  // little-endian host, as the ARM
  return value;
}

void NativeHost::write(uint32_t address, uint64_t value, unsigned bytes) {
  if (inside(memory_map::display_regs, address, bytes))
    return write_display_reg(address - memory_map::display_regs.base);
  if (uint8_t* data = memory_at(address, bytes)) std::memcpy(data, &value, bytes);
}

uint32_t NativeHost::read32(uint32_t address) {
  return static_cast<uint32_t>(read(address, 4));
}
uint16_t NativeHost::read16(uint32_t address) {
  return static_cast<uint16_t>(read(address, 2));
}
uint8_t NativeHost::read8(uint32_t address) {
  return static_cast<uint8_t>(read(address, 1));
}
void NativeHost::write32(uint32_t address, uint32_t value) {
  write(address, value, 4);
}
void NativeHost::write16(uint32_t address, uint16_t value) {
  write(address, value, 2);
}
void NativeHost::write8(uint32_t address, uint8_t value) {
  write(address, value, 1);
}

void NativeHost::read_words(uint32_t address, uint32_t* words, unsigned count) {
  const uint8_t* data = memory_at(address, uint64_t{count} * 4);
  if (!data) throw BusError("native host: the display port is write-only: " + hex(address), address);
  std::memcpy(words, data, size_t{count} * 4);
}

void NativeHost::write_words(uint32_t address, const uint32_t* words, unsigned count) {
  if (uint8_t* data = memory_at(address, uint64_t{count} * 4)) std::memcpy(data, words, size_t{count} * 4);
}

const uint8_t* NativeHost::load_span(uint32_t address, unsigned size, unsigned count) {
  return store_span(address, size, count);
}

uint8_t* NativeHost::store_span(uint32_t address, unsigned size, unsigned count) {
  const uint64_t bytes = std::max<uint64_t>(uint64_t{size} * count, 1);
  if (address < memory_map::sysmem.base || uint64_t{address} - memory_map::sysmem.base + bytes > m_memory.size())
    throw std::invalid_argument("native host: span at " + hex(address) + " leaves system memory");
  return m_memory.data() + (address - memory_map::sysmem.base);
}

}  // namespace tessera::bench
