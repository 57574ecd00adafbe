#include "array/array_processor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "array/array_regs.h"
#include "common/log.h"

namespace tessera {

using sc_core::sc_time;
namespace regs = array_regs;

namespace {

uint32_t low32(uint64_t value) {
  return static_cast<uint32_t>(std::min<uint64_t>(value, UINT32_MAX));
}

// The AC's broadcasts: one per instruction, except the multiplication of
// CMEM operands, which stands for the repeated additions on CMEM operands
// it is made of: it counts one broadcast per CMEM-operand addition time
// (array.cycles.add + array.cycles.cmem_operand) of its cycles, 35 with the
// defaults. The register-level mul is one long instruction, one broadcast.
// The energy model charges the AC per broadcast (tlm/power/README.md,
// "Parameters").
double ac_broadcasts(const ap::CycleTable& table, uint64_t instructions, uint64_t cmem_multiplies) {
  const double addition = table.cycles[static_cast<unsigned>(ap::Opcode::op_add)] + table.cmem_operand;
  const double steps = addition > 0 ? table.cycles[static_cast<unsigned>(ap::Opcode::op_mulm)] / addition : 1;
  return static_cast<double>(instructions) + static_cast<double>(cmem_multiplies) * (steps - 1);
}

}  // namespace

ArrayProcessor::ArrayProcessor(sc_core::sc_module_name name, const ArrayParams& params)
    : Peripheral(name, params.clock_period),
      program_in("program_in"),
      m_params(params),
      m_core(params.geometry, params.cycles, params.program_words, params.max_program_cycles),
      m_programs(counter("programs", "programs started (one per START)")),
      m_failed_programs(counter("failed_programs", "programs that stopped with an error")),
      m_instructions(counter("instructions", "instructions the AC broadcast (each loop iteration's counted)")),
      m_cycles(counter("cycles.total", "array clock cycles of every program")),
      m_lane_operations(counter("lanes.operations", "lane operations: CUs x instructions that did lane work")),
      m_useful_operations(counter("lanes.useful", "lane operations in CUs whose mask was set")),
      m_cmem_reads(counter("cmem.bytes_read", "bytes the CUs read from CMEM, all CUs together")),
      m_cmem_writes(counter("cmem.bytes_written", "bytes the CUs stored in CMEM (unmasked CUs only)")),
      m_neighbour_transfers(counter("neighbour_transfers", "CUs x nget instructions that read a neighbour")),
      m_program_writes(counter("program_memory.writes", "32-bit writes into program memory")),
      m_refused_program_writes(
          counter("program_memory.refused_writes", "program memory writes refused while a program ran")),
      m_busy_trace("busy"),
      m_program_trace("program"),
      m_stage_trace("stage") {
  sleeps_until_used();
  const ap::ArrayGeometry& g = params.geometry;
  if (g.columns == 0 || g.rows == 0 || g.columns % regs::CUS_PER_GROUP != 0 || g.registers < 3 ||
      g.registers > ap::MAX_REGISTERS || g.cmem_bytes == 0 || g.cmem_bytes > (1u << ap::ADDRESS_BITS) ||
      params.program_words == 0)
    throw std::invalid_argument(std::string(this->name()) + ": impossible array geometry");
  m_core.skip_idle_cus(params.skip_idle_cus);
  m_core.enable_ops(params.enabled_ops);
  m_core.set_issue_skew(params.issue_skew, params.issue_skew_cycles);
  m_core.array().set_row_ring(params.row_ring);
  if (params.issue_skew_cycles != 0)
    m_skew_cycles = &counter("issue_skew.cycles",
                             "cycles from the first CU's halt to the last CU's, (CUs - 1) x "
                             "array.issue_skew_cycles per program ((rows - 1) x it by row; in cycles.total)");
  if (params.lut_enabled()) {
    m_core.set_lut_ports(params.lut_ports);
    m_core.array().set_lut_entries(params.lut_entries);
    m_lut_stall_cycles =
        &counter("lut.stall_cycles", "cycles the AC waited for the lookup table's ports (in cycles.total)");
    m_lut_lookups = &counter("lut.lookups", "lookups in the table: CUs x lut instructions");
    m_lut_writes = &counter("lut.host_writes", "table entries the host wrote through LUT_DATA");
  }
  if (params.enabled_ops[static_cast<unsigned>(ap::Opcode::op_zsend)])
    m_zbuf_stall_cycles = &counter("zbuf.stall_cycles",
                                   "cycles the AC waited for the z-buffer unit's port before a zsend or a halt (in "
                                   "cycles.total)");
  if (params.enabled_ops[static_cast<unsigned>(ap::Opcode::op_endloopany)]) {
    m_wired_or_exits =
        &counter("wired_or.exits", "loops endloopany left before their count ran out (no masked-in CU's condition)");
    m_wired_or_iterations_saved = &counter(
        "wired_or.iterations_saved", "iterations the loops' counts would still have run where endloopany left them");
  }
  // An instruction that is not enabled never runs: it has no counter, so that
  // the statistics of a J2210 array are the J2210's.
  for (const ap::OpInfo& info : ap::all_ops())
    if (params.enabled_ops[static_cast<unsigned>(info.opcode)])
      m_mix[static_cast<unsigned>(info.opcode)] =
          &counter("mix." + std::string(info.mnemonic), "executions of " + std::string(info.mnemonic));
  for (unsigned stage = 0; stage < ap::STAGE_COUNT; ++stage) {
    const std::string stage_name(ap::stage_name(static_cast<ap::Stage>(stage)));
    m_stage_cycles[stage] = &counter("cycles." + stage_name, "cycles of instructions of stage " + stage_name);
  }
  program_in.register_b_transport(this, &ArrayProcessor::program_b_transport);
  program_in.register_transport_dbg(this, &ArrayProcessor::program_transport_dbg);

  STATUS.on_read(this, &ArrayProcessor::read_STATUS);
  START.on_write(this, &ArrayProcessor::write_START);
  bind_irq_registers(IRQ_STATUS, IRQ_ENABLE);
  ERROR_CODE.on_read(this, &ArrayProcessor::read_ERROR_CODE);
  ERROR_PC.on_read(this, &ArrayProcessor::read_ERROR_PC);
  CYCLES.on_read(this, &ArrayProcessor::read_CYCLES);
  TOTAL_CYCLES.on_read(this, &ArrayProcessor::read_TOTAL_CYCLES);
  PROGRAMS.on_read(this, &ArrayProcessor::read_PROGRAMS);
  COLUMNS.set_reset(g.columns);
  ROWS.set_reset(g.rows);
  CMEM_BYTES.set_reset(g.cmem_bytes);
  REGISTERS.set_reset(g.registers);
  PROGRAM_WORDS.set_reset(params.program_words);
  LUT_ENTRIES.set_reset(params.lut_enabled() ? params.lut_entries : 0);
  LUT_DATA.on_read(this, &ArrayProcessor::read_LUT_DATA);
  LUT_DATA.on_write(this, &ArrayProcessor::write_LUT_DATA);
  CLOCK_KHZ.set_reset(static_cast<uint32_t>(std::llround(1e-3 / params.clock_period.to_seconds())));
  Register* const stage_registers[ap::STAGE_COUNT] = {&STAGE_CYCLES0, &STAGE_CYCLES1, &STAGE_CYCLES2, &STAGE_CYCLES3,
                                                      &STAGE_CYCLES4, &STAGE_CYCLES5, &STAGE_CYCLES6, &STAGE_CYCLES7};
  for (unsigned stage = 0; stage < ap::STAGE_COUNT; ++stage)
    stage_registers[stage]->on_read([this, stage] { return read_STAGE_CYCLES(stage); });
}

uint32_t ArrayProcessor::read_STATUS() const {
  const sc_time now = access_time();
  const bool busy = busy_at(now);
  const ap::RunResult& shown = shown_result(now);
  const bool ran = m_programs.value > (busy ? 1u : 0u);
  return (busy ? regs::STATUS_BUSY : 0u) | (ran && shown.ok ? regs::STATUS_DONE : 0u) |
         (ran && !shown.ok ? regs::STATUS_ERROR : 0u) | (m_refused ? regs::STATUS_REFUSED : 0u);
}

void ArrayProcessor::write_START(uint32_t value) {
  if ((value & 1u) != 0) start(access_time());
}

uint32_t ArrayProcessor::read_ERROR_CODE() const {
  return static_cast<uint32_t>(shown_result(access_time()).kind);
}

uint32_t ArrayProcessor::read_ERROR_PC() const {
  const ap::RunResult& shown = shown_result(access_time());
  return shown.ok ? 0u : shown.error_pc;
}

uint32_t ArrayProcessor::read_CYCLES() const {
  return low32(shown_result(access_time()).cycles);
}

uint32_t ArrayProcessor::read_TOTAL_CYCLES() const {
  // Only programs that have finished by the access count.
  const uint64_t running = busy_at(access_time()) ? m_current.cycles : 0;
  return static_cast<uint32_t>(m_core.activity().cycles - running);
}

uint32_t ArrayProcessor::read_PROGRAMS() const {
  return static_cast<uint32_t>(m_programs.value);
}

uint32_t ArrayProcessor::read_STAGE_CYCLES(unsigned stage) const {
  return low32(busy_at(access_time()) ? m_previous_stages[stage] : m_current_stages[stage]);
}

const ap::RunResult& ArrayProcessor::shown_result(const sc_time& when) const {
  return busy_at(when) ? m_previous : m_current;
}

uint32_t ArrayProcessor::read_LUT_DATA() const {
  const unsigned index = LUT_INDEX.get();
  return m_params.lut_enabled() && index < m_params.lut_entries ? m_core.array().lut_entry(index) : 0u;
}

void ArrayProcessor::write_LUT_DATA(uint32_t value) {
  // write_refusal() has checked the switch and the index.
  const unsigned index = LUT_INDEX.get();
  m_core.array().set_lut_entry(index, static_cast<uint16_t>(value));
  LUT_INDEX.set(index + 1);
  ++*m_lut_writes;
}

const char* ArrayProcessor::write_refusal(const tlm::tlm_generic_payload& gp) const {
  if (!gp.is_write()) return nullptr;
  const uint64_t offset = gp.get_address();
  if (offset == regs::IRQ_STATUS || offset == regs::IRQ_ENABLE || !busy_at(access_time())) {
    if (offset != regs::LUT_INDEX && offset != regs::LUT_DATA) return nullptr;
    if (!m_params.lut_enabled()) return "the lookup table needs array.features.lut = true";
    if (offset == regs::LUT_DATA && LUT_INDEX.get() >= m_params.lut_entries) {
      m_refusal = "LUT_INDEX " + std::to_string(LUT_INDEX.get()) + " is beyond the table's " +
                  std::to_string(m_params.lut_entries) + " entries (array.lut.entries)";
      return m_refusal.c_str();
    }
    return nullptr;
  }
  m_refused = true;
  return "written while a program runs";
}

void ArrayProcessor::start(const sc_time& access_time) {
  const unsigned entry = ENTRY.get();
  // The run starts one clock after the write reaches the register.
  const sc_time begin = access_time + m_params.clock_period;
  m_previous = m_current;
  m_previous_stages = m_current_stages;
  m_refused = false;
  const ap::ControllerActivity& before = m_core.activity();
  const std::array<uint64_t, ap::STAGE_COUNT> stages_before = before.stage_cycles;
  m_core.record_stages(m_tracing || m_timeline_stages);
  m_current = m_core.run(entry);
  for (unsigned stage = 0; stage < ap::STAGE_COUNT; ++stage)
    m_current_stages[stage] = m_core.activity().stage_cycles[stage] - stages_before[stage];
  const sc_time length = m_params.clock_period * static_cast<double>(m_current.cycles);
  m_busy_until = begin + length;
  m_busy_time += length;
  EntryTotals& totals = m_by_entry[entry];
  ++totals.runs;
  totals.cycles += m_current.cycles;
  m_program_cycles.sample(m_current.cycles);
  copy_counters();

  if (m_tracing) {
    m_busy_trace.set_at(true, begin);
    m_program_trace.set_at(entry, begin);
    for (const auto& change : m_core.stage_changes())
      m_stage_trace.set_at(static_cast<uint32_t>(change.stage),
                           begin + m_params.clock_period * static_cast<double>(change.cycle));
    m_busy_trace.set_at(false, m_busy_until);
  }
  if (m_timeline) record_program(entry, begin);
  const sc_time until_end = m_busy_until - sc_core::sc_time_stamp();
  if (m_current.ok) {
    log::info(name(), "program at word " + std::to_string(entry) + ": " + std::to_string(m_current.cycles) +
                          " cycles, " + std::to_string(m_current.instructions) + " instructions");
    raise_irq(regs::IRQ_DONE, until_end);
  } else {
    log::warning(name(), "program at word " + std::to_string(entry) + " stopped: " + m_current.error);
    raise_irq(regs::IRQ_ERROR, until_end);
  }
}

void ArrayProcessor::copy_counters() {
  const ap::ControllerActivity& core = m_core.activity();
  const ap::ArrayActivity& lanes = m_core.array().activity();
  m_programs.value = core.programs;
  m_failed_programs.value = core.failed_programs;
  m_instructions.value = core.instructions;
  m_cycles.value = core.cycles;
  for (unsigned stage = 0; stage < ap::STAGE_COUNT; ++stage) m_stage_cycles[stage]->value = core.stage_cycles[stage];
  for (unsigned op = 0; op < ap::OPCODE_COUNT; ++op)
    if (m_mix[op] != nullptr) m_mix[op]->value = core.instruction_mix[op];
  m_lane_operations.value = lanes.lane_operations;
  m_useful_operations.value = lanes.useful_operations;
  m_cmem_reads.value = lanes.cmem_reads;
  m_cmem_writes.value = lanes.cmem_writes;
  m_neighbour_transfers.value = lanes.neighbour_transfers;
  if (m_skew_cycles != nullptr) m_skew_cycles->value = core.skew_cycles;
  if (m_zbuf_stall_cycles != nullptr) m_zbuf_stall_cycles->value = core.zbuf_stall_cycles;
  if (m_wired_or_exits != nullptr) {
    m_wired_or_exits->value = core.wired_or_exits;
    m_wired_or_iterations_saved->value = core.wired_or_iterations_saved;
  }
  if (m_lut_stall_cycles != nullptr) {
    m_lut_stall_cycles->value = core.lut_stall_cycles;
    m_lut_lookups->value = core.instruction_mix[static_cast<unsigned>(ap::Opcode::op_lut)] * m_params.geometry.lanes();
  }
}

void ArrayProcessor::program_b_transport(tlm::tlm_generic_payload& gp, sc_time& delay) {
  mark_used(delay);
  const uint64_t address = gp.get_address();
  const uint64_t length = gp.get_data_length();
  const uint64_t size = uint64_t{m_params.program_words} * regs::PROGRAM_WORD_BYTES;
  if (address % 4 != 0 || length == 0 || length % 4 != 0 || address >= size || length > size - address) {
    gp.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    log::warning(name(), "program memory access of " + std::to_string(length) + " bytes at offset " +
                             log::hex(address) + " outside the " + std::to_string(size) +
                             "-byte program memory or not whole aligned words");
    return;
  }
  if (gp.get_byte_enable_ptr() || gp.get_streaming_width() < length) {
    gp.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    return;
  }
  const sc_time when = sc_core::sc_time_stamp() + delay;
  if (gp.is_write() && busy_at(when)) {
    ++m_refused_program_writes;
    m_refused = true;
    gp.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    log::warning(name(), "program memory write at offset " + log::hex(address) + " refused: a program runs");
    delay += m_params.clock_period;
    return;
  }
  uint8_t* data = gp.get_data_ptr();
  for (uint64_t offset = 0; offset < length; offset += 4) {
    const auto word_index = static_cast<unsigned>((address + offset) / regs::PROGRAM_WORD_BYTES);
    const bool high = ((address + offset) % regs::PROGRAM_WORD_BYTES) != 0;
    uint64_t word = m_core.word(word_index);
    uint32_t half = 0;
    if (gp.is_write()) {
      std::memcpy(&half, data + offset, 4);
      word = high ? (word & 0xffffffffull) | (uint64_t{half} << 32) : (word & ~0xffffffffull) | half;
      m_core.write_word(word_index, word);
      ++m_program_writes;
    } else if (gp.is_read()) {
      half = static_cast<uint32_t>(high ? word >> 32 : word);
      std::memcpy(data + offset, &half, 4);
    }
  }
  delay += m_params.clock_period * static_cast<double>(length) / 4.0;
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

unsigned ArrayProcessor::program_transport_dbg(tlm::tlm_generic_payload& gp) {
  const uint64_t address = gp.get_address();
  const uint64_t size = uint64_t{m_params.program_words} * regs::PROGRAM_WORD_BYTES;
  if (address >= size) return 0;
  const uint64_t length = std::min<uint64_t>(gp.get_data_length(), size - address);
  for (uint64_t i = 0; i < length; ++i) {
    const auto word_index = static_cast<unsigned>((address + i) / regs::PROGRAM_WORD_BYTES);
    const unsigned shift = 8 * static_cast<unsigned>((address + i) % regs::PROGRAM_WORD_BYTES);
    uint64_t word = m_core.word(word_index);
    if (gp.is_write()) {
      word = (word & ~(0xffull << shift)) | (uint64_t{gp.get_data_ptr()[i]} << shift);
      m_core.write_word(word_index, word);
    } else {
      gp.get_data_ptr()[i] = static_cast<uint8_t>(word >> shift);
    }
  }
  return static_cast<unsigned>(length);
}

void ArrayProcessor::trace_signals(sc_core::sc_trace_file* file) {
  m_tracing = true;
  const std::string prefix = std::string(name()) + ".";
  sc_core::sc_trace(file, m_busy_trace.signal, prefix + "busy");
  sc_core::sc_trace(file, m_program_trace.signal, prefix + "program");
  sc_core::sc_trace(file, m_stage_trace.signal, prefix + "stage");
  sc_core::sc_trace(file, irq, prefix + "irq");
}

void ArrayProcessor::timeline_to(TimelineSink& sink) {
  m_timeline = &sink;
  m_program_track = sink.track(name(), "programs");
  m_timeline_stages = sink.records(TimelineDetail::all);
  if (m_timeline_stages) m_stage_track = sink.track(name(), "stages");
}

void ArrayProcessor::record_program(unsigned entry, const sc_time& begin) {
  if (!m_timeline->records(TimelineDetail::blocks)) return;
  m_timeline->slice(m_program_track, m_current.ok ? "program" : "program (failed)", begin, m_busy_until,
                    {{"entry", static_cast<double>(entry)},
                     {"cycles", static_cast<double>(m_current.cycles)},
                     {"instructions", static_cast<double>(m_current.instructions)}});
  // What the DMA wrote into CMEM before the program started, it reads.
  m_timeline->flow_to(cmem_flow_key(*this), m_program_track, begin);
  if (!m_timeline_stages) return;
  const auto& changes = m_core.stage_changes();
  for (size_t i = 0; i < changes.size(); ++i) {
    const sc_time from = begin + m_params.clock_period * static_cast<double>(changes[i].cycle);
    const sc_time to = i + 1 < changes.size()
                           ? begin + m_params.clock_period * static_cast<double>(changes[i + 1].cycle)
                           : m_busy_until;
    if (to > from) m_timeline->slice(m_stage_track, ap::stage_name(changes[i].stage), from, to);
  }
}

nlohmann::json ArrayProcessor::stats_json(const sc_time& elapsed) const {
  nlohmann::json stats = Peripheral::stats_json(elapsed);
  stats["clock_mhz"] = 1e-6 / m_params.clock_period.to_seconds();
  stats["columns"] = m_params.geometry.columns;
  stats["rows"] = m_params.geometry.rows;
  stats["cmem_bytes"] = m_params.geometry.cmem_bytes;
  stats["registers"] = m_params.geometry.registers;
  add_busy_stats(stats, m_busy_time, elapsed);
  stats["cu_utilisation"] =
      m_lane_operations.value > 0 ? static_cast<double>(m_useful_operations.value) / m_lane_operations.value : 0.0;
  nlohmann::json by_entry = nlohmann::json::object();
  for (const auto& [entry, totals] : m_by_entry)
    by_entry[std::to_string(entry)] = {{"runs", totals.runs}, {"cycles", totals.cycles}};
  stats["programs_by_entry"] = by_entry;
  // The profile: every program word that ran, with its instruction, its
  // stage, how often it ran and the cycles it took.
  nlohmann::json profile = nlohmann::json::array();
  const ap::ControllerActivity& core = m_core.activity();
  for (unsigned word = 0; word < core.word_cycles.size(); ++word) {
    if (core.word_executions[word] == 0) continue;
    const ap::Decoded decoded = ap::decode(m_core.word(word));
    profile.push_back({{"word", word},
                       {"instruction", decoded.error.empty() ? ap::format_instruction(decoded.instruction)
                                                             : "(bad word: " + decoded.error + ")"},
                       {"stage", std::string(ap::stage_name(decoded.instruction.stage))},
                       {"executions", core.word_executions[word]},
                       {"cycles", core.word_cycles[word]}});
  }
  stats["profile"] = profile;
  stats["histograms"]["program_cycles"] = histogram_json(m_program_cycles);
  return stats;
}

void ArrayProcessor::describe_stats(StatsSchema& schema) const {
  Peripheral::describe_stats(schema);
  schema.add("clock_mhz", "MHz", "the array's clock frequency (array.clock_mhz)");
  schema.add_setting("columns", "count", "columns of CUs (array.columns)");
  schema.add_setting("rows", "count", "rows of CUs (array.rows)");
  schema.add_setting("cmem_bytes", "bytes", "CMEM of each CU (array.cmem_bytes)");
  schema.add_setting("registers", "count", "registers of each CU (array.registers)");
  describe_busy_stats(schema, "time the array ran programs");
  schema.add("cu_utilisation", "fraction",
             "useful lane operations over all lane operations (lanes.useful / lanes.operations)");
  schema.add("programs_by_entry.*.runs", "count", "runs of the program that starts at this program-memory word");
  schema.add("programs_by_entry.*.cycles", "cycles",
             "array cycles of the runs of the program that starts at this word");
  schema.add("profile[].word", "index", "program-memory word of the profile's row (only words that ran)");
  schema.add("profile[].executions", "count", "times the word's instruction was issued");
  schema.add("profile[].cycles", "cycles", "array cycles the word's instruction took, all its executions");
  schema.add_histogram("histograms.program_cycles", "cycles", "the cycles of each program run");
}

SummaryRow ArrayProcessor::summary_row(const sc_time& elapsed) const {
  const double utilisation =
      m_lane_operations.value > 0 ? static_cast<double>(m_useful_operations.value) / m_lane_operations.value : 0.0;
  return busy_row(m_busy_time, elapsed,
                  std::to_string(m_programs.value) + " programs, " + std::to_string(m_cycles.value) + " cycles, " +
                      std::to_string(m_instructions.value) + " instructions, CUs useful " +
                      format_percent(utilisation));
}

EnergyActivity ArrayProcessor::energy_activity(const sc_time& now) const {
  (void)now;
  const double lanes = static_cast<double>(m_params.geometry.columns) * m_params.geometry.rows;
  const double broadcasts =
      ac_broadcasts(m_params.cycles, m_instructions.value, m_mix[static_cast<unsigned>(ap::Opcode::op_mulm)]->value);
  return {{"array_controller", {{"broadcasts", broadcasts}}},
          {"cu_array",
           {{"cu_cycles", lanes * static_cast<double>(m_cycles.value)},
            {"cmem_bytes_read", static_cast<double>(m_cmem_reads.value)},
            {"cmem_bytes_written", static_cast<double>(m_cmem_writes.value)},
            {"neighbour_transfers", static_cast<double>(m_neighbour_transfers.value)}}}};
}

std::vector<ArrayProcessor::StageActivity> ArrayProcessor::stage_activity() const {
  const ap::ControllerActivity& core = m_core.activity();
  const double lanes = static_cast<double>(m_params.geometry.columns) * m_params.geometry.rows;
  std::vector<StageActivity> stages;
  for (unsigned stage = 0; stage < ap::STAGE_COUNT; ++stage) {
    const uint64_t cycles = core.stage_cycles[stage];
    if (cycles == 0 && core.stage_instructions[stage] == 0) continue;
    const ap::ArrayActivity& used = core.stage_lanes[stage];
    stages.push_back(
        {std::string(ap::stage_name(static_cast<ap::Stage>(stage))),
         m_params.clock_period.to_seconds() * static_cast<double>(cycles),
         {{"array_controller",
           {{"broadcasts", ac_broadcasts(m_params.cycles, core.stage_instructions[stage],
                                         core.stage_mix[stage][static_cast<unsigned>(ap::Opcode::op_mulm)])}}},
          {"cu_array",
           {{"cu_cycles", lanes * static_cast<double>(cycles)},
            {"cmem_bytes_read", static_cast<double>(used.cmem_reads)},
            {"cmem_bytes_written", static_cast<double>(used.cmem_writes)},
            {"neighbour_transfers", static_cast<double>(used.neighbour_transfers)}}}}});
  }
  return stages;
}

}  // namespace tessera
