// Fuzz target: the system/array DMA's descriptor chains against the core's
// validation (tlm/dma/core): a register descriptor and a chain in memory,
// walked as the block walks them (dma.cpp): each descriptor's address
// checked, a loop refused, the descriptor validated, and only then moved
// through a port that checks every access.
//
// Input: an 8-byte header -- lanes (0: no array), CMEM bytes per CU, the
// memory's base address, the row buffer, whether the chain runs without
// the register descriptor -- then the register descriptor's 32 bytes, then
// the memory image (at most 4 KiB; shorter inputs give a smaller memory).
//
// Checks: a validated descriptor reads and writes only memory inside the
// memory and CMEM inside each CU's, of lanes that exist; it moves exactly
// LENGTH bytes; a mem_to_mem copy leaves memory as memmove would, even
// when source and destination overlap; a refused descriptor moves nothing;
// a chain ends (a descriptor met twice is chain_loop).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_set>
#include <vector>

#include "dma/core/dma_engine.h"
#include "fuzz_support.h"

namespace {

using namespace tessera::dma;
using tessera::fuzz::ByteReader;
using tessera::fuzz::fail;

constexpr size_t MAX_MEMORY = 4096;
// What the header's bytes pick from: CUs (0: no array), CMEM bytes per CU,
// the memory's base address.
constexpr unsigned LANES[] = {0, 1, 8, 24, 96};
constexpr unsigned CMEM[] = {16, 64, 4096};
constexpr uint64_t BASES[] = {0, 0x1000, 0xFFFFF000u};

struct CheckingPort : DmaPort {
  uint64_t base = 0;
  std::vector<uint8_t> memory;
  unsigned lanes = 0, cmem_bytes = 0;
  std::vector<std::vector<uint8_t>> cmem;
  uint64_t accesses = 0;

  uint8_t* at(uint32_t address, unsigned bytes) {
    ++accesses;
    if (address < base || uint64_t{address} + bytes > base + memory.size())
      fail("a validated descriptor reached memory outside it at " + std::to_string(address) + " (" +
           std::to_string(bytes) + " bytes)");
    return memory.data() + (address - base);
  }
  void check_cmem(unsigned count, uint64_t last) {
    ++accesses;
    if (count > lanes) fail("a CMEM pass over " + std::to_string(count) + " of " + std::to_string(lanes) + " lanes");
    if (last >= cmem_bytes) fail("a validated descriptor reached CMEM address " + std::to_string(last));
  }
  bool read_memory(uint32_t address, uint8_t* data, unsigned bytes) override {
    std::memcpy(data, at(address, bytes), bytes);
    return true;
  }
  bool write_memory(uint32_t address, const uint8_t* data, unsigned bytes) override {
    std::memcpy(at(address, bytes), data, bytes);
    return true;
  }
  void write_cmem_row(unsigned count, uint32_t address, unsigned element, const uint8_t* data) override {
    check_cmem(count, uint64_t{address} + element - 1);
    for (unsigned l = 0; l < count; ++l) std::memcpy(&cmem[l][address], data + l * element, element);
  }
  void read_cmem_row(unsigned count, uint32_t address, unsigned element, uint8_t* data) override {
    check_cmem(count, uint64_t{address} + element - 1);
    for (unsigned l = 0; l < count; ++l) std::memcpy(data + l * element, &cmem[l][address], element);
  }
  void broadcast_cmem(const std::vector<uint8_t>& mask, uint32_t address, uint32_t step, const uint8_t* data,
                      unsigned bytes) override {
    check_cmem(lanes, uint64_t{address} + uint64_t{bytes - 1} * step);
    if (!mask.empty() && mask.size() != mask_bytes(lanes)) fail("a mask of the wrong size");
    for (unsigned l = 0; l < lanes; ++l)
      if (mask.empty() || ((mask[l / 8] >> (l % 8)) & 1) != 0)
        for (unsigned j = 0; j < bytes; ++j) cmem[l][address + j * step] = data[j];
  }
};

// One descriptor: validated, then moved and checked.
void run_one(const Descriptor& d, const Limits& limits, unsigned buffer, CheckingPort& port) {
  const Fault fault = validate(d, limits);
  if (!fault.ok()) return;  // refused: nothing moves (the port is not called)
  std::vector<uint8_t> expected;
  if (d.kind() == Kind::mem_to_mem) {
    expected = port.memory;
    std::memmove(expected.data() + (d.dst - port.base), expected.data() + (d.src - port.base), d.length);
  }
  uint64_t moved = 0;
  const Fault done = execute(d, limits, buffer, port, moved);
  if (!done.ok()) fail(std::string("a validated descriptor failed: ") + error_text(done.error));
  if (moved != d.length) fail("moved " + std::to_string(moved) + " of " + std::to_string(d.length) + " bytes");
  if (d.kind() == Kind::mem_to_mem && port.memory != expected) fail("a copy that is not memmove's");
}

}  // namespace

// NOLINTNEXTLINE(readability-identifier-naming): the name libFuzzer calls
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ByteReader in(data, size);
  CheckingPort port;
  port.lanes = LANES[in.pick(5)];
  port.cmem_bytes = port.lanes == 0 ? 0 : CMEM[in.pick(3)];
  port.base = BASES[in.pick(3)];
  // The row buffer holds a reshuffle row (a configuration error otherwise).
  const unsigned buffer = std::max<unsigned>(16u << in.pick(6), 2 * port.lanes);
  const bool chain_only = in.boolean();
  in.u8(), in.u8(), in.u8();  // reserved: the header is 8 bytes
  uint8_t registers[DESCRIPTOR_BYTES];
  for (uint8_t& byte : registers) byte = in.u8();
  const size_t memory_bytes = std::max<size_t>(DESCRIPTOR_BYTES, std::min(in.remaining(), MAX_MEMORY)) & ~size_t{3};
  port.memory.assign(memory_bytes, 0);
  for (uint8_t& byte : port.memory) byte = in.u8();
  port.cmem.assign(port.lanes, std::vector<uint8_t>(port.cmem_bytes, 0));
  const Limits limits{port.base, port.memory.size(), port.lanes, port.cmem_bytes};

  Descriptor d = decode_bytes(registers);
  uint32_t next = d.next;
  if (!chain_only) {
    run_one(d, limits, buffer, port);
    if (!validate(d, limits).ok()) return 0;  // the channel stops at a refused descriptor
  }
  std::unordered_set<uint32_t> visited;
  while (next != 0) {
    if (!validate_descriptor_address(next, limits).ok()) return 0;
    if (!visited.insert(next).second) return 0;  // chain_loop
    if (visited.size() > port.memory.size() / 4) fail("a chain longer than memory has descriptor addresses");
    d = decode_bytes(port.at(next, DESCRIPTOR_BYTES));
    next = d.next;
    if (!validate(d, limits).ok()) return 0;
    run_one(d, limits, buffer, port);
  }
  return 0;
}
