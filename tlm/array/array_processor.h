// The array controller (AC) with its CU array, as a bus peripheral: the
// register target `in` (array_regs.def), the program memory target
// `program_in`, and the interrupt `irq` raised when a program finishes.
//
// A program runs as a whole on the functional core (core/array_controller.h)
// when START is written: the core executes every instruction at once and
// counts the cycles, and the AC is busy for that many periods of the array
// clock from one clock after the write, when its interrupt rises. The CIU
// (ciu.h) holds host accesses to CMEM back until then, so the host never
// sees a result before the array would have produced it. While busy, writes
// to ENTRY, START and program memory are refused (a command error response,
// a warning naming the address, STATUS.refused); reads are answered, and
// CYCLES and the stage counters keep the previous program's figures until
// the running one has finished.
//
// CmemAccess is the direct CMEM path of the system/array DMA (tlm/dma): it
// reads and writes CU bytes without the CIU and waits, as the CIU does, for
// a running program to finish.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <tlm_utils/simple_target_socket.h>
#include <systemc>
#include <tlm>

#include <nlohmann/json.hpp>

#include "array/cmem_access.h"
#include "array/core/array_controller.h"
#include "common/peripheral.h"
#include "common/timed_trace.h"
#include "config/config.h"

namespace tessera {

// Every field is read from array.* (from_config); none has a default of its
// own (the geometry's are the J2210's, ap_isa.h, which array.* defaults to).
struct ArrayParams {
  ap::ArrayGeometry geometry;
  ap::CycleTable cycles;
  unsigned program_words = 0;
  uint64_t max_program_cycles = 0;
  bool skip_idle_cus = false;
  // The J2210's instructions, and those whose array.features.<feature> is on.
  ap::EnabledOps enabled_ops = ap::j2210_ops();
  // Delayed execution (array.issue_skew) and its K (array.issue_skew_cycles
  // when array.issue_skew is lane or row), 0 for lockstep.
  ap::IssueSkew issue_skew = ap::IssueSkew::none;
  unsigned issue_skew_cycles = 0;
  bool row_ring = false;  // array.row_ring
  unsigned lut_entries = 0;
  unsigned lut_ports = 0;
  bool lut_enabled() const { return enabled_ops[static_cast<unsigned>(ap::Opcode::op_lut)]; }
  sc_core::sc_time clock_period;

  // The parameters this block owns, the one place their defaults live.
  static ParamGroup parameters();
  static ArrayParams from_config(const Config& config);
  static ArrayParams defaults();
};

class ArrayProcessor : public Peripheral, public CmemAccess {
 public:
  SC_HAS_PROCESS(ArrayProcessor);

  // Registers on `in` and the interrupt on `irq` (Peripheral).
  tlm_utils::simple_target_socket<ArrayProcessor, 32> program_in;

  // The registers, one member each (array_regs.def).
#define TESSERA_REGISTER_TABLE "array/array_regs.def"
#include "common/register_members.inc"

  ArrayProcessor(sc_core::sc_module_name name, const ArrayParams& params);

  const ArrayParams& params() const {
    return m_params;
  }
  ap::ArrayController& core() {
    return m_core;
  }
  const ap::ArrayController& core() const {
    return m_core;
  }
  // When the running program finishes (a time not later than now when none runs).
  const sc_core::sc_time& busy_until() const {
    return m_busy_until;
  }
  bool busy_at(const sc_core::sc_time& when) const {
    return when < m_busy_until;
  }
  const ap::RunResult& last_result() const {
    return m_current;
  }

  // CmemAccess: the DMA's path into CMEM.
  const ap::ArrayGeometry& cmem_geometry() const override {
    return m_params.geometry;
  }
  sc_core::sc_time cmem_free_from(const sc_core::sc_time& arrival) const override {
    return busy_at(arrival) ? m_busy_until : arrival;
  }
  uint8_t read_cmem(unsigned lane, unsigned address) const override {
    return m_core.array().cmem(lane, address);
  }
  void write_cmem(unsigned lane, unsigned address, uint8_t value) override {
    mark_used();
    m_core.array().set_cmem(lane, address, value);
  }

  void trace_signals(sc_core::sc_trace_file* file) override;
  // Programs on the track "programs", each with the CMEM-filling DMA
  // descriptors before it as flows; stages on "stages" (detail all).
  void timeline_to(TimelineSink& sink) override;
  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;
  EnergyActivity energy_activity(const sc_core::sc_time& now) const override;

  // Per stage of the programs run so far (the stages the program words are
  // marked with: fill, depth, ...): the time its instructions took at the
  // array clock, and their activity in the energy model's units
  // (array_controller, cu_array), so that the energy of some stages alone
  // can be computed (Soc: stats.energy.array_stages). Stages never run are
  // left out.
  struct StageActivity {
    std::string stage;
    double seconds = 0;
    EnergyActivity units;
  };
  std::vector<StageActivity> stage_activity() const;

 private:
  uint32_t read_STATUS() const;
  void write_START(uint32_t value);
  uint32_t read_ERROR_CODE() const;
  uint32_t read_ERROR_PC() const;
  uint32_t read_CYCLES() const;
  uint32_t read_TOTAL_CYCLES() const;
  uint32_t read_PROGRAMS() const;
  // STAGE_CYCLES0 ... STAGE_CYCLES7.
  uint32_t read_STAGE_CYCLES(unsigned stage) const;
  uint32_t read_LUT_DATA() const;
  void write_LUT_DATA(uint32_t value);
  const char* write_refusal(const tlm::tlm_generic_payload& gp) const override;
  void start(const sc_core::sc_time& access_time);
  // The result the registers show at `when`: the running program's only
  // once it has finished.
  const ap::RunResult& shown_result(const sc_core::sc_time& when) const;
  void program_b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  unsigned program_transport_dbg(tlm::tlm_generic_payload& gp);
  void copy_counters();

  ArrayParams m_params;
  ap::ArrayController m_core;
  sc_core::sc_time m_busy_until;
  sc_core::sc_time m_busy_time;
  // Set by write_refusal(), which the bus calls through a const path.
  mutable bool m_refused = false;
  mutable std::string m_refusal;  // write_refusal()'s reason when it is built
  ap::RunResult m_current, m_previous;
  std::array<uint64_t, ap::STAGE_COUNT> m_current_stages{}, m_previous_stages{};
  // Runs and cycles per entry word: the programs a frame ran.
  struct EntryTotals {
    uint64_t runs = 0;
    uint64_t cycles = 0;
  };
  std::map<unsigned, EntryTotals> m_by_entry;
  Log2Histogram m_program_cycles;  // the cycles of each run (histograms.program_cycles)

  ActivityCounter& m_programs;
  ActivityCounter& m_failed_programs;
  ActivityCounter& m_instructions;
  ActivityCounter& m_cycles;
  ActivityCounter& m_lane_operations;
  ActivityCounter& m_useful_operations;
  ActivityCounter& m_cmem_reads;
  ActivityCounter& m_cmem_writes;
  ActivityCounter& m_neighbour_transfers;
  ActivityCounter& m_program_writes;
  ActivityCounter& m_refused_program_writes;
  std::array<ActivityCounter*, ap::STAGE_COUNT> m_stage_cycles{};
  std::array<ActivityCounter*, ap::OPCODE_COUNT> m_mix{};
  // Only with delayed execution, and with the lookup table: a J2210's
  // statistics have neither.
  ActivityCounter* m_skew_cycles = nullptr;
  ActivityCounter* m_lut_stall_cycles = nullptr;
  ActivityCounter* m_lut_lookups = nullptr;
  ActivityCounter* m_lut_writes = nullptr;
  // Only with array.features.zsend.
  ActivityCounter* m_zbuf_stall_cycles = nullptr;
  // Only with array.features.wired_or_loop.
  ActivityCounter* m_wired_or_exits = nullptr;
  ActivityCounter* m_wired_or_iterations_saved = nullptr;

  TimedTrace m_busy_trace;
  TimedWord m_program_trace;
  TimedWord m_stage_trace;
  bool m_tracing = false;
  // timeline_to: null without a timeline.
  TimelineSink* m_timeline = nullptr;
  unsigned m_program_track = 0, m_stage_track = 0;
  bool m_timeline_stages = false;
  // The program just started, from `begin`, on the timeline.
  void record_program(unsigned entry, const sc_core::sc_time& begin);
};

}  // namespace tessera
