// Driver of the system/array DMA (tlm/dma/README.md): builds descriptors,
// writes chains into system memory, starts channels and waits for them.
// Every register access is a bus transaction of the host model. The DMA is
// in the SoC only with dma.enabled=true (present() says so).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "device/app_environment.h"
#include "dma/dma_descriptor.h"

namespace tessera {

// A channel that stopped with an error: the DMA's code, the descriptor's
// address (0xFFFFFFFF: the registers) and the offending address.
class DmaError : public std::runtime_error {
 public:
  DmaError(const std::string& what, uint32_t code, uint32_t descriptor, uint64_t address)
      : std::runtime_error(what), m_code(code), m_descriptor(descriptor), m_address(address) {}
  uint32_t code() const { return m_code; }
  uint32_t descriptor() const { return m_descriptor; }
  // ERROR_ADDR_HI:ERROR_ADDR, up to 33 bits.
  uint64_t address() const { return m_address; }

 private:
  uint32_t m_code, m_descriptor;
  uint64_t m_address;
};

class DmaDriver {
 public:
  explicit DmaDriver(AppEnvironment& env);

  // Reads the ID register: false when the SoC has no DMA (dma.enabled=false).
  bool present();
  unsigned channels();

  // Descriptor builders (README.md, "The descriptor").
  // `count` values of `element_bytes` (1 or 2), one per CU in CU order, from
  // the plain array at `src` (the host's little-endian values) to CMEM address `cmem` (high byte first).
  static dma::Descriptor to_cmem(uint32_t src, uint32_t cmem, unsigned count, unsigned element_bytes);
  // The reverse: CMEM address `cmem` of each CU out to a plain array at `dst`.
  static dma::Descriptor from_cmem(uint32_t cmem, uint32_t dst, unsigned count, unsigned element_bytes);
  static dma::Descriptor copy(uint32_t src, uint32_t dst, uint32_t bytes);
  // `bytes` at `src` to CMEM address `cmem`.. of every CU (mask 0) or of the
  // CUs whose bit is set in the mask at `mask` (ceil(CUs / 8) bytes).
  static dma::Descriptor broadcast(uint32_t src, uint32_t cmem, uint32_t bytes, uint32_t mask = 0);

  // Links the descriptors (each one's next is the following one's address,
  // the last 0) and writes them at `address` (32 bytes each, 4-aligned).
  void write_chain(uint32_t address, std::vector<dma::Descriptor> descriptors);
  // Runs one descriptor from the channel's registers (its next, if any, continues in memory).
  void start(unsigned channel, const dma::Descriptor& descriptor);
  // Runs the chain written at `address`.
  void start_chain(unsigned channel, uint32_t address);
  // Sleeps until the channel's interrupt (done or error), clears it;
  // throws DmaError when the channel stopped with an error. Other
  // channels' interrupts seen meanwhile are acknowledged and kept for
  // their own wait().
  void wait(unsigned channel);
  // Polls STATUS instead of sleeping.
  void poll(unsigned channel);
  bool busy(unsigned channel);

 private:
  void finish(unsigned channel);
  void enable_irq(unsigned channel);

  HostApi& m_host;
  uint32_t m_enabled = 0;
  uint32_t m_latched = 0;  // interrupts acknowledged but not yet waited for
};

}  // namespace tessera
