// The CMEM interface unit (CIU): the host's only way into CMEM, as a bus
// target mapping every CU's CMEM with the J2210's WriteMem32 layout
// (array_regs.h, cmem_offset): a 32-bit word at CMEM address a of CU group
// (i, j) is one byte in each of the four CUs of row j, columns 4i..4i+3,
// byte 0 in column 4i. Only whole 32-bit words: any other access is an
// error response.
//
// Timing: each word costs ciu.write_cycles or ciu.read_cycles of the array
// clock as target latency (calibrated with the host's address computation to
// the board's 488 ns and 830 ns, docs/calibration.md). An access that
// arrives while the AC runs a program waits until the program has finished
// (the CUs own CMEM while they run), and the wait is counted.
//
// The CIU is its own forward interface, as the memory is: on ap-pixel every
// host access but the frame buffer's comes here, and simple_target_socket
// would add a second virtual hop and a member-function pointer to each; the
// bus calls it as a DirectTransport (common/direct_transport.h).
// Loosely timed only (nb_transport_fw is a command error), no DMI.
#pragma once

#include <cstdint>
#include <vector>

#include <systemc>
#include <tlm>

#include <nlohmann/json.hpp>

#include "array/array_processor.h"
#include "common/block.h"
#include "common/direct_transport.h"
#include "common/schedule_untouched.h"
#include "common/timed_trace.h"
#include "config/config.h"

namespace tessera {

struct CiuParams {
  unsigned write_cycles = 0;
  unsigned read_cycles = 0;
  sc_core::sc_time clock_period;  // set by the SoC: the array clock

  static ParamGroup parameters();
  static CiuParams from_config(const Config& config);
  static CiuParams defaults();
};

class Ciu : public Block, public tlm::tlm_fw_transport_if<>, public DirectTransport {
 public:
  tlm::tlm_target_socket<32> in;

  Ciu(sc_core::sc_module_name name, const CiuParams& params, ArrayProcessor& array);

  // Bytes of the window that map CMEM: every group's every address.
  uint64_t window_bytes() const { return m_window_bytes; }

  void trace_signals(sc_core::sc_trace_file* file) override;
  // Track "accesses": bursts (accesses that follow each other within
  // BURST_GAP, with their number and latency) or, at detail all, each access.
  void timeline_to(TimelineSink& sink) override;
  void finish_timeline() override;
  static constexpr double BURST_GAP_NS = 1000;
  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;

 private:
  // Through the socket, "untouched" goes to the payload's extension;
  // called directly, to DirectExtras.
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) final {
    if (transport(gp, delay)) mark_schedule_untouched(gp);
  }
  void direct_b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay, DirectExtras& extras) override {
    if (transport(gp, delay)) extras.untouched = true;
  }
  // Both doors' access: true when it scheduled nothing (a word moved).
  bool transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  // Store trains (common/direct_transport.h): writes only, each word as
  // transport() takes it.
  bool quote_train(const WordTrain& train, uint64_t first_ticks, TrainQuote& quote) override;
  void direct_train(const WordTrain& train, const uint64_t* arrivals) override;
  // An access's latency in ticks, ciu.write_cycles or ciu.read_cycles of
  // the array clock a word (whole ticks: what clock_period *
  // double(cycles * words) gives).
  uint64_t latency_ticks(bool write, uint64_t words) const {
    return m_params.clock_period.value() * (write ? m_params.write_cycles : m_params.read_cycles) * words;
  }
  // Counts an access of `words` with its latency.
  void count_access(bool write, uint64_t words, const sc_core::sc_time& latency);
  unsigned transport_dbg(tlm::tlm_generic_payload& gp) override;
  // No DMI: refused with the whole range and read-write allowed, as
  // simple_target_socket answers for a target without it. Non-blocking
  // calls: refused (common/loosely_timed.h), an error counted.
  bool get_direct_mem_ptr(tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi) override;
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& phase,
                                     sc_core::sc_time& delay) override;
  // The group of four CUs and the CMEM address of the word at `offset`
  // (byte k of it is CU m_group_lane[group] + k).
  struct WordPlace {
    uint64_t group;
    unsigned address;
  };
  WordPlace place_of(uint64_t offset) const;
  // Moves `words` whole words at `offset` between the payload's data and
  // CMEM (to CMEM when `write`, from it when `read`).
  void move_words(uint64_t offset, uint64_t words, uint8_t* data, bool write, bool read);

  CiuParams m_params;
  ArrayProcessor& m_array;
  ActivityCounter& m_writes;
  ActivityCounter& m_reads;
  ActivityCounter& m_bytes_written;
  ActivityCounter& m_bytes_read;
  ActivityCounter& m_stalled;
  ActivityCounter& m_errors;
  uint64_t m_window_bytes = 0;  // every lane's CMEM
  unsigned m_cmem_bytes = 0;
  unsigned m_cmem_shift = 0;            // log2 of m_cmem_bytes when a power of two, else 0
  std::vector<unsigned> m_group_lane;   // each group's first lane
  bool m_groups_in_lane_order = false;  // group g's first lane is 4 g: a CMEM address's words are one run of a row
  sc_core::sc_time m_access_time;       // latency charged, all accesses
  sc_core::sc_time m_stall_time;        // waiting for a running program
  TimedTrace m_access_trace;
  bool m_tracing = false;
  TimelineSink* m_timeline = nullptr;  // timeline_to: null without a timeline
  unsigned m_timeline_track = 0;
  // The burst being extended: from its first access's start to its last
  // access's end, and the accesses' latency.
  struct Burst {
    sc_core::sc_time begin, end, latency;
    uint64_t accesses = 0;
  };
  Burst m_burst;
  void record_access(const sc_core::sc_time& start, const sc_core::sc_time& latency);
};

}  // namespace tessera
