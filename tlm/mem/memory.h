// System memory (SDRAM): a TLM target with a first-access latency and a
// per-beat burst latency in bus cycles, DMI for reads and writes, and debug
// transport. Addresses are offsets into the memory (the bus subtracts the
// region base). An access past the end is an address error.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tlm_utils/simple_target_socket.h>
#include <systemc>
#include <tlm>

#include <nlohmann/json.hpp>

#include "common/block.h"
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

class Memory : public Block {
 public:
  tlm_utils::simple_target_socket<Memory, 32> in;

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
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;

 private:
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  unsigned transport_dbg(tlm::tlm_generic_payload& gp);
  bool get_direct_mem_ptr(tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi);
  // Checks range and attributes; sets the response status on failure.
  bool check(tlm::tlm_generic_payload& gp) const;
  // access_time() in ticks (the time resolution's units): integers only.
  uint64_t access_ticks(uint64_t bytes) const {
    const uint64_t beats = bytes == 0 ? 1 : m_beats.ceil(bytes);
    return m_first_access_ticks + beats * m_beat_ticks;
  }

  MemoryParams m_params;
  std::vector<uint8_t> m_data;
  FixedDivider m_beats;  // bytes to beats (the width)
  uint64_t m_first_access_ticks;
  uint64_t m_beat_ticks;
  sc_core::sc_time m_last_access;  // the time of the access before, kept as an sc_time
  ActivityCounter& m_reads;
  ActivityCounter& m_writes;
  ActivityCounter& m_bytes_read;
  ActivityCounter& m_bytes_written;
  ActivityCounter& m_errors;
  uint64_t m_busy_ticks = 0;
};

}  // namespace tessera
