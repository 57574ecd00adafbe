// System memory (SDRAM): a TLM target with a first-access latency and a
// per-beat burst latency in bus cycles, DMI for reads and writes, and debug
// transport. Addresses are offsets into the memory (the bus subtracts the
// region base). An access past the end is an address error.
//
// The memory is its own forward interface: its socket calls b_transport
// with one virtual call, where simple_target_socket adds a second hop and a
// member-function pointer (the memory is on every bus access's path), and
// a DirectTransport, which the bus calls without the virtual bases' thunks
// (common/direct_transport.h).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>

#include <systemc>
#include <tlm>

#include <nlohmann/json.hpp>

#include "common/block.h"
#include "common/direct_transport.h"
#include "common/fixed_divider.h"
#include "config/config.h"

namespace tessera {

struct MemoryParams {
  uint64_t size_bytes = 0;
  sc_core::sc_time clock_period;     // set by the SoC: the bus clock
  unsigned width_bytes = 0;          // set by the SoC: one beat moves the bus width
  unsigned first_access_cycles = 0;  // wait states before the first beat
  unsigned beat_cycles = 0;          // cycles per beat

  // The parameters this block owns (the one place their defaults live),
  // read back from a configuration that holds them; fields marked "set by the
  // SoC" are other blocks' values and stay zero here.
  static ParamGroup parameters();
  static MemoryParams from_config(const Config& config);
  // from_config of the defaults alone.
  static MemoryParams defaults();
};

class Memory : public Block, public tlm::tlm_fw_transport_if<>, public DirectTransport {
 public:
  tlm::tlm_target_socket<32> in;

  Memory(sc_core::sc_module_name name, const MemoryParams& params);

  // Revokes every DMI pointer handed out (e.g. before the host model's view of
  // memory changes); initiators get invalidate_direct_mem_ptr.
  void invalidate_dmi();

  uint64_t size() const { return m_data.size(); }
  // Direct view for the testbench (loading programs, checking results).
  uint8_t* data() { return m_data.data(); }
  // Data-phase time of an access of `bytes` bytes.
  sc_core::sc_time access_time(uint64_t bytes) const { return sc_core::sc_time::from_value(access_ticks(bytes)); }

  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;

 private:
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) final;
  // Both doors' access: `transfers` single transfers (TransferTrain).
  void transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay, unsigned transfers);
  void direct_b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay, DirectExtras& extras) override {
    transport(gp, delay, extras.transfers > 0 ? extras.transfers : 1);
  }
  bool quote_accesses(tlm::tlm_command command, uint64_t address, unsigned bytes, size_t count, unsigned transfers,
                      uint64_t& latency_ticks, bool& untouched) override;
  void direct_accesses(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned bytes,
                       size_t count) override;
  unsigned transport_dbg(tlm::tlm_generic_payload& gp) override;
  bool get_direct_mem_ptr(tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi) override;
  // Loosely timed only: a non-blocking call is answered with a command error.
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& phase,
                                     sc_core::sc_time& delay) override;
  // The error response to an access outside the memory or with a streaming
  // width (not supported).
  void refuse(tlm::tlm_generic_payload& gp);
  // The copy of an access with byte enables.
  void move_enabled(tlm::tlm_generic_payload& gp);
  // access_time() in ticks (the time resolution's units): integers only.
  uint64_t access_ticks(uint64_t bytes) const {
    const uint64_t beats = bytes == 0 ? 1 : m_beats.ceil(bytes);
    return m_first_access_ticks + beats * m_beat_ticks;
  }

  // The memory's bytes, zero at the start: from calloc, which takes large
  // sizes from the system's zeroed pages as they are first touched rather
  // than writing zeros over all of it (a 64 MiB SDRAM's zeros were an
  // eighth of the host instructions of a short program's soc_sim run:
  // callgrind, compute_arm.elf).
  struct Bytes {
    struct Free {
      void operator()(uint8_t* p) const { std::free(p); }
    };
    explicit Bytes(uint64_t size);
    uint64_t size() const { return m_size; }
    uint8_t* data() { return m_bytes.get(); }
    const uint8_t* data() const { return m_bytes.get(); }

   private:
    std::unique_ptr<uint8_t, Free> m_bytes;
    uint64_t m_size;
  };

  MemoryParams m_params;
  Bytes m_data;
  FixedDivider m_beats;  // bytes to beats (the width)
  uint64_t m_first_access_ticks;
  uint64_t m_beat_ticks;
  ActivityCounter& m_reads;
  ActivityCounter& m_writes;
  ActivityCounter& m_bytes_read;
  ActivityCounter& m_bytes_written;
  ActivityCounter& m_errors;
  uint64_t m_busy_ticks = 0;
};

}  // namespace tessera
