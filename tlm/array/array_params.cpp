// The array processor's parameters: array.*. The four calibrated cycle
// counts (add, adc, mul, mulm and cmem_operand; docs/calibration.md) have
// their defaults in isa/ap_isa.def with every other instruction's.
#include <algorithm>
#include <string>

#include "array/array_processor.h"

namespace tessera {

namespace {

// array.issue_skew = row: a row's lookups in the table take
// ceil(columns / ports) cycles, which must end before the next row's begin
// (tlm/array/README.md, "The lookup table").
void check_row_skew(const Config& config) {
  if (config.get_string("array.issue_skew") != "row" || !config.get_bool("array.features.lut")) return;
  const uint64_t columns = config.get_uint("array.columns"), ports = config.get_uint("array.lut.ports");
  const uint64_t row_cycles = (columns + ports - 1) / ports, skew = config.get_uint("array.issue_skew_cycles");
  if (row_cycles > skew)
    throw ConfigError(
        "configuration: impossible combination: array.features.lut=true with array.issue_skew=row "
        "needs a row's lookups, ceil(array.columns / array.lut.ports) = " +
        std::to_string(row_cycles) + " cycles, within array.issue_skew_cycles (" + std::to_string(skew) +
        "): the rows' lookups would collide on the table's ports");
}

}  // namespace

ParamGroup ArrayParams::parameters() {
  using param::integer;
  std::vector<ParamSpec> specs = {
      param::real("array.clock_mhz", 96.0, 1, 1000, "MHz", "array clock: the AC and the CUs (the J2210: 96 MHz)"),
      integer("array.columns", ap::J2210::COLUMNS, 4, 64, "CUs",
              "CU grid columns; a multiple of 4, the CUs one 32-bit CIU access reaches"),
      integer("array.rows", ap::J2210::ROWS, 1, 16, "CUs", "CU grid rows"),
      integer("array.registers", ap::J2210::REGISTERS, 3, ap::MAX_REGISTERS, "registers",
              "8-bit registers per CU (the multiply needs 3 for its product)"),
      integer("array.cmem_bytes", ap::J2210::CMEM_BYTES, 16, 1u << ap::ADDRESS_BITS, "bytes",
              "CMEM per CU (the J2210: 4 KB)"),
      integer("array.program_words", ap::J2210::PROGRAM_WORDS, 16, 8192, "words",
              "AC program memory, in 64-bit instruction words"),
      integer("array.max_program_cycles", 1000000000, 1000, 1e15, "cycles",
              "a program running longer stops with an error (a watchdog for runaway loops)"),
      param::boolean("array.skip_idle_cus", true,
                     "the simulator skips the CUs whose run of a program would repeat their last run of it "
                     "exactly (a simulation speed-up: results, cycles and statistics are the same either way)"),
      integer("array.cycles.cmem_operand", ap::CycleTable{}.cmem_operand, 0, 1000, "cycles",
              "extra cycles of an instruction of form RM with an operand in CMEM (calibrated: docs/calibration.md)"),
      param::choice("array.issue_skew", "none", {"none", "lane", "row"},
                    "delayed execution: none, every CU runs each instruction at once (the J2210); lane (the Image "
                    "Blender's), CU i runs it array.issue_skew_cycles after CU i - 1, the CUs chained in "
                    "row-major order; row (MorphoSys's row-sequential issue), row r runs it "
                    "array.issue_skew_cycles after row r - 1, the CUs of a row together (tlm/array/README.md, "
                    "\"Delayed execution\")"),
      integer("array.issue_skew_cycles", 1, 1, 1000, "cycles",
              "with array.issue_skew = lane or row: the delay K between one CU of the chain (one row) and the "
              "next; a program takes (CUs - 1) x K ((rows - 1) x K) cycles more"),
      param::boolean("array.row_ring", false,
                     "closes each CU row into a ring for the neighbour reads: column 0's left is the row's last "
                     "column and the last column's right is column 0 (tlm/array/README.md, \"The row ring\"); off, "
                     "the grid's edges read 0 (the J2210)"),
      integer("array.lut.entries", 256, 1, 65536, "entries",
              "16-bit entries of the lookup table lut reads (with array.features.lut)"),
      integer("array.lut.ports", 1, 1, 1024, "ports",
              "lookups the table serves per cycle (with array.features.lut): without skew a lut waits "
              "ceil(CUs / ports) - 1 cycles; with lane skew each lut holds a port for (CUs - 1) x K + 1 cycles; "
              "with row skew a row's lookups take ceil(columns / ports) cycles, at most K"),
  };
  for (const ap::OpInfo& info : ap::all_ops())
    specs.push_back(integer("array.cycles." + std::string(info.mnemonic), info.cycles, 0, 100000, "cycles",
                            std::string(info.mnemonic) + ": " + std::string(info.description)));
  // One switch per feature of ap_isa.def, off: the J2210's instruction set.
  for (const ap::OpInfo& info : ap::all_ops()) {
    if (info.feature.empty()) continue;
    std::string ops;
    for (const ap::OpInfo& other : ap::all_ops())
      if (other.feature == info.feature) ops += (ops.empty() ? "" : ", ") + std::string(other.mnemonic);
    const std::string key = ap::feature_key(info);
    const bool declared = std::any_of(specs.begin(), specs.end(), [&](const ParamSpec& s) { return s.key == key; });
    if (!declared)
      specs.push_back(param::boolean(key, false,
                                     "enables " + ops +
                                         ", beyond the J2210's instruction set (off: a program using it stops "
                                         "with ERROR_CODE 1, the warning naming this switch)"));
  }
  return {"array", std::move(specs), [](const Config& config) {
            if (config.get_uint("array.columns") % 4 != 0)
              throw ConfigError(
                  "configuration: 'array.columns' must be a multiple of 4 (one CIU word reaches 4 "
                  "CUs of a row), got " +
                  std::to_string(config.get_uint("array.columns")));
            // The wired OR decides the AC's next word from every CU's flags at
            // once, which a chain of CUs issuing one after another does not
            // have until its last CU has run the loop's body.
            if (config.get_bool("array.features.wired_or_loop") && config.get_string("array.issue_skew") != "none")
              throw ConfigError(
                  "configuration: impossible combination: array.features.wired_or_loop=true with "
                  "array.issue_skew=" +
                  config.get_string("array.issue_skew") +
                  ": endloopany's wired OR is modelled for lockstep issue only");
            check_row_skew(config);
          }};
}

ArrayParams ArrayParams::from_config(const Config& config) {
  ArrayParams p;
  p.geometry.columns = static_cast<unsigned>(config.get_uint("array.columns"));
  p.geometry.rows = static_cast<unsigned>(config.get_uint("array.rows"));
  p.geometry.registers = static_cast<unsigned>(config.get_uint("array.registers"));
  p.geometry.cmem_bytes = static_cast<unsigned>(config.get_uint("array.cmem_bytes"));
  p.program_words = static_cast<unsigned>(config.get_uint("array.program_words"));
  p.max_program_cycles = config.get_uint("array.max_program_cycles");
  p.skip_idle_cus = config.get_bool("array.skip_idle_cus");
  p.cycles.cmem_operand = static_cast<unsigned>(config.get_uint("array.cycles.cmem_operand"));
  const std::string skew = config.get_string("array.issue_skew");
  p.issue_skew = skew == "lane" ? ap::IssueSkew::lane : skew == "row" ? ap::IssueSkew::row : ap::IssueSkew::none;
  p.issue_skew_cycles =
      p.issue_skew != ap::IssueSkew::none ? static_cast<unsigned>(config.get_uint("array.issue_skew_cycles")) : 0;
  p.row_ring = config.get_bool("array.row_ring");
  p.lut_entries = static_cast<unsigned>(config.get_uint("array.lut.entries"));
  p.lut_ports = static_cast<unsigned>(config.get_uint("array.lut.ports"));
  for (const ap::OpInfo& info : ap::all_ops())
    if (!info.feature.empty())
      p.enabled_ops[static_cast<unsigned>(info.opcode)] = config.get_bool(ap::feature_key(info));
  for (const ap::OpInfo& info : ap::all_ops())
    p.cycles.cycles[static_cast<unsigned>(info.opcode)] =
        static_cast<unsigned>(config.get_uint("array.cycles." + std::string(info.mnemonic)));
  p.clock_period = sc_core::sc_time(1e3 / config.get_real("array.clock_mhz"), sc_core::SC_NS);
  return p;
}

ArrayParams ArrayParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
