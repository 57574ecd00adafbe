// The system/array DMA (README.md): a peripheral whose channels run
// descriptors (in their registers or chained in system memory) that move
// data between system memory, over its own bus-master socket, and CMEM,
// through the array's direct CMEM path (array/cmem_access.h) at its own
// rate, not the host's CIU. One engine thread serves the channels
// round-robin, a descriptor at a time; each descriptor is validated as a
// whole (core/dma_descriptor.h) before a byte moves, and a bad one stops its
// channel with an error code, an interrupt and a warning.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

#include <systemc>

#include <nlohmann/json.hpp>

#include "array/cmem_access.h"
#include "common/bus_master.h"
#include "common/peripheral.h"
#include "common/timed_trace.h"
#include "config/config.h"
#include "dma/core/dma_engine.h"

namespace tessera {

struct DmaParams {
  bool enabled = false;
  bool broadcast = false;  // a renderer switch; the block does not read it
  unsigned channels = 0;
  unsigned burst_beats = 0;
  unsigned cmem_bytes_per_cycle = 0;
  unsigned row_buffer_bytes = 0;
  unsigned burst_bytes = 0;            // set by the SoC: burst_beats words of the bus
  sc_core::sc_time clock_period;       // set by the SoC: the system (bus) clock
  sc_core::sc_time cmem_clock_period;  // set by the SoC: the array clock
  uint64_t memory_base = 0;            // set by the SoC: system memory
  uint64_t memory_bytes = 0;
  // Set by the SoC: a device window a copy may read (dma::Limits), the
  // z-buffer unit's colour plane when zbuf.enabled; 0 bytes: none.
  uint64_t readable_base = 0;
  uint64_t readable_bytes = 0;

  static ParamGroup parameters();
  static DmaParams from_config(const Config& config);
  static DmaParams defaults();
};

class Dma : public Peripheral {
 public:
  SC_HAS_PROCESS(Dma);

  // Registers on `in`, the interrupt on `irq` (Peripheral).
  BusMaster out;  // bus initiator dma

  // The global registers, one member each (dma_regs.def's TESSERA_REG rows);
  // each channel's are in its ChannelRegisters.
#define TESSERA_REGISTER_TABLE "dma/dma_regs.def"
#include "common/register_members.inc"

  Dma(sc_core::sc_module_name name, const DmaParams& params);
  ~Dma() override;

  const DmaParams& params() const {
    return m_params;
  }
  // The array's direct CMEM path; without one, CMEM descriptors fail (no_array).
  void connect_cmem(CmemAccess& cmem);
  // Where the bus's arbitration wait of this initiator is read (cycles of
  // the bus clock so far), for the per-channel bus wait. Optional.
  void set_bus_wait_probe(std::function<uint64_t()> wait_cycles) {
    m_bus_wait_probe = std::move(wait_cycles);
  }

  bool channel_busy(unsigned channel) const {
    return m_channels.at(channel).busy;
  }
  // Notified whenever a channel finishes (done or error).
  const sc_core::sc_event& channel_finished_event() const {
    return m_finished;
  }

  void trace_signals(sc_core::sc_trace_file* file) override;
  // Per channel a track "chN": its chains (from START to the channel's
  // end, the channel's busy time) with their descriptors nested; a
  // descriptor that fills CMEM is a flow to the array's next program.
  void timeline_to(TimelineSink& sink) override;
  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;

 private:
  class Port;
  // One channel's registers (dma_regs.def's TESSERA_CHANNEL_REG rows) at
  // dma_regs::channel_base(c) in the block's bank.
  struct ChannelRegisters {
    ChannelRegisters(RegisterBank& bank, uint32_t base) : bank(bank), base(base) {}
    RegisterBank& bank;
    uint32_t base;
#define TESSERA_REG(name, offset, reset, access)
#define TESSERA_BITS(prefix, name, lsb, width)
#define TESSERA_CHANNEL_REG(name, offset, reset, access) \
  Register name{bank, {#name, base + (offset), reset, RegAccess::access}};
#include "dma/dma_regs.def"
#undef TESSERA_CHANNEL_REG
#undef TESSERA_BITS
#undef TESSERA_REG
  };
  struct Channel {
    std::unique_ptr<ChannelRegisters> registers;
    bool busy = false;
    bool queued = false;
    bool registers_first = false;  // the register descriptor still to run
    uint32_t next = 0;             // the next descriptor in memory
    std::unordered_set<uint32_t> visited;
    bool done = false, error = false, refused = false;
    uint32_t error_code = 0, error_desc = 0;
    uint64_t error_addr = 0;    // up to 33 bits: the last byte of a range past 4 GiB
    sc_core::sc_time ready_at;  // the START's time
    sc_core::sc_time busy_time;
    sc_core::sc_time bus_wait;
    ActivityCounter* descriptors = nullptr;
    ActivityCounter* bytes = nullptr;
    ActivityCounter* errors = nullptr;
    std::unique_ptr<TimedTrace> busy_trace;
    unsigned timeline_track = 0;
  };

  const char* write_refusal(const tlm::tlm_generic_payload& gp) const override;
  // Channel c's register handlers.
  void write_START(unsigned channel, uint32_t value);
  uint32_t read_STATUS(unsigned channel) const;
  uint32_t read_ERROR_CODE(unsigned channel) const {
    return m_channels[channel].error_code;
  }
  uint32_t read_ERROR_DESC(unsigned channel) const {
    return m_channels[channel].error_desc;
  }
  uint32_t read_ERROR_ADDR(unsigned channel) const;
  uint32_t read_ERROR_ADDR_HI(unsigned channel) const;
  uint32_t read_DESCRIPTORS(unsigned channel) const;
  uint32_t read_BYTES(unsigned channel) const;
  void engine();  // SC_THREAD
  // Runs the channel's next descriptor.
  void step(unsigned channel);
  void finish(unsigned channel);
  void fail(unsigned channel, uint32_t descriptor, const dma::Fault& fault);
  dma::Limits limits() const;
  dma::Descriptor register_descriptor(unsigned channel) const;

  DmaParams m_params;
  CmemAccess* m_cmem = nullptr;
  std::function<uint64_t()> m_bus_wait_probe;
  std::vector<Channel> m_channels;
  unsigned m_round_robin = 0;
  sc_core::sc_event m_wake;
  sc_core::sc_event m_finished;
  sc_core::sc_time m_engine_busy;
  sc_core::sc_time m_cmem_stall;
  ActivityCounter& m_cmem_written;
  ActivityCounter& m_cmem_read;
  ActivityCounter& m_cmem_passes;
  ActivityCounter& m_cmem_cycles;
  ActivityCounter& m_cmem_stalls;
  ActivityCounter& m_descriptor_fetches;
  Log2Histogram m_descriptor_bytes;  // each completed descriptor's LENGTH (histograms.descriptor_bytes)
  bool m_tracing = false;
  TimelineSink* m_timeline = nullptr;  // timeline_to: null without a timeline
  std::string m_cmem_flow_key;
};

}  // namespace tessera
