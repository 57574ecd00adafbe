// The ARM922T host: runs application and driver code (host-compiled C++) in
// an SC_THREAD and charges its time by a cost model in ARM cycles per
// operation class, through a TLM-2.0 quantum keeper. Loads and stores go
// through a tag model of the data cache (system memory is cacheable, devices
// are not) and a posted-write buffer; misses, write-buffer drains and device
// accesses are real bus transactions, so the host sees contention and its
// traffic is measured. Cache hits read and write memory through DMI.
//
// Time is split into busy (executing), stalled (waiting on the bus: line
// fills, full write buffer, device reads) and idle (waiting for an interrupt
// or finished).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/tlm_quantumkeeper.h>
#include <systemc>
#include <tlm>

#include <nlohmann/json.hpp>

#include "common/block.h"
#include "common/direct_transport.h"
#include "common/schedule_untouched.h"
#include "common/timed_trace.h"
#include "common/transfer_train.h"
#include "config/config.h"
#include "host/data_cache.h"
#include "host/host_api.h"
#include "host/host_core.h"

namespace tessera {

struct HostParams {
  sc_core::sc_time clock_period;
  std::array<unsigned, static_cast<size_t>(Op::count_)> op_cycles{};  // per Op
  unsigned load_cycles = 0;
  unsigned store_cycles = 0;
  unsigned dcache_bytes = 0;
  unsigned dcache_line_bytes = 0;
  unsigned dcache_ways = 0;
  // host.dcache.replacement: round-robin (true) or pseudo-random. With
  // host.model=iss the program's CP15 RR bit decides instead.
  bool dcache_round_robin = true;
  // host.dcache.write_policy of the cacheable range: write-through (true) or
  // write-back, as the ARM922T's page tables' C and B bits would say.
  bool write_through = false;
  unsigned write_buffer_words = 0;
  unsigned write_buffer_addresses = 0;
  unsigned irq_lines = 0;
  bool iss = false;  // host.model=iss: the software is an ARM executable on the ISS
  // Cacheable address range (set by the SoC: system memory).
  uint32_t cacheable_base = 0;
  uint32_t cacheable_size = 0;
  // How far past the kernel's time the host may run on when its quantum is
  // used up but no other process has anything scheduled within that window
  // (zero: always synchronise at the quantum). Set by the SoC, which owns
  // the simulation's timing policy (sim.quantum_ns, sim.run_ahead_us).
  sc_core::sc_time run_ahead = sc_core::SC_ZERO_TIME;

  // The parameters this block owns (the one place their defaults live),
  // read back from a configuration that holds them; fields marked "set by the
  // SoC" are other blocks' values and stay zero here.
  static ParamGroup parameters();
  static HostParams from_config(const Config& config);
  // from_config of the defaults alone.
  static HostParams defaults();
};

class Host : public Block, public HostApi, public HostCore {
 public:
  SC_HAS_PROCESS(Host);

  using Program = std::function<int(HostApi&)>;

  tlm_utils::simple_initiator_socket<Host, 32> out;
  sc_core::sc_vector<sc_core::sc_in<bool>> irq;
  // The core's own interrupt inputs, from the interrupt controller: what
  // the ISS takes IRQ and FIQ exceptions on and wakes from a wait for
  // interrupt by. Bound with host.model=iss only (the host-compiled model
  // waits on the lines themselves); unbound, they read as low.
  using OptionalInput = sc_core::sc_port<sc_core::sc_signal_in_if<bool>, 1, sc_core::SC_ZERO_OR_MORE_BOUND>;
  OptionalInput core_irq;
  OptionalInput core_fiq;

  Host(sc_core::sc_module_name name, const HostParams& params);

  void set_program(Program program) { m_program = std::move(program); }
  // Called (in simulation) when the program returns or fails.
  void on_finish(std::function<void()> callback) { m_on_finish = std::move(callback); }
  bool finished() const { return m_finished; }
  const HostParams& params() const { return m_params; }
  int exit_code() const { return m_exit_code; }
  const std::string& failure() const { return m_failure; }

  void trace_signals(sc_core::sc_trace_file* file) override;
  // Track "activity": the time between waits for an interrupt in slices
  // "running" of at least TIMELINE_SLICE (cut where one ends), each with
  // its busy and stalled time (busy_ns, stalled_ns), or at detail all
  // "busy" and "stalled" apart; and the waits, "waiting for interrupt".
  // Track "driver phase" (host-compiled model only): the GL driver's phases
  // (sw_driver/gl/frame_phases.h), each from the switch to it to the next.
  void timeline_to(TimelineSink& sink) override;
  void finish_timeline() override;
  void driver_phase(const char* phase) override;
  // Track "driver calls" (detail all, host-compiled model only): each GL
  // call the application made, from its entry to its return.
  void driver_call(const char* name, bool begins) override;
  static constexpr double TIMELINE_SLICE_US = 1000;
  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;
  sc_core::sc_time busy_time() const { return m_params.clock_period * static_cast<double>(m_busy_cycles.value); }
  // For the power trace, whose windows end at the kernel's time while the
  // host may have charged cycles beyond it (a long computation charged at
  // once, a quantum run ahead): from now on energy_activity(now) counts only
  // the busy and stalled time before `now`, so each window holds the energy
  // spent in it. Off by default: the frames' and the run's energies are
  // taken where the host's time and the kernel's agree.
  void attribute_activity_in_time() {
    m_attribute_in_time = m_note_segments = true;
    m_hit_lines.revoke_all();
  }
  // Whether store trains, frame copies and posted trains may be taken in
  // closed form (README.md: "Store trains", "The frame copy", "Posted
  // trains"; on by default): off, every one goes by the calls, which give
  // the same times, figures and bytes (the tests compare the two).
  void take_units(bool on) { m_take_units = on; }
  sc_core::sc_time stall_time() const { return sc_core::sc_time::from_value(m_stall_ticks); }
  sc_core::sc_time idle_time() const { return sc_core::sc_time::from_value(m_idle_ticks); }

  // HostApi
  void compute(Op op, uint64_t count = 1) override;
  void compute_cycles(uint64_t cycles) override;
  uint32_t read32(uint32_t address) override;
  uint16_t read16(uint32_t address) override;
  uint8_t read8(uint32_t address) override;
  void write32(uint32_t address, uint32_t value) override;
  void write16(uint32_t address, uint16_t value) override;
  void write8(uint32_t address, uint8_t value) override;
  void read_words(uint32_t address, uint32_t* words, unsigned count) override;
  void write_words(uint32_t address, const uint32_t* words, unsigned count) override;
  void write32_train(uint32_t address, uint32_t stride, const uint32_t* values, const uint64_t* cycles,
                     unsigned count) override;
  const uint8_t* load_span(uint32_t address, unsigned size, unsigned count) override;
  uint8_t* store_span(uint32_t address, unsigned size, unsigned count) override;
  void copy_words(uint32_t to, uint32_t from, uint32_t words, const uint64_t* cycles) override;
  void wait_irq(unsigned line) override;
  bool irq_pending(unsigned line) override;
  double now_seconds() const override;
  double clock_hz() const override { return 1.0 / m_params.clock_period.to_seconds(); }
  uint64_t now_cycles() const override { return local_ticks() / m_period_ticks; }

  // HostCore
  void fetch(uint32_t address, unsigned bytes) override;
  bool irq_asserted() override { return core_irq.size() != 0 && core_irq->read(); }
  bool fiq_asserted() override { return core_fiq.size() != 0 && core_fiq->read(); }
  void wait_for_interrupt() override;
  bool debug_read(uint32_t address, uint8_t* data, unsigned bytes) override;
  bool debug_write(uint32_t address, const uint8_t* data, unsigned bytes) override;
  uint64_t busy_cycles() const override { return m_busy_cycles.value; }
  double stalled_cycles() const override {
    return static_cast<double>(m_stall_ticks) / static_cast<double>(m_period_ticks);
  }
  uint64_t data_cache_misses() const override { return m_dcache.misses(); }
  CounterLocations counter_locations() const override {
    return {&m_busy_cycles.value, &m_stall_ticks, m_period_ticks, m_dcache.misses_location()};
  }
  DataHitLines* data_hit_lines() override;
  void set_data_cache_control(bool enabled, bool round_robin) override;
  void invalidate_data_cache() override { m_dcache.invalidate_all(); }
  void invalidate_data_line(uint32_t address) override { m_dcache.invalidate_line(address); }
  void clean_data_line(uint32_t address, bool invalidate) override;
  void clean_data_index(uint32_t index, bool invalidate) override;
  void drain_write_buffer() override;
  void set_program_statistics(std::function<nlohmann::json()> statistics) override {
    m_program_statistics = std::move(statistics);
  }
  bool tracing_program() const override { return m_tracing && m_pc_trace != nullptr; }
  void trace_program(uint32_t pc, uint32_t function, uint32_t cpsr) override;
  void set_function_names(std::vector<std::string> names) override { m_function_names = std::move(names); }
  bool profiling_program() const override { return m_profiling; }
  // soc_sim --iss-profile (HostCore::profiling_program); before the program starts.
  void set_profiling_program(bool profiling) { m_profiling = profiling; }
  DirectMemory direct_memory(uint32_t address) override;
  void on_direct_memory_invalidated(const std::function<void()>& callback) override {
    m_direct_memory_invalidated = callback;
  }
  const std::vector<std::string>& function_names() const { return m_function_names; }

 private:
  void run();
  // The kernel's time in ticks: sc_simcontext::time_stamp() is inline,
  // sc_time_stamp() a call into the SystemC library.
  uint64_t kernel_ticks() const { return m_context->time_stamp().value(); }
  uint64_t local_ticks() const { return kernel_ticks() + m_local_ticks; }
  // Adds busy cycles; the hot path is an addition and a compare in ticks.
  void charge(uint64_t cycles) {
    if (m_note_segments) note_segment(true, local_ticks(), local_ticks() + cycles * m_period_ticks);
    m_busy_cycles += cycles;
    m_local_ticks += cycles * m_period_ticks;
    if (m_local_ticks >= m_budget_ticks) quantum_used_up();
  }
  void stall_until(uint64_t absolute_ticks);
  bool cacheable(uint32_t address, unsigned bytes) const {
    return address >= m_params.cacheable_base && uint64_t{address} + bytes <= m_cacheable_end;
  }
  // Whether an access is looked up in the data cache: cacheable, and the
  // cache present and on (CP15's C bit).
  bool cached(uint32_t address, unsigned bytes) const {
    return m_dcache_on && m_dcache.enabled() && cacheable(address, bytes);
  }
  // A bus transaction issued at the host's local time (or later, `not_before`);
  // returns its completion time in absolute ticks. Throws BusError.
  uint64_t transact(tlm::tlm_command command, uint32_t address, uint8_t* data, unsigned bytes,
                    uint64_t not_before_ticks);
  // A load of `bytes`; `counted`: the loads it adds to the count (an LDM's
  // words after its first add none: the instruction counts once).
  void read_data(uint32_t address, void* data, unsigned bytes, unsigned counted = 1);
  void write_data(uint32_t address, const void* data, unsigned bytes);
  // Posts `transfers` single transfers (a train) or one burst (transfers =
  // 1) to the write buffer. A train leaves it as bus requests of at most a
  // buffer's worth of transfers (its words or its addresses, whichever runs
  // out first), so that arbitration can serve other initiators between them
  // (tlm/bus/README.md, "Fairness").
  void post_write(uint32_t address, const uint8_t* data, unsigned bytes, unsigned transfers = 1);
  // One bus request through the write buffer: room made for its words and
  // addresses (make_room: the finished requests retired, a stall for each
  // the core waits for), the request issued, entered (enter_request).
  void post_request(uint32_t address, const uint8_t* data, unsigned bytes, unsigned transfers);
  void make_room(unsigned held_words, unsigned held_addresses);
  void enter_request(uint64_t done_ticks, unsigned held_words, unsigned held_addresses);
  // A store train (write32_train; README.md, "Store trains"): while one
  // runs, its words' bus requests are deferred (train_transact) where the
  // bus and the target quote the train, and handed over as a unit
  // (flush_train) before the train's next transaction that is not
  // deferred (train_transact) and before the host lets the kernel run
  // (sync): until then nothing but the host acts, so the quote holds and
  // every time and count is what the single transactions give.
  struct StoreTrain {
    bool running = false;  // within write32_train
    WordTrain words;       // the whole train
    size_t next = 0;       // the word being stored
    bool quoted = false;   // `quote` holds for the words from `first`
    TrainQuote quote;
    const uint64_t* cycles = nullptr;  // the cycles before each word
    size_t first = 0;                  // the first deferred word
    // The deferred words' issue times: the first `arrived` (grown to a
    // train's words, never shrunk, so not filled again at each train).
    std::vector<uint64_t> arrivals;
    size_t arrived = 0;
  };
  StoreTrain m_store_train;
  uint64_t train_transact(uint32_t address, const uint8_t* data, unsigned bytes, uint64_t not_before_ticks);
  // The train's words from `from` on, each exactly as the loop of
  // write32_train would take it, with the host's state in local variables,
  // while nothing but these steps happens: the word uncached, the quote
  // taken, the write buffer holding single words, and every quantum end a
  // run-ahead the kernel need not be asked about (README.md, "Store
  // trains"). Returns the first word it left for that loop.
  size_t train_steady(size_t from);
  // The frame copy's whole blocks from `first` that copy_words takes in
  // closed form (README.md, "The frame copy"), handed to the bus: how many.
  uint32_t copy_steady(const CopyPlan& plan, uint32_t first, const uint64_t* cycles);
  // A posted train's requests from `first` that post_write takes in closed
  // form (README.md, "Posted trains"), handed to the bus: how many.
  size_t posts_steady(const PostPlan& plan, size_t first, const uint8_t* data);
  std::vector<CopyRequest> m_copy_requests;      // copy_steady's and posts_steady's, grown, never shrunk
  static constexpr unsigned STEADY_BUFFER = 16;  // the largest buffer a closed form holds
  // The host's state that a closed form (train_steady, copy_steady,
  // posts_steady) keeps in local variables while it steps (steady_host),
  // and puts back with what its steps add to the counters (commit_steady;
  // each puts back its write buffer itself).
  struct SteadyHost {
    uint64_t local = 0, budget = 0, free = 0;  // m_local_ticks, m_budget_ticks, m_write_buffer_free_ticks
    bool window_clear = false;
    uint64_t measured = 0, busy = 0, stalls = 0, stall = 0, run_aheads = 0;
    // quantum_used_up at a local time of `local` where it only runs ahead
    // on the kernel's cached answer: whether it does (false: the calls
    // must take the step, to ask the kernel or synchronise).
    bool reach(uint64_t at, uint64_t run_ahead_ticks, bool edges_unchanged) {
      if (at < budget) return true;
      if (at >= run_ahead_ticks || !window_clear || !edges_unchanged) return false;
      ++run_aheads;
      budget = run_ahead_ticks;
      return true;
    }
  };
  // Field by field into the closed form's state (its counters start at
  // 0): a copy of a whole SteadyHost built apart was stored in pieces
  // that its first reads spanned, a stall the processor cannot forward
  // (a quarter of train_steady's samples in an ap-pixel frame).
  void steady_host(SteadyHost& s) const {
    s.local = m_local_ticks;
    s.budget = m_budget_ticks;
    s.free = m_write_buffer_free_ticks;
    s.window_clear = m_window_clear;
  }
  void commit_steady(const SteadyHost& s);
  // train_steady's copy of the host's state: the write buffer's requests
  // (single words: their completions in a ring, the oldest at `head`),
  // and the rest of the host's state (SteadyHost).
  struct SteadyTrain : SteadyHost {
    unsigned cap = 0;  // requests the buffer holds
    // The held requests' completions, a ring of `cap` slots from `head`:
    // only the `pending` slots from `head` are read, each written before,
    // so it is not cleared (train_steady makes one at each word that
    // write32_train's loop takes itself).
    uint64_t done_at[STEADY_BUFFER];
    size_t head = 0, pending = 0;
    size_t slot(size_t i) const { return head + i < cap ? head + i : head + i - cap; }
    uint64_t now = 0;  // the kernel's time, which stands meanwhile
    bool edges_unchanged = false;
  };
  // A run of words from `from` in the bus-bound steady state, in closed
  // form (README.md, "Store trains"); returns how many (0: none).
  size_t steady_run(SteadyTrain& st, size_t from);
  void flush_train() {
    if (m_store_train.arrived != 0) hand_over_train();
  }
  void hand_over_train();
  // Transfers of `bytes_each` that the buffer's data words hold.
  unsigned transfers_per_request(unsigned bytes_each) const;
  uint8_t* span_pointer(uint32_t address, unsigned bytes);
  // Posts a line's dirty data (a victim's, or a clean's) to the write buffer.
  void write_back(const DataCache::WriteBack& dirty);
  // A pointer to `bytes` at `address` through DMI, or null where DMI does
  // not reach; the DMI region is asked for at the first call and after
  // each invalidation.
  uint8_t* dmi_pointer(uint32_t address, unsigned bytes) {
    if (m_dmi_valid && address >= m_dmi.get_start_address() && uint64_t{address} + bytes - 1 <= m_dmi.get_end_address())
      return m_dmi.get_dmi_ptr() + (address - m_dmi.get_start_address());
    return dmi_pointer_or_null(address, bytes);
  }
  uint8_t* dmi_pointer_or_null(uint32_t address, unsigned bytes);
  void invalidate_direct_mem_ptr(sc_dt::uint64 start, sc_dt::uint64 end);
  // Hands the host's local time to the quantum keeper and waits for it.
  void sync();
  // Idles until `done()`, looking again at each `event` (the wait of
  // wait_irq and wait_for_interrupt), counting the time as idle.
  template <typename Event, typename Done>
  void idle_until(const Event& event, Done done);
  bool debug_access(tlm::tlm_command command, uint32_t address, uint8_t* data, unsigned bytes);

  HostParams m_params;
  sc_core::sc_simcontext* m_context;
  uint64_t m_period_ticks;   // clock period in kernel time units
  uint64_t m_cacheable_end;  // the cacheable range's end, exclusive
  Program m_program;
  std::function<void()> m_on_finish;
  std::function<void()> m_direct_memory_invalidated;
  // The quantum keeper with its next synchronisation point readable, so that
  // charging time is an addition and a compare in ticks (the hot path); the
  // keeper is handed the local time when the host synchronises.
  struct QuantumKeeper : tlm_utils::tlm_quantumkeeper {
    uint64_t next_sync_ticks() const { return m_next_sync_point.value(); }
  };
  QuantumKeeper m_qk;
  uint64_t m_local_ticks = 0;     // local time: ahead of the kernel's time by this much
  uint64_t m_quantum_ticks = 0;   // local time at which the quantum is used up
  uint64_t m_budget_ticks = 0;    // local time at which to look again: the quantum's end, or later (run-ahead)
  uint64_t m_run_ahead_ticks;     // params.run_ahead
  ActivityCounter& m_run_aheads;  // synchronisations skipped
  ActivityCounter& m_syncs;       // synchronisations made
  // Whether the kernel was last seen with nothing scheduled within the
  // run-ahead window, and nothing can have been scheduled since: the host
  // has not waited, its bus accesses since went to memory (which cannot
  // wake a process) and no traced edge was scheduled (`m_traced_edges`,
  // timed_signal_edges() when the kernel was looked at). See quantum_used_up.
  bool m_window_clear = false;
  uint64_t m_traced_edges = 0;
  void restart_quantum();
  void quantum_used_up();
  bool nothing_scheduled_in_window();
  DataCache m_dcache;
  bool m_dcache_on = true;  // CP15 c1's C bit (host.model=iss); always on for host-compiled code
  // The lines granted to a core model (data_hit_lines), once one asked
  // (then attached).
  DataHitLines m_hit_lines;
  // After a hit at `address`: its line granted, where DataHitLines may
  // serve it (see data_hit_lines.h).
  void grant_hit_line(uint32_t address) {
    if (m_hit_lines.attached() && !m_hit_lines.holds(m_dcache.line_address(address))) grant_line(address);
  }
  void grant_line(uint32_t address);
  tlm::tlm_generic_payload m_payload;
  TransferTrain* m_train;          // owned by m_payload
  ScheduleUntouched* m_untouched;  // owned by m_payload
  // What `out` is bound to, as a DirectTransport (the bus's port), or null
  // (common/direct_transport.h): found at the end of elaboration.
  DirectTransport* m_direct_out = nullptr;
  void end_of_elaboration() override;

  tlm::tlm_dmi m_dmi;
  bool m_dmi_valid = false;
  bool m_dmi_denied = false;

  struct PendingWrite {
    uint64_t done_ticks;
    unsigned words;
    unsigned addresses;
  };
  // The buffer's requests in order: a ring of host.write_buffer.addresses
  // entries, since each request holds at least one address (a deque's
  // bookkeeping of its blocks was on every posted store's path).
  class PendingWrites {
   public:
    explicit PendingWrites(unsigned capacity) : m_entries(capacity) {}
    bool empty() const { return m_count == 0; }
    size_t size() const { return m_count; }
    const PendingWrite& front() const { return m_entries[m_first]; }
    // The i-th request from the front (i < size()).
    const PendingWrite& at(size_t i) const {
      const size_t k = m_first + i;
      return m_entries[k < m_entries.size() ? k : k - m_entries.size()];
    }
    void pop_front() {
      if (++m_first == m_entries.size()) m_first = 0;
      --m_count;
    }
    void push_back(const PendingWrite& write) {
      if (m_count == m_entries.size()) throw std::logic_error("host: write buffer holds more requests than addresses");
      size_t at = m_first + m_count;
      if (at >= m_entries.size()) at -= m_entries.size();
      m_entries[at] = write;
      ++m_count;
    }
    void clear() { m_first = m_count = 0; }

   private:
    std::vector<PendingWrite> m_entries;
    size_t m_first = 0, m_count = 0;
  };
  PendingWrites m_write_buffer;
  std::vector<uint8_t> m_post_data;  // payload data of the write being posted
  unsigned m_write_buffer_words = 0;
  unsigned m_write_buffer_addresses = 0;
  uint64_t m_write_buffer_free_ticks = 0;  // when the buffer finishes its last write

  bool m_finished = false;
  int m_exit_code = 0;
  std::string m_failure;

  ActivityCounter& m_busy_cycles;
  ActivityCounter& m_measured_cycles;
  uint64_t m_stall_ticks = 0;
  // attribute_activity_in_time: the host's busy and stalled intervals that
  // may lie beyond the kernel's time, in absolute ticks, oldest first.
  struct AheadSegment {
    uint64_t start_ticks;
    uint64_t end_ticks;
    bool busy;  // else stalled
  };
  bool m_attribute_in_time = false;
  std::deque<AheadSegment> m_ahead;
  void note_ahead(bool busy, uint64_t start_ticks, uint64_t end_ticks);
  // Whether busy and stalled intervals are noted (note_segment): for
  // attribute_activity_in_time or the timeline; one test on the hot path for both.
  bool m_note_segments = false;
  bool m_take_units = true;
  void note_segment(bool busy, uint64_t start_ticks, uint64_t end_ticks) {
    if (m_attribute_in_time) note_ahead(busy, start_ticks, end_ticks);
    if (m_timeline) timeline_segment(busy, start_ticks, end_ticks);
  }
  // The timeline (timeline_to; null without one) and the slice being
  // extended, in absolute ticks (empty when end == start).
  TimelineSink* m_timeline = nullptr;
  unsigned m_timeline_track = 0;
  bool m_timeline_all = false;  // detail all: busy and stalled apart
  uint64_t m_timeline_slice_ticks = 0;
  struct ActivitySlice {
    uint64_t start_ticks = 0, end_ticks = 0, busy_ticks = 0, stalled_ticks = 0;
    bool busy = true;
  };
  ActivitySlice m_activity;
  void timeline_segment(bool busy, uint64_t start_ticks, uint64_t end_ticks);
  void close_activity_slice();           // hands the slice being extended to the timeline
  sc_core::sc_time close_phase_slice();  // hands the driver's phase so far to the timeline; returns now
  // The driver's phase since m_phase_since (null before the first).
  unsigned m_phase_track = 0;
  const char* m_phase_name = nullptr;
  sc_core::sc_time m_phase_since;
  // The calls under way (a call may make another), with their starts.
  bool m_call_timeline = false;
  unsigned m_call_track = 0;
  std::vector<std::pair<const char*, sc_core::sc_time>> m_calls;
  // The busy and stalled ticks of m_ahead after `now_ticks`.
  std::pair<uint64_t, uint64_t> ticks_after(uint64_t now_ticks) const;
  uint64_t m_idle_ticks = 0;
  ActivityCounter& m_write_buffer_stalls;
  ActivityCounter& m_bus_errors;
  std::array<ActivityCounter*, static_cast<size_t>(Op::count_)> m_op_counts{};
  ActivityCounter& m_loads;
  ActivityCounter& m_stores;
  // Instruction-side fills and uncached fetches (fetch()): declared at the
  // first, so that the host-compiled model's statistics do not list them.
  ActivityCounter* m_fetches = nullptr;
  ActivityCounter* m_fetch_bytes = nullptr;

  TimedTrace m_busy_trace;
  bool m_tracing = false;
  bool m_profiling = false;
  // The program on the ISS (host.model=iss): its PC and function in the VCD
  // (built only then), its statistics in stats.json.
  std::unique_ptr<TimedWord> m_pc_trace, m_function_trace, m_cpsr_trace;
  std::function<nlohmann::json()> m_program_statistics;
  std::vector<std::string> m_function_names;
};

}  // namespace tessera
