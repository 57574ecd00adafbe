// A HostApi that runs the software natively and charges nothing: the same
// GL front end, driver and arm renderer as on the simulated SoC, with system
// memory a plain byte array and no cost model, cache or bus. It answers the
// display controller's geometry registers so that the display driver sets
// itself up as it does on the SoC, discards what is written to the display
// port, and notes the wall-clock time of every frame presented.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include "common/pixel_format.h"
#include "host/host_api.h"

namespace tessera::bench {

struct NativeDisplay {
  unsigned width = 320;
  unsigned height = 240;
  PixelFormat format = PixelFormat::rgb565;
  bool dma = false;
};

class NativeHost : public HostApi {
 public:
  using Clock = std::chrono::steady_clock;

  NativeHost(uint32_t memory_bytes, const NativeDisplay& display);

  void compute(Op, uint64_t) override {}
  void compute_cycles(uint64_t) override {}

  uint32_t read32(uint32_t address) override;
  uint16_t read16(uint32_t address) override;
  uint8_t read8(uint32_t address) override;
  void write32(uint32_t address, uint32_t value) override;
  void write16(uint32_t address, uint16_t value) override;
  void write8(uint32_t address, uint8_t value) override;
  void read_words(uint32_t address, uint32_t* words, unsigned count) override;
  void write_words(uint32_t address, const uint32_t* words, unsigned count) override;

  const uint8_t* load_span(uint32_t address, unsigned size, unsigned count) override;
  uint8_t* store_span(uint32_t address, unsigned size, unsigned count) override;

  // Nothing is simulated: an interrupt the driver waits for (display swap
  // done) has always happened already.
  void wait_irq(unsigned) override {}
  bool irq_pending(unsigned) override { return true; }

  // No simulated time passes on this host.
  double now_seconds() const override { return 0.0; }
  double clock_hz() const override { return 0.0; }

  // When each frame was handed to the display (PRESENT in port mode, SWAP
  // in DMA mode), in order.
  const std::vector<Clock::time_point>& present_times() const { return m_present_times; }
  // The process's CPU time (seconds) at each of them: what a loaded
  // machine does not inflate.
  const std::vector<double>& present_cpu_seconds() const { return m_present_cpu_seconds; }

 private:
  // Where `bytes` bytes at `address` live: system memory, or nullptr for the
  // display port (writes vanish). Anything else is a BusError.
  uint8_t* memory_at(uint32_t address, uint64_t bytes);
  uint32_t read_display_reg(uint32_t offset) const;
  void write_display_reg(uint32_t offset);
  uint64_t read(uint32_t address, unsigned bytes);
  void write(uint32_t address, uint64_t value, unsigned bytes);

  std::vector<uint8_t> m_memory;
  NativeDisplay m_display;
  std::vector<Clock::time_point> m_present_times;
  std::vector<double> m_present_cpu_seconds;
};

}  // namespace tessera::bench
