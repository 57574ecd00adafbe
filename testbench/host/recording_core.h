// The host's core side (HostCore) over a RecordingHost's memory, for the
// ISS launcher's tests (tools/soc_sim/launch/iss_launcher.cpp): debug access reads and
// writes that memory, instruction-side fills are counted (and charge
// nothing), no interrupt is ever asserted. With `direct`, fetches read the
// memory directly (HostCore::direct_memory, as the SoC's host gives them
// system memory's DMI); without, the launcher fetches by debug access.
#pragma once

#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "host/host_core.h"
#include "host/recording_host.h"

namespace tessera::test {

// One issue cycle per word the program loaded or stored (what the SoC's host
// charges with host.cycles.load and .store at 1).
inline uint64_t issue_cycles(const RecordingHost& host) {
  uint64_t cycles = 0;
  for (const auto& access : host.log()) {
    using Kind = RecordingHost::Access::Kind;
    if (access.kind == Kind::read || access.kind == Kind::write) ++cycles;
    if (access.kind == Kind::read_words || access.kind == Kind::write_words) cycles += access.count;
  }
  return cycles;
}

class RecordingCore : public tessera::HostCore {
 public:
  explicit RecordingCore(RecordingHost& host, uint32_t direct_bytes = 0) : m_host(host), m_direct_bytes(direct_bytes) {}
  void fetch(uint32_t address, unsigned bytes) override {
    EXPECT_EQ(bytes, 32u);
    EXPECT_EQ(address % 32, 0u);
    ++fetches;
  }
  bool irq_asserted() override { return false; }
  bool fiq_asserted() override { return false; }
  void wait_for_interrupt() override { ADD_FAILURE() << "the test programs do not wait for interrupts"; }
  bool debug_read(uint32_t address, uint8_t* data, unsigned bytes) override {
    std::memcpy(data, m_host.memory(address, bytes), bytes);
    return true;
  }
  bool debug_write(uint32_t address, const uint8_t* data, unsigned bytes) override {
    std::memcpy(m_host.memory(address, bytes), data, bytes);
    return true;
  }
  // As the SoC's host with host.cycles.load and .store at 1: one issue
  // cycle per word loaded or stored.
  uint64_t busy_cycles() const override { return *m_host.words_accessed(); }
  void set_data_cache_control(bool /*enabled*/, bool /*round_robin*/) override {}
  void invalidate_data_cache() override {}
  void invalidate_data_line(uint32_t /*address*/) override {}
  void clean_data_line(uint32_t /*address*/, bool /*invalidate*/) override {}
  void clean_data_index(uint32_t /*index*/, bool /*invalidate*/) override {}
  void drain_write_buffer() override {}
  double stalled_cycles() const override { return 0; }
  uint64_t data_cache_misses() const override { return 0; }
  // No stall and no miss ever: those two stay at 0.
  CounterLocations counter_locations() const override { return {m_host.words_accessed(), &m_zero, 1, &m_zero}; }
  void set_program_statistics(std::function<nlohmann::json()> statistics) override {
    this->statistics = std::move(statistics);
  }
  bool tracing_program() const override { return false; }
  void trace_program(uint32_t /*pc*/, uint32_t /*function*/, uint32_t /*cpsr*/) override {}
  void set_function_names(std::vector<std::string> /*names*/) override {}
  DirectMemory direct_memory(uint32_t address) override {
    ++direct_memory_asked;
    if (address >= m_direct_bytes) return {};
    return {m_host.memory(0, m_direct_bytes), 0, m_direct_bytes};
  }
  void on_direct_memory_invalidated(const std::function<void()>& callback) override { m_invalidated = callback; }
  // As the SoC's memory withdrawing its DMI.
  void invalidate_direct_memory() {
    if (m_invalidated) m_invalidated();
  }
  uint64_t direct_memory_asked = 0;
  uint64_t fetches = 0;
  std::function<nlohmann::json()> statistics;

 private:
  RecordingHost& m_host;
  uint32_t m_direct_bytes;
  const uint64_t m_zero = 0;
  std::function<void()> m_invalidated;
};

}  // namespace tessera::test
