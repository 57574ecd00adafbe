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

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <tlm_utils/multi_passthrough_initiator_socket.h>
#include <systemc>
#include <tlm>

#include <nlohmann/json.hpp>

#include "common/block.h"
#include "common/direct_transport.h"
#include "common/fixed_divider.h"
#include "common/histogram.h"
#include "common/ticks_time.h"
#include "common/timed_trace.h"
#include "common/transaction_trace.h"
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
  class InitiatorPort;

 public:
  tlm_utils::multi_passthrough_initiator_socket<AhbBus, 32> out;  // bound to targets

  AhbBus(sc_core::sc_module_name name, const BusParams& params);
  ~AhbBus() override;

  // Binds an initiator socket to the bus, through a target socket of its
  // own (<bus>.<initiator_name>_in, made and bound before the end of
  // elaboration, inside the bus). Lower priority value = served first under
  // fixed priority. Call in the order initiators should be visited by
  // round-robin, before the simulation starts.
  template <typename Socket>
  void attach(Socket& initiator, const std::string& initiator_name, unsigned priority) {
    add_initiator(initiator_name, priority, [&initiator](tlm::tlm_target_socket<32>& port) { initiator.bind(port); });
  }

  // Binds a target socket to the bus at [base, base + size).
  template <typename Socket>
  void map(Socket& target, uint64_t base, uint64_t size, const std::string& target_name) {
    add_region(base, size, target_name);
    out.bind(target);
  }

  // Traces request and grant of every initiator (call before simulation).
  void trace_signals(sc_core::sc_trace_file* file) override;
  // Hands every transaction from now on to `sink` (common/transaction_trace.h),
  // which outlives the simulation.
  void trace_transactions_to(TransactionSink& sink) {
    m_transactions = &sink;
    m_observed = true;
  }

  const BusParams& params() const { return m_params; }
  const std::vector<BusInitiatorStats>& initiator_stats() const { return m_stats; }
  uint64_t busy_cycles() const { return m_busy_cycles.value; }
  // Bytes moved by every initiator so far.
  uint64_t bytes() const;
  // Statistics as JSON, utilisation computed over `elapsed`.
  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;
  // Traffic per initiator.
  std::vector<SummaryTable> summary_tables(const sc_core::sc_time& elapsed) const override;

 private:
  // Ticks to bus cycles, rounded up, remembering the last conversion: an
  // initiator's next request is usually at the end of its last one, and a
  // target's latency repeats, so most conversions are one comparison.
  struct CycleMemo {
    uint64_t ticks = 0;
    uint64_t cycles = 0;
  };

  struct Region {
    uint64_t base;
    uint64_t size;
    std::string name;
    unsigned target_index;
    mutable CycleMemo latency;  // the target's last latency in cycles
    // The target as a DirectTransport (common/direct_transport.h), or null:
    // found at the end of elaboration.
    DirectTransport* direct = nullptr;
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

  using BindInitiator = std::function<void(tlm::tlm_target_socket<32>&)>;
  void add_initiator(const std::string& name, unsigned priority, BindInitiator bind);
  // Makes every initiator's target socket and binds the initiator to it.
  void before_end_of_elaboration() override;
  void end_of_elaboration() override;
  void add_region(uint64_t base, uint64_t size, const std::string& name);
  // The last two regions decoded are remembered: an initiator alternating
  // between two targets (the host copying a frame from memory to the
  // display port) finds both without a search.
  const Region* decode(uint64_t address) const {
    if (m_last_region && address - m_last_region->base < m_last_region->size) return m_last_region;
    if (m_other_region && address - m_other_region->base < m_other_region->size) {
      std::swap(m_last_region, m_other_region);
      return m_last_region;
    }
    return decode_other(address);
  }
  const Region* decode_other(uint64_t address) const;  // and remembers it

  // An initiator's access through the bus's socket, and through its
  // DirectTransport, whose `extras` carry the payload's train count and
  // its target's "untouched" (DirectExtras). One body (serve), inline in
  // both, so that each door's port is a plain forwarder.
  void b_transport(unsigned initiator, tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  void b_transport(unsigned initiator, tlm::tlm_generic_payload& gp, sc_core::sc_time& delay, DirectExtras& extras);
  // A frame copy as a unit (common/direct_transport.h, CopyPlan).
  bool quote_copy(const CopyPlan& plan, CopyQuote& quote);
  void direct_copy(unsigned initiator, const CopyPlan& plan, const CopyQuote& quote, size_t first_block, size_t blocks,
                   const CopyRequest* requests, uint8_t* data);
  // A posted train as a unit (common/direct_transport.h, PostPlan).
  bool quote_posts(const PostPlan& plan, PostQuote& quote);
  void direct_posts(unsigned initiator, const PostPlan& plan, const PostQuote& quote, size_t first, size_t count,
                    const CopyRequest* requests, const uint8_t* data);
  // Whether a unit's requests are served by reserve() alone: nothing
  // observed or logged, no synchronised request waiting.
  bool units_served() const;
  LastReservation last_reservation() const {
    LastReservation last;
    if (!m_reserved.empty()) last = {true, m_reserved.back().start, m_reserved.back().end};
    return last;
  }
  __attribute__((always_inline)) inline void serve(unsigned initiator, tlm::tlm_generic_payload& gp,
                                                   sc_core::sc_time& delay, DirectExtras& extras);
  // Store trains (common/direct_transport.h): a train of single-word
  // writes quoted and served as serve() would serve its words one by one,
  // where it would only reserve each at its request.
  bool quote_train(unsigned initiator, const WordTrain& train, uint64_t first_ticks, TrainQuote& quote);
  void direct_train(unsigned initiator, const WordTrain& train, const uint64_t* arrivals);
  unsigned transport_dbg(unsigned initiator, tlm::tlm_generic_payload& gp);
  bool get_direct_mem_ptr(unsigned initiator, tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi);
  void invalidate_direct_mem_ptr(int id, sc_dt::uint64 start, sc_dt::uint64 end);

  uint64_t ceil_cycles(uint64_t ticks, CycleMemo& memo) const {
    if (ticks != memo.ticks) memo = {ticks, m_cycles.ceil(ticks)};
    return memo.cycles;
  }
  // `cycles` bus cycles as an sc_time.
  sc_core::sc_time cycles_time(uint64_t cycles) const { return ticks_time(cycles * m_period_ticks); }
  // Whether a synchronised request must wait a delta cycle for the others
  // of its instant (see b_transport).
  bool must_collect() const;

  // Earliest start >= request at which [start, start + length) is free;
  // reserves it. `now`: the kernel's time in ticks. A request at or after
  // the end of every reservation, as almost every one is, is placed
  // without a search.
  uint64_t reserve(uint64_t now, uint64_t request_cycle, uint64_t length_cycles) {
    uint64_t start = request_cycle;
    if (m_reserved.empty() || m_reserved.back().end <= start) {
      // Joins the last interval if that ends where it starts.
      if (!m_reserved.empty() && m_reserved.back().end == start) {
        m_reserved.back().end = start + length_cycles;
      } else {
        if (m_reserved.size() >= m_prune_at) prune(now);
        // Field by field: push_back of an Interval built on the stack had
        // its two words stored apart and loaded as one, which the CPU
        // cannot forward (a stall on the bus's hottest path).
        Interval& added = m_reserved.emplace_back();
        added.start = start;
        added.end = start + length_cycles;
      }
    } else if (request_cycle >= m_reserved.back().start) {
      // Requested while the last reservation runs (a read behind a posted
      // write): it joins that reservation at its end, as reserve_among's
      // search would find (without its pruning, which only drops
      // intervals ended before the kernel's time, that no request reaches).
      start = m_reserved.back().end;
      m_reserved.back().end = start + length_cycles;
    } else {
      start = reserve_among(now, request_cycle, length_cycles);
    }
    m_busy_cycles += length_cycles;
    return start;
  }
  // reserve() for a request before the end of the last reservation: a search.
  uint64_t reserve_among(uint64_t now, uint64_t request_cycle, uint64_t length_cycles);
  // Beats of a train of `transfers` transfers of length / transfers bytes.
  uint64_t train_beats(uint64_t length, unsigned transfers) const;
  // Beats of one transfer of `length` bytes: at least one.
  uint64_t single_beats(uint64_t length) const { return std::max<uint64_t>(1, m_beats.ceil(length)); }
  // Cycles a request of `transfers` transfers holds the bus: an address
  // cycle each, then the target's latency or the beats, whichever is longer.
  uint64_t occupancy(uint64_t target_cycles, uint64_t beats, unsigned transfers = 1) const {
    return transfers * m_params.address_cycles + std::max(target_cycles, beats);
  }
  // Drops the reservations that ended by `now`.
  void prune(uint64_t now);
  void resolve_batch();
  // A synchronised request: joins the batch of this instant and waits a
  // delta cycle for its grant. The start cycle.
  uint64_t collect(unsigned initiator, uint64_t request_cycle, uint64_t occupancy_cycles);
  // The error response to an unmapped address; its occupancy.
  uint64_t unmapped(unsigned initiator, tlm::tlm_generic_payload& gp);
  void trace_grant(unsigned initiator, uint64_t request_cycle, uint64_t start_cycle, uint64_t end_cycle);
  // A transaction served, to the VCD's signals and the transaction sink.
  void observe(unsigned initiator, const tlm::tlm_generic_payload& gp, const Region* region, uint64_t request_cycle,
               uint64_t start_cycle, uint64_t end_cycle);
  void log_grant(unsigned initiator, const tlm::tlm_generic_payload& gp, uint64_t start_cycle,
                 uint64_t occupancy_cycles) const;
  // Bus cycles over which utilisation is computed: `elapsed`, or up to the
  // end of the last granted transfer if that is later.
  double span_cycles(const sc_core::sc_time& elapsed) const;

  BusParams m_params;
  // The kernel's time is read from the context on every access (the
  // sc_time_stamp() function is a call into the SystemC library).
  const sc_core::sc_simcontext* m_context;
  uint64_t m_period_ticks;
  FixedDivider m_cycles;  // ticks to bus cycles
  FixedDivider m_beats;   // bytes to beats
  std::vector<Region> m_regions;
  std::vector<BusInitiatorStats> m_stats;
  // Each initiator's wait cycles per access (stats.json's
  // histograms.wait_cycles), beside m_stats.
  std::vector<Log2Histogram> m_wait_histograms;
  std::vector<BindInitiator> m_binds;  // per initiator, until its socket is made
  std::vector<std::unique_ptr<InitiatorPort>> m_ports;
  // Per initiator: its last request's end, which is where its next request
  // usually is.
  std::vector<CycleMemo> m_request_memo;
  // The reservation timeline: disjoint [start, end) intervals in cycles,
  // sorted. A sorted vector rather than a map: requests arrive nearly in
  // time order, so almost every reservation extends or follows the last
  // interval (which reserve() tries first). Intervals that ended before the
  // kernel's time can no longer be hit (nothing is requested in the past);
  // they are dropped whenever the vector has doubled since the last time,
  // so the cost per reservation does not grow with the simulation's
  // history.
  struct Interval {
    uint64_t start;
    uint64_t end;
  };
  static constexpr size_t PRUNE_AT_LEAST = 64;
  std::vector<Interval> m_reserved;
  size_t m_prune_at = PRUNE_AT_LEAST;
  std::vector<Request*> m_batch;
  std::vector<uint64_t> m_train_arrivals;  // direct_train's words at the target
  unsigned m_last_granted = 0;
  ActivityCounter& m_busy_cycles;
  // The latest end of a reservation dropped from the timeline; with the
  // timeline's last interval, the end of the last granted transfer.
  uint64_t m_pruned_end_cycle = 0;
  mutable const Region* m_last_region = nullptr;
  mutable const Region* m_other_region = nullptr;
  bool m_tracing = false;
  TransactionSink* m_transactions = nullptr;
  // m_tracing or m_transactions: the one test on the hot path for both.
  bool m_observed = false;
  std::vector<std::unique_ptr<TimedTrace>> m_request_traces;
  std::vector<std::unique_ptr<TimedTrace>> m_grant_traces;
};

Arbitration parse_arbitration(const std::string& name);

}  // namespace tessera
