// The system/array DMA's functional core, plain C++ (no SystemC): a
// descriptor's (contract/dma/dma_descriptor.h) validation against system
// memory and CMEM, the reshuffle and broadcast address arithmetic, and
// execute(), which moves one validated descriptor through a DmaPort. The
// SystemC block (dma.h) supplies the port: the bus for memory, the array's
// direct CMEM access for CMEM, with the timing. README.md walks through it.
#pragma once

#include <cstdint>
#include <vector>

#include "dma/dma_descriptor.h"

namespace tessera::dma {

// What a descriptor may address.
struct Limits {
  uint64_t memory_base = 0;
  uint64_t memory_bytes = 0;
  unsigned lanes = 0;       // CUs, 0: no array (CMEM kinds are refused)
  unsigned cmem_bytes = 0;  // per CU
  // A device window a copy (mem_to_mem) may also read, besides memory: the
  // z-buffer unit's colour plane when the SoC has one (tlm/zbuf), so that
  // the frame's colours reach the back buffer without the host. 0 bytes: none.
  uint64_t readable_base = 0;
  uint64_t readable_bytes = 0;
};

// A validation or transfer failure: what and the offending address (or length).
struct Fault {
  Error error = Error::none;
  uint64_t address = 0;
  bool ok() const { return error == Error::none; }
};

// The whole descriptor checked before anything moves: ranges (every byte
// it would read or write), length, alignment, fields. Reserved CTRL bits
// and the words the kind does not use (MASK but for a broadcast,
// SRC_STRIDE of a broadcast, the strides of a copy) must be 0.
Fault validate(const Descriptor& d, const Limits& limits);
// A descriptor's own address in a chain: 4-aligned, its 32 bytes in memory.
Fault validate_descriptor_address(uint32_t address, const Limits& limits);

// The reshuffle arithmetic (mem_to_cmem, cmem_to_mem): element k of the
// plain array is lane k mod lanes, row k / lanes.
struct Reshuffle {
  uint32_t memory = 0;         // plain array
  uint32_t memory_stride = 0;  // between rows (resolved: 0 became lanes x element)
  uint32_t cmem = 0;           // CMEM address of row 0
  uint32_t cmem_stride = 0;    // between rows (resolved: 0 became element)
  unsigned element = 1;
  uint64_t elements = 0;
  unsigned lanes = 0;

  uint64_t rows() const { return (elements + lanes - 1) / lanes; }
  // Elements of row r (lanes except, perhaps, the last row).
  unsigned row_elements(uint64_t r) const;
  uint64_t memory_address(uint64_t k) const { return memory + (k / lanes) * memory_stride + (k % lanes) * element; }
  uint64_t cmem_address(uint64_t k) const { return cmem + (k / lanes) * cmem_stride; }
};
Reshuffle reshuffle_of(const Descriptor& d, unsigned lanes);

// CMEM address of broadcast byte j: dst + j x step (step 0 became 1).
inline uint32_t broadcast_step(const Descriptor& d) {
  return d.dst_stride == 0 ? 1 : d.dst_stride;
}

// The engine's two sides. Memory accesses return false on a bus error.
// CMEM accesses are passes over the CUs' shared data lines.
class DmaPort {
 public:
  virtual ~DmaPort() = default;
  virtual bool read_memory(uint32_t address, uint8_t* data, unsigned bytes) = 0;
  virtual bool write_memory(uint32_t address, const uint8_t* data, unsigned bytes) = 0;
  // Lanes 0..count-1: lane l's element (data[l e .. l e + e), most
  // significant byte first) to / from CMEM address..address+e-1.
  virtual void write_cmem_row(unsigned count, uint32_t address, unsigned element, const uint8_t* data) = 0;
  virtual void read_cmem_row(unsigned count, uint32_t address, unsigned element, uint8_t* data) = 0;
  // Byte j of data to CMEM address + j x step of every lane whose mask bit
  // is set (an empty mask: every lane).
  virtual void broadcast_cmem(const std::vector<uint8_t>& mask, uint32_t address, uint32_t step, const uint8_t* data,
                              unsigned bytes) = 0;
};

// Moves one descriptor that validate() accepted, in rows: a reshuffle row
// is `lanes` elements, a copy or a broadcast moves chunks of at most
// `buffer_bytes` (which must hold a reshuffle row). A copy whose
// destination overlaps its source above it moves its chunks from the last
// to the first, so that overlapping copies give memmove's result. Returns the first
// failed memory access (bus_error) or success; `moved` gets the bytes
// delivered.
Fault execute(const Descriptor& d, const Limits& limits, unsigned buffer_bytes, DmaPort& port, uint64_t& moved);

}  // namespace tessera::dma
