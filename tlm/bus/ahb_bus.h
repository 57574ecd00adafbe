// AHB-style shared bus: several initiators, several targets decoded by
// address range, fixed-priority or round-robin arbitration, bursts of one beat
// per bus word, address and data phases, target wait states, error responses,
// DMI pass-through with invalidation, and debug transport.
//
// Timing (loosely timed, bus clock cycles):
//   request time  = initiator's local time, rounded up to a bus clock edge
//   occupancy     = address_cycles + data phase, where the data phase is the
//                   time the target annotates (its wait states plus one beat
//                   per word), at least one cycle per beat
//   start         = first time at or after the request at which the bus is free
//                   for the whole occupancy (a timeline of reservations, so an
//                   initiator running ahead in its quantum does not block one
//                   that is behind it)
//   wait cycles   = start - request (contention), busy cycles = occupancy
// The access returns with delay = end of occupancy - sc_time_stamp().
//
// Arbitration: requests that arrive at the same simulated time with no local
// time offset (synchronised initiators) are collected for one delta cycle and
// served in the order the policy gives (a request from an initiator ahead
// in time that arrives during that delta cycle serves the collected ones
// first, since they are earlier). Requests from initiators ahead in
// their quantum are served in arrival order at their request times; the
// quantum (sim.quantum_ns) bounds how far that order can differ from the
// hardware's. A quantum of 0 synchronises the host before each of its own
// accesses, but posted writes leaving its write buffer and a DMA's later
// bursts of a line still carry a time offset.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <tlm_utils/multi_passthrough_initiator_socket.h>
#include <tlm_utils/multi_passthrough_target_socket.h>
#include <systemc>
#include <tlm>

#include <nlohmann/json.hpp>

#include "common/block.h"
#include "common/fixed_divider.h"
#include "common/timed_trace.h"
#include "config/config.h"

namespace tessera {

enum class Arbitration { fixed_priority, round_robin };

struct BusParams {
  sc_core::sc_time clock_period;
  Arbitration arbitration = Arbitration::fixed_priority;
  unsigned width_bytes = 0;
  unsigned address_cycles = 0;
  unsigned error_cycles = 0;

  // The parameters this block owns (the one place their defaults live),
  // read back from a configuration that holds them; fields marked "set by the
  // SoC" are other blocks' values and stay zero here.
  static ParamGroup parameters();
  static BusParams from_config(const Config& config);
  // from_config of the defaults alone.
  static BusParams defaults();
};

struct BusInitiatorStats {
  std::string name;
  unsigned priority = 0;
  uint64_t transactions = 0;
  uint64_t reads = 0;
  uint64_t writes = 0;
  uint64_t bytes = 0;
  uint64_t beats = 0;
  uint64_t busy_cycles = 0;
  uint64_t wait_cycles = 0;
  uint64_t errors = 0;
  uint64_t debug_accesses = 0;
  uint64_t dmi_grants = 0;
};

class AhbBus : public Block {
 public:
  tlm_utils::multi_passthrough_target_socket<AhbBus, 32> in;      // initiators bind here
  tlm_utils::multi_passthrough_initiator_socket<AhbBus, 32> out;  // bound to targets

  AhbBus(sc_core::sc_module_name name, const BusParams& params);

  // Binds an initiator socket to the bus. Lower priority value = served
  // first under fixed priority. Call in the order initiators should be
  // visited by round-robin.
  template <typename Socket>
  void attach(Socket& initiator, const std::string& initiator_name, unsigned priority) {
    initiator.bind(in);
    add_initiator(initiator_name, priority);
  }

  // Binds a target socket to the bus at [base, base + size).
  template <typename Socket>
  void map(Socket& target, uint64_t base, uint64_t size, const std::string& target_name) {
    add_region(base, size, target_name);
    out.bind(target);
  }

  // Traces request and grant of every initiator (call before simulation).
  void trace_signals(sc_core::sc_trace_file* file) override;

  const BusParams& params() const { return m_params; }
  const std::vector<BusInitiatorStats>& initiator_stats() const { return m_stats; }
  uint64_t busy_cycles() const { return m_busy_cycles.value; }
  // Bytes moved by every initiator so far.
  uint64_t bytes() const;
  // Statistics as JSON, utilisation computed over `elapsed`.
  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;
  // Traffic per initiator.
  std::vector<SummaryTable> summary_tables(const sc_core::sc_time& elapsed) const override;

 private:
  struct Region {
    uint64_t base;
    uint64_t size;
    std::string name;
    unsigned target_index;
  };
  // Times in bus cycles from time 0 (cycle c is the clock edge at c
  // periods): every request is aligned to an edge and every occupancy is a
  // whole number of cycles, so the timeline needs no finer unit.
  struct Request {
    unsigned initiator;
    uint64_t request_cycle;
    uint64_t occupancy_cycles;
    uint64_t start_cycle = 0;
    bool granted = false;
  };

  void add_initiator(const std::string& name, unsigned priority);
  void add_region(uint64_t base, uint64_t size, const std::string& name);
  const Region* decode(uint64_t address) const {
    if (m_last_region && address - m_last_region->base < m_last_region->size) return m_last_region;
    return decode_other(address);
  }
  const Region* decode_other(uint64_t address) const;  // and remembers it

  void b_transport(int id, tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  unsigned transport_dbg(int id, tlm::tlm_generic_payload& gp);
  bool get_direct_mem_ptr(int id, tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi);
  void invalidate_direct_mem_ptr(int id, sc_dt::uint64 start, sc_dt::uint64 end);

  // Earliest start >= request at which [start, start + length) is free;
  // reserves it. `now`: the kernel's time in ticks.
  uint64_t reserve(uint64_t now, uint64_t request_cycle, uint64_t length_cycles);
  void resolve_batch();
  void account(unsigned initiator, const tlm::tlm_generic_payload& gp, unsigned transfers, uint64_t beats,
               const Request& request);
  // Bus cycles over which utilisation is computed: `elapsed`, or up to the
  // end of the last granted transfer if that is later.
  double span_cycles(const sc_core::sc_time& elapsed) const;

  BusParams m_params;
  uint64_t m_period_ticks;
  FixedDivider m_cycles;  // ticks to bus cycles
  FixedDivider m_beats;   // bytes to beats
  std::vector<Region> m_regions;
  std::vector<BusInitiatorStats> m_stats;
  // The reservation timeline: disjoint [start, end) intervals in cycles,
  // sorted, from m_reserved_head on (the ones before it have ended). A sorted
  // vector rather than a map: requests arrive nearly in time order, so
  // almost every reservation extends or follows the last interval (which
  // reserve() tries first), and the intervals that have ended are dropped
  // as time passes, so the cost does not grow with the simulation's
  // history.
  struct Interval {
    uint64_t start;
    uint64_t end;
  };
  std::vector<Interval> m_reserved;
  size_t m_reserved_head = 0;
  std::vector<Request*> m_batch;
  unsigned m_last_granted = 0;
  ActivityCounter& m_busy_cycles;
  uint64_t m_last_end_cycle = 0;
  mutable const Region* m_last_region = nullptr;
  bool m_tracing = false;
  std::vector<std::unique_ptr<TimedTrace>> m_request_traces;
  std::vector<std::unique_ptr<TimedTrace>> m_grant_traces;
};

Arbitration parse_arbitration(const std::string& name);

}  // namespace tessera
