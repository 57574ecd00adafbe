// TLM tests of the array controller (tlm/array/array_processor.h) and the
// CIU (tlm/array/ciu.h) on a bus: the CIU's WriteMem32 layout byte for byte,
// a program loaded over the bus, started, and its interrupt at the time its
// cycles give; host accesses while it runs (CMEM waits, writes to the AC are
// refused); every bad access and bad program; statistics and summary rows.
//
// Bench: initiator -> checker -> bus (100 MHz) -> AC registers at 0,
// program memory at 0x10000, CIU window at 0x1000000. The array clock is
// also 100 MHz so expected times are whole nanoseconds.
#include <array>
#include <cstring>
#include <map>
#include <sstream>
#include <string>

#include "array/array_processor.h"
#include "array/array_regs.h"
#include "array/ciu.h"
#include "bus/ahb_bus.h"
#include "checker/protocol_checker.h"
#include "common/schedule_untouched.h"
#include "tlm_bench/bench_block_params.h"
#include "tlm_bench/bench_params.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;
namespace regs = array_regs;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);
constexpr uint64_t AC = 0x0, PROGRAM = 0x10000, CMEM = 0x1000000;
// A second array with the Image Blender's features on: delayed execution
// (K = 1), the row ring, the lookup table (64 entries, one port), divide and
// the neighbour adds.
constexpr uint64_t BLENDER_AC = 0x2000, BLENDER_PROGRAM = 0x20000;
constexpr unsigned LUT_ENTRIES = 64;
// A third with MorphoSys's 16-bit operations and wired-OR loop.
constexpr uint64_t MORPHO_AC = 0x3000, MORPHO_PROGRAM = 0x30000;
constexpr unsigned WRITE_CYCLES = 7, READ_CYCLES = 11;
constexpr unsigned CMEM_BYTES = 4096, COLUMNS = 24;

ArrayParams array_params() {
  return test::bench_array_params(CYCLE);
}

ArrayParams blender_params() {
  Config config({ArrayParams::parameters()});
  for (const char* key :
       {"array.features.lut=true", "array.features.divide=true", "array.features.neighbour_add=true",
        "array.issue_skew=lane", "array.issue_skew_cycles=1", "array.lut.entries=64", "array.row_ring=true"})
    config.apply_override(key);
  ArrayParams p = ArrayParams::from_config(config);
  p.clock_period = CYCLE;
  p.program_words = 256;
  p.max_program_cycles = 100000;
  return p;
}

ArrayParams morpho_params() {
  Config config({ArrayParams::parameters()});
  for (const char* key : {"array.features.wide_ops=true", "array.features.wired_or_loop=true"})
    config.apply_override(key);
  config.validate();
  ArrayParams p = ArrayParams::from_config(config);
  p.clock_period = CYCLE;
  p.program_words = 256;
  p.max_program_cycles = 100000;
  return p;
}

CiuParams ciu_params() {
  CiuParams p = CiuParams::defaults();
  p.write_cycles = WRITE_CYCLES;
  p.read_cycles = READ_CYCLES;
  p.clock_period = CYCLE;
  return p;
}

struct Bench : sc_core::sc_module {
  test::TestInitiator host;
  ProtocolChecker<32> check_host;
  AhbBus bus;
  ArrayProcessor array;
  Ciu ciu;
  ArrayProcessor blender;
  ArrayProcessor morpho;
  sc_core::sc_signal<bool> irq, blender_irq, morpho_irq;
  explicit Bench(sc_core::sc_module_name name)
      : sc_core::sc_module(name),
        host("host"),
        check_host("check_host"),
        bus("bus", test::bench_bus_params(CYCLE)),
        array("array", array_params()),
        ciu("ciu", ciu_params(), array),
        blender("blender", blender_params()),
        morpho("morpho", morpho_params()) {
    host.out.bind(check_host.in);
    bus.attach(check_host.out, "host", 0);
    bus.map(array.in, AC, 0x1000, "array_regs");
    bus.map(array.program_in, PROGRAM, 0x10000, "array_program");
    bus.map(ciu.in, CMEM, 0x1000000, "array_cmem");
    array.irq.bind(irq);
    bus.map(blender.in, BLENDER_AC, 0x1000, "blender_regs");
    bus.map(blender.program_in, BLENDER_PROGRAM, 0x10000, "blender_program");
    blender.irq.bind(blender_irq);
    bus.map(morpho.in, MORPHO_AC, 0x1000, "morpho_regs");
    bus.map(morpho.program_in, MORPHO_PROGRAM, 0x10000, "morpho_program");
    morpho.irq.bind(morpho_irq);
  }
};

Bench* g_bench = nullptr;

// Instructions, built field by field.
ap::Operand reg(unsigned index) {
  return {false, static_cast<uint16_t>(index), 0};
}
ap::Operand mem(unsigned address, unsigned loop = 0) {
  return {true, static_cast<uint16_t>(address), static_cast<uint8_t>(loop)};
}
uint64_t op(ap::Opcode opcode, ap::Operand d = {}, ap::Operand a = {}, ap::Operand b = {}) {
  ap::Instruction in;
  in.opcode = opcode;
  in.d = d;
  in.a = a;
  in.b = b;
  return ap::encode(in);
}
uint64_t loop(unsigned level, unsigned start, unsigned step) {
  return op(ap::Opcode::op_loop, reg(level), reg(start), reg(step));
}

// Group (i, j), CMEM address a, as the CIU maps it.
uint64_t cmem_address(unsigned i, unsigned j, unsigned a) {
  return CMEM + regs::cmem_offset(j * (COLUMNS / 4) + i, a, CMEM_BYTES);
}

// The host waits for every access to complete (no temporal decoupling),
// so each one starts on an idle bus.
tlm::tlm_response_status write32(Bench& b, uint64_t address, uint32_t value) {
  const auto result = b.host.write32(address, value);
  sc_core::wait(result.delay);
  return result.status;
}
uint32_t read32(Bench& b, uint64_t address) {
  test::TestInitiator::Result result{};
  const uint32_t value = b.host.read32(address, &result);
  sc_core::wait(result.delay);
  return value;
}

void load(Bench& b, unsigned at, const std::vector<uint64_t>& words) {
  for (size_t w = 0; w < words.size(); ++w) {
    const uint64_t address = PROGRAM + (at + w) * regs::PROGRAM_WORD_BYTES;
    ASSERT_EQ(write32(b, address, static_cast<uint32_t>(words[w])), tlm::TLM_OK_RESPONSE);
    ASSERT_EQ(write32(b, address + 4, static_cast<uint32_t>(words[w] >> 32)), tlm::TLM_OK_RESPONSE);
  }
}

// Writes START and returns the time the write reached the AC: the bus
// forwards it at once and adds its address phase to the response.
sc_time start(Bench& b, unsigned entry) {
  write32(b, AC + regs::ENTRY, entry);
  const sc_time at = sc_core::sc_time_stamp();
  EXPECT_EQ(write32(b, AC + regs::START, 1), tlm::TLM_OK_RESPONSE);
  return at;
}

void wait_irq(Bench& b) {
  if (!b.irq.read()) sc_core::wait(b.irq.posedge_event());
}

void clear_irq(Bench& b) {
  write32(b, AC + regs::IRQ_STATUS, regs::IRQ_DONE | regs::IRQ_ERROR);
  sc_core::wait(CYCLE);
}

}  // namespace

TEST(Ciu, AWordLandsOneByteInEachOfFourAdjacentCusOfItsRow) {
  Bench& b = *g_bench;
  ap::CuArray& cus = b.array.core().array();
  test::run_thread([&] {
    EXPECT_EQ(b.host.write32(cmem_address(0, 0, 5), 0xffffffffu).status, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(b.host.write32(cmem_address(2, 1, 7), 0x44332211u).status, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(b.host.write32(cmem_address(5, 3, 4095), 0xa0b0c0d0u).status, tlm::TLM_OK_RESPONSE);
  });
  for (unsigned lane = 0; lane < 4; ++lane) EXPECT_EQ(cus.cmem(lane, 5), 0xff) << lane;
  EXPECT_EQ(cus.cmem(4, 5), 0);
  EXPECT_EQ(cus.cmem(COLUMNS, 5), 0);  // row 1 untouched
  // Group (2, 1): row 1, columns 8..11; byte 0 (0x11) in column 8.
  EXPECT_EQ(cus.cmem(COLUMNS + 8, 7), 0x11);
  EXPECT_EQ(cus.cmem(COLUMNS + 9, 7), 0x22);
  EXPECT_EQ(cus.cmem(COLUMNS + 10, 7), 0x33);
  EXPECT_EQ(cus.cmem(COLUMNS + 11, 7), 0x44);
  EXPECT_EQ(cus.cmem(COLUMNS + 12, 7), 0);
  // The last group of the last row, the last address.
  EXPECT_EQ(cus.cmem(3 * COLUMNS + 20, 4095), 0xd0);
  EXPECT_EQ(cus.cmem(3 * COLUMNS + 23, 4095), 0xa0);
  cus.set_cmem(COLUMNS + 10, 7, 0x99);
  test::run_thread([&] { EXPECT_EQ(b.host.read32(cmem_address(2, 1, 7)), 0x44992211u); });
}

// A burst's words follow CMEM's addresses of one group of four CUs, and
// past a group's last address the next group's first: the window is the
// groups one after another, 4096 words each.
TEST(Ciu, ABurstRunsOnFromAGroupsLastAddressToTheNextGroupsFirst) {
  Bench& b = *g_bench;
  ap::CuArray& cus = b.array.core().array();
  const uint32_t words[3] = {0x04030201u, 0x08070605u, 0x0c0b0a09u};
  uint32_t back[3] = {};
  test::run_thread([&] {
    // Group 5 is (5, 0), row 0's last; group 6 is (0, 1), row 1's first.
    const uint64_t at = cmem_address(5, 0, 4094);
    EXPECT_EQ(b.host.write(at, reinterpret_cast<const uint8_t*>(words), 12).status, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(b.host.read(at, reinterpret_cast<uint8_t*>(back), 12).status, tlm::TLM_OK_RESPONSE);
  });
  for (unsigned k = 0; k < 4; ++k) {
    EXPECT_EQ(cus.cmem(20 + k, 4094), 1 + k) << k;
    EXPECT_EQ(cus.cmem(20 + k, 4095), 5 + k) << k;
    EXPECT_EQ(cus.cmem(COLUMNS + k, 0), 9 + k) << k;
  }
  EXPECT_EQ(cus.cmem(COLUMNS + 4, 0), 0);
  for (unsigned w = 0; w < 3; ++w) EXPECT_EQ(back[w], words[w]) << w;
}

// A debugger's access (transport_dbg) takes any bytes, each where the
// word it is in puts it, across words and groups.
TEST(Ciu, ADebugAccessPlacesEachByteAsItsWordWould) {
  Bench& b = *g_bench;
  ap::CuArray& cus = b.array.core().array();
  uint8_t bytes[6] = {0xa1, 0xa2, 0xa3, 0xa4, 0xa5, 0xa6};
  const uint64_t at = cmem_address(5, 0, 4095) + 2;  // bytes 2 and 3 of group 5's last word, then group 6's first
  EXPECT_EQ(b.host.debug(tlm::TLM_WRITE_COMMAND, at, bytes, 6), 6u);
  EXPECT_EQ(cus.cmem(22, 4095), 0xa1);
  EXPECT_EQ(cus.cmem(23, 4095), 0xa2);
  for (unsigned k = 0; k < 4; ++k) EXPECT_EQ(cus.cmem(COLUMNS + k, 0), 0xa3 + k) << k;
  uint8_t back[6] = {};
  EXPECT_EQ(b.host.debug(tlm::TLM_READ_COMMAND, at, back, 6), 6u);
  for (unsigned i = 0; i < 6; ++i) EXPECT_EQ(back[i], bytes[i]) << i;
}

// The CIU says its accesses scheduled nothing (ScheduleUntouched, which
// lets the host keep running ahead); the AC's registers, which start
// programs, and a refused access do not.
TEST(Ciu, SaysItsAccessesScheduleNothingAndTheAcsDoNot) {
  Bench& b = *g_bench;
  const auto untouched = [&](uint64_t address, unsigned length) {
    tlm::tlm_generic_payload gp;
    auto* extension = new ScheduleUntouched;
    gp.set_extension(extension);
    uint8_t data[8] = {};
    gp.set_command(tlm::TLM_WRITE_COMMAND);
    gp.set_address(address);
    gp.set_data_ptr(data);
    gp.set_data_length(length);
    gp.set_streaming_width(length);
    gp.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    sc_time delay = CYCLE;
    b.host.out->b_transport(gp, delay);
    sc_core::wait(delay);
    return extension->untouched;  // the payload deletes the extension
  };
  test::ReportCapture capture;
  test::run_thread([&] {
    EXPECT_TRUE(untouched(cmem_address(1, 2, 3), 4));
    EXPECT_TRUE(untouched(cmem_address(1, 2, 3), 8));
    EXPECT_FALSE(untouched(cmem_address(1, 2, 3) + 2, 4)) << "refused: not a whole word";
    EXPECT_FALSE(untouched(AC + regs::ENTRY, 4));
  });
}

TEST(Ciu, EachWordCostsItsCyclesOfTheArrayClock) {
  Bench& b = *g_bench;
  test::run_thread([&] {
    const auto write = b.host.write32(cmem_address(1, 1, 1), 1);
    sc_core::wait(write.delay);
    test::TestInitiator::Result read{};
    b.host.read32(cmem_address(1, 1, 1), &read);
    sc_core::wait(read.delay);
    // The bus's address phase (one cycle), then the CIU's latency.
    EXPECT_EQ(write.delay, CYCLE * (1.0 + WRITE_CYCLES));
    EXPECT_EQ(read.delay, CYCLE * (1.0 + READ_CYCLES));
    // A burst of three words: three words' latency.
    uint8_t data[12] = {};
    const auto burst_write = b.host.write(cmem_address(1, 1, 1), data, 12);
    sc_core::wait(burst_write.delay);
    const auto burst_read = b.host.read(cmem_address(1, 1, 1), data, 12);
    sc_core::wait(burst_read.delay);
    EXPECT_EQ(burst_write.delay, CYCLE * (1.0 + 3 * WRITE_CYCLES));
    EXPECT_EQ(burst_read.delay, CYCLE * (1.0 + 3 * READ_CYCLES));
  });
}

TEST(Ciu, GrantsNoDirectPointerAndAnswersANonBlockingCallWithACommandError) {
  Bench& b = *g_bench;
  test::ReportCapture capture;
  tlm::tlm_generic_payload gp;
  gp.set_command(tlm::TLM_READ_COMMAND);
  gp.set_address(cmem_address(0, 0, 0));
  tlm::tlm_dmi dmi;
  EXPECT_FALSE(b.host.out->get_direct_mem_ptr(gp, dmi));
  EXPECT_EQ(dmi.get_dmi_ptr(), nullptr);

  const uint64_t errors = b.ciu.counters().value("errors");
  uint32_t word = 0;
  gp.set_address(0);
  gp.set_data_ptr(reinterpret_cast<uint8_t*>(&word));
  gp.set_data_length(4);
  gp.set_streaming_width(4);
  tlm::tlm_phase phase = tlm::BEGIN_REQ;
  sc_time delay = sc_core::SC_ZERO_TIME;
  EXPECT_EQ(b.ciu.in.get_base_interface().nb_transport_fw(gp, phase, delay), tlm::TLM_COMPLETED);
  EXPECT_EQ(gp.get_response_status(), tlm::TLM_COMMAND_ERROR_RESPONSE);
  EXPECT_EQ(b.ciu.counters().value("errors"), errors + 1);
  EXPECT_TRUE(capture.contains("nb_transport_fw is not supported"));
}

TEST(Ciu, BadAccessesAreErrorsNamingTheAddress) {
  Bench& b = *g_bench;
  test::ReportCapture capture;
  const uint64_t errors = b.ciu.counters().value("errors");
  test::run_thread([&] {
    uint16_t half = 0;
    EXPECT_EQ(b.host.read(cmem_address(0, 0, 0), reinterpret_cast<uint8_t*>(&half), 2).status,
              tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(b.host.write32(cmem_address(0, 0, 0) + 2, 0).status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
    // Beyond the last group: 96 CUs x 4096 bytes.
    EXPECT_EQ(b.host.write32(CMEM + 96u * CMEM_BYTES, 0).status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  });
  EXPECT_EQ(b.ciu.counters().value("errors"), errors + 3);
  EXPECT_TRUE(capture.contains("60000")) << "the log names the offset beyond CMEM";
}

TEST(ArrayProcessor, RunsALoadedProgramAndRaisesItsInterruptAfterItsCycles) {
  Bench& b = *g_bench;
  ap::CuArray& cus = b.array.core().array();
  // c = a + b, 16-bit big-endian at 0x100 (a), 0x102 (b), 0x104 (c), over
  // 4 passes at 0x100 + 8k (loop k = 24, 16, 8, 0).
  const std::vector<uint64_t> program = {
      loop(0, 24, 8),
      op(ap::Opcode::op_add, mem(0x105, 1), mem(0x101, 1), mem(0x103, 1)),
      op(ap::Opcode::op_adc, mem(0x104, 1), mem(0x100, 1), mem(0x102, 1)),
      op(ap::Opcode::op_endloop),
      op(ap::Opcode::op_halt),
  };
  // 1 (loop) + 4 x (3 + 3 + 0) + 1 (halt)
  const unsigned cycles = 1 + 4 * 6 + 1;
  for (unsigned lane = 0; lane < cus.lanes(); ++lane)
    for (unsigned k = 0; k < 4; ++k) {
      const unsigned base = 0x100 + 8 * k;
      const uint16_t x = static_cast<uint16_t>(lane * 300 + k * 7000), y = static_cast<uint16_t>(lane * 211 + 999);
      cus.set_cmem(lane, base, x >> 8);
      cus.set_cmem(lane, base + 1, x & 0xff);
      cus.set_cmem(lane, base + 2, y >> 8);
      cus.set_cmem(lane, base + 3, y & 0xff);
    }
  sc_time started, raised, read_done;
  uint32_t busy_status = 0;
  test::run_thread([&] {
    load(b, 16, program);
    write32(b, AC + regs::IRQ_ENABLE, regs::IRQ_DONE | regs::IRQ_ERROR);
    started = start(b, 16);
    busy_status = read32(b, AC + regs::STATUS);
    wait_irq(b);
    raised = sc_core::sc_time_stamp();
    EXPECT_EQ(read32(b, AC + regs::IRQ_STATUS), regs::IRQ_DONE);
    EXPECT_EQ(read32(b, AC + regs::STATUS) & (regs::STATUS_BUSY | regs::STATUS_DONE), regs::STATUS_DONE);
    EXPECT_EQ(read32(b, AC + regs::CYCLES), cycles);
    EXPECT_EQ(read32(b, AC + regs::STAGE_CYCLES0), cycles);  // no stage markers: all "other"
    clear_irq(b);
    EXPECT_FALSE(b.irq.read());
  });
  EXPECT_EQ(busy_status & regs::STATUS_BUSY, regs::STATUS_BUSY);
  // The run begins one array clock after START reaches the AC and lasts its cycles.
  const sc_time run_begins = started + CYCLE;
  EXPECT_EQ(raised, run_begins + CYCLE * static_cast<double>(cycles));
  for (unsigned lane = 0; lane < cus.lanes(); ++lane)
    for (unsigned k = 0; k < 4; ++k) {
      const unsigned base = 0x100 + 8 * k;
      const auto x = static_cast<uint16_t>(lane * 300 + k * 7000), y = static_cast<uint16_t>(lane * 211 + 999);
      const auto sum = static_cast<uint16_t>(x + y);
      ASSERT_EQ(cus.cmem(lane, base + 4), sum >> 8) << lane << " " << k;
      ASSERT_EQ(cus.cmem(lane, base + 5), sum & 0xff) << lane << " " << k;
    }
}

TEST(ArrayProcessor, WhileAProgramRunsCmemWaitsAndTheAcRefusesWrites) {
  Bench& b = *g_bench;
  test::ReportCapture capture;
  // 1 + 100 x 40 + 1 cycles of multiplies.
  const std::vector<uint64_t> program = {
      loop(0, 99, 1),
      op(ap::Opcode::op_mul, reg(0), reg(3), reg(5)),
      op(ap::Opcode::op_endloop),
      op(ap::Opcode::op_halt),
  };
  const unsigned cycles = 1 + 100 * 40 + 1;
  test::run_thread([&] {
    load(b, 40, program);
    const sc_time started = start(b, 40);
    const sc_time run_end = started + CYCLE + CYCLE * static_cast<double>(cycles);
    EXPECT_EQ(write32(b, AC + regs::START, 1), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(write32(b, AC + regs::ENTRY, 0), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(write32(b, PROGRAM, 0), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_NE(read32(b, AC + regs::STATUS) & regs::STATUS_REFUSED, 0u);
    // A CMEM read waits for the program's end, then takes its own time
    // and the bus's address phase.
    const sc_time arrival = sc_core::sc_time_stamp();
    EXPECT_LT(arrival, run_end);
    test::TestInitiator::Result read{};
    b.host.read32(cmem_address(0, 0, 0), &read);
    EXPECT_EQ(arrival + read.delay, run_end + CYCLE * (READ_CYCLES + 1.0));
    if (sc_core::sc_time_stamp() < run_end) {
      wait_irq(b);
      EXPECT_EQ(sc_core::sc_time_stamp(), run_end);
    }
    EXPECT_TRUE(b.irq.read());
    EXPECT_EQ(read32(b, AC + regs::CYCLES), cycles);
    clear_irq(b);
    // After the run the AC takes writes again.
    EXPECT_EQ(write32(b, AC + regs::ENTRY, 40), tlm::TLM_OK_RESPONSE);
  });
  EXPECT_TRUE(capture.contains("written while a program runs"));
  EXPECT_TRUE(capture.contains("refused: a program runs"));
  EXPECT_GE(b.ciu.counters().value("stalled_accesses"), 1u);
  EXPECT_EQ(b.array.counters().value("program_memory.refused_writes"), 1u);
}

TEST(ArrayProcessor, BadProgramsStopWithAnErrorCodeAndTheWord) {
  Bench& b = *g_bench;
  test::ReportCapture capture;
  struct Case {
    std::vector<uint64_t> words;
    ap::RunError error;
    unsigned pc;  // relative to the load address
    const char* logged;
  };
  const std::vector<Case> cases = {
      // Loop variable up to 4095 + 4095 beyond CMEM.
      {{loop(0, 4095, 1), op(ap::Opcode::op_mov, reg(0), mem(4095, 1)), op(ap::Opcode::op_endloop),
        op(ap::Opcode::op_halt)},
       ap::RunError::cmem_address,
       1,
       "CMEM address 8190 is beyond the 4096 bytes"},
      {{uint64_t{1} << 63}, ap::RunError::bad_word, 0, "reserved bits"},
      {{op(ap::Opcode::op_endloop)}, ap::RunError::loop, 0, "endloop with no loop"},
      // A loop of 200 x 200 iterations of mul: past max_program_cycles.
      {{loop(0, 199, 1), loop(1, 199, 1), op(ap::Opcode::op_mul, reg(0), reg(3), reg(5)), op(ap::Opcode::op_endloop),
        op(ap::Opcode::op_endloop), op(ap::Opcode::op_halt)},
       ap::RunError::too_long,
       2,
       "array.max_program_cycles"},
      // The Image Blender's instructions, with their switches off (the default).
      {{op(ap::Opcode::op_mset), op(ap::Opcode::op_div, reg(0), reg(1), reg(3)), op(ap::Opcode::op_halt)},
       ap::RunError::bad_word,
       1,
       "div is not enabled: it needs array.features.divide = true"},
      {{op(ap::Opcode::op_nadd, reg(0), reg(1), reg(static_cast<unsigned>(ap::Direction::left))),
        op(ap::Opcode::op_halt)},
       ap::RunError::bad_word,
       0,
       "nadd is not enabled: it needs array.features.neighbour_add = true"},
      {{op(ap::Opcode::op_lut, reg(0), reg(2)), op(ap::Opcode::op_halt)},
       ap::RunError::bad_word,
       0,
       "lut is not enabled: it needs array.features.lut = true"},
      // MorphoSys's, likewise.
      {{op(ap::Opcode::op_mset), op(ap::Opcode::op_add16, reg(0), reg(2), reg(4)), op(ap::Opcode::op_halt)},
       ap::RunError::bad_word,
       1,
       "add16 is not enabled: it needs array.features.wide_ops = true"},
      {{loop(0, 3, 1), op(ap::Opcode::op_endloopany, {}, reg(static_cast<unsigned>(ap::Cond::nz))),
        op(ap::Opcode::op_halt)},
       ap::RunError::bad_word,
       1,
       "endloopany is not enabled: it needs array.features.wired_or_loop = true"},
  };
  test::run_thread([&] {
    for (const Case& c : cases) {
      load(b, 100, c.words);
      start(b, 100);
      wait_irq(b);
      EXPECT_EQ(read32(b, AC + regs::IRQ_STATUS), regs::IRQ_ERROR);
      EXPECT_EQ(read32(b, AC + regs::ERROR_CODE), static_cast<uint32_t>(c.error)) << c.logged;
      EXPECT_EQ(read32(b, AC + regs::ERROR_PC), 100 + c.pc) << c.logged;
      EXPECT_NE(read32(b, AC + regs::STATUS) & regs::STATUS_ERROR, 0u);
      EXPECT_TRUE(capture.contains(c.logged)) << c.logged;
      clear_irq(b);
    }
    // A start with no program: program memory's zeros are nops, and the
    // AC runs off the end of its memory.
    start(b, 200);
    wait_irq(b);
    EXPECT_EQ(read32(b, AC + regs::ERROR_CODE), static_cast<uint32_t>(ap::RunError::past_end));
    clear_irq(b);
    // Program memory beyond its 256 words, and half words.
    EXPECT_EQ(write32(b, PROGRAM + 256 * 8, 0), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    uint16_t half = 0;
    EXPECT_EQ(b.host.write(PROGRAM, reinterpret_cast<uint8_t*>(&half), 2).status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  });
  EXPECT_TRUE(capture.contains("past the end of program memory"));
  EXPECT_TRUE(capture.contains("outside the 2048-byte program memory"));
}

TEST(ArrayParams, FeatureSwitchesAreOffByDefaultAndEachEnablesItsInstruction) {
  const auto enabled = [](const ArrayParams& p, ap::Opcode opcode) {
    return p.enabled_ops[static_cast<unsigned>(opcode)];
  };
  const ArrayParams off = ArrayParams::defaults();
  EXPECT_FALSE(enabled(off, ap::Opcode::op_div));
  EXPECT_FALSE(enabled(off, ap::Opcode::op_nadd));
  EXPECT_TRUE(enabled(off, ap::Opcode::op_mul));
  EXPECT_EQ(off.cycles.cycles[static_cast<unsigned>(ap::Opcode::op_div)], 2u);
  Config config({ArrayParams::parameters()});
  config.apply_override("array.features.divide=true");
  const ArrayParams divide = ArrayParams::from_config(config);
  EXPECT_TRUE(enabled(divide, ap::Opcode::op_div));
  EXPECT_FALSE(enabled(divide, ap::Opcode::op_nadd));
  config.apply_override("array.features.neighbour_add=true");
  config.apply_override("array.cycles.div=40");
  const ArrayParams both = ArrayParams::from_config(config);
  EXPECT_TRUE(enabled(both, ap::Opcode::op_nadd));
  EXPECT_TRUE(enabled(both, ap::Opcode::op_nadds));
  EXPECT_TRUE(enabled(both, ap::Opcode::op_nadcs));
  EXPECT_EQ(both.cycles.cycles[static_cast<unsigned>(ap::Opcode::op_div)], 40u);
  // MorphoSys's: one switch for the four 16-bit operations, one for the loop.
  const std::array<ap::Opcode, 4> pairs{ap::Opcode::op_add16, ap::Opcode::op_sub16, ap::Opcode::op_cmp16,
                                        ap::Opcode::op_mov16};
  for (const ap::Opcode opcode : pairs) {
    EXPECT_FALSE(enabled(both, opcode));
    EXPECT_EQ(off.cycles.cycles[static_cast<unsigned>(opcode)], 4u);
  }
  EXPECT_FALSE(enabled(both, ap::Opcode::op_endloopany));
  EXPECT_EQ(off.cycles.cycles[static_cast<unsigned>(ap::Opcode::op_endloopany)], 2u);
  config.apply_override("array.features.wide_ops=true");
  for (const ap::Opcode opcode : pairs) EXPECT_TRUE(enabled(ArrayParams::from_config(config), opcode));
  EXPECT_FALSE(enabled(ArrayParams::from_config(config), ap::Opcode::op_endloopany));
  config.apply_override("array.features.wired_or_loop=true");
  EXPECT_TRUE(enabled(ArrayParams::from_config(config), ap::Opcode::op_endloopany));
  // The row ring: off by default; on, the core's rows are rings.
  EXPECT_FALSE(off.row_ring);
  EXPECT_FALSE(off.enabled_ops[static_cast<unsigned>(ap::Opcode::op_nadds)]);
  config.apply_override("array.row_ring=true");
  EXPECT_TRUE(ArrayParams::from_config(config).row_ring);
  EXPECT_FALSE(g_bench->array.core().array().row_ring());
  EXPECT_TRUE(g_bench->blender.core().array().row_ring());
}

constexpr const char* ROW_LUT_TOO_SLOW =
    "array.issue_skew=row array.issue_skew_cycles=5 array.features.lut=true array.lut.ports=4";

// What each bad setting was refused with ("" if accepted), worked out in
// sc_main before the simulation: an exception thrown on sc_main's stack
// after the kernel has switched to its processes and back confuses the
// address sanitizer's view of the stack (the sanitize preset).
std::map<std::string, std::string> g_refusals;

// `settings`: one or more key=value, separated by spaces.
std::string refusal(const std::string& settings) {
  try {
    Config config({ArrayParams::parameters()});
    std::istringstream words(settings);
    for (std::string setting; words >> setting;) config.apply_override(setting);
    config.validate();
    (void)ArrayParams::from_config(config);
  } catch (const std::exception& error) {
    return error.what();
  }
  return "";
}

// The last: under row skew a row's 24 lookups on 4 ports take 6 cycles,
// more than K = 5.
const char* const BAD_SETTINGS[] = {
    "array.issue_skew=column", "array.issue_skew_cycles=0", "array.issue_skew=row array.issue_skew_cycles=1001",
    "array.lut.entries=65537", "array.lut.ports=0",         ROW_LUT_TOO_SLOW};
const char* const GOOD_SETTINGS[] = {
    "array.issue_skew=row array.issue_skew_cycles=4",
    "array.issue_skew=row array.issue_skew_cycles=6 array.features.lut=true array.lut.ports=4",
    "array.issue_skew=row array.issue_skew_cycles=5 array.lut.ports=4"};

// The wired OR under delayed execution: each setting alone is fine, the
// two together are refused by the group's validation.
std::string combination_refusal() {
  try {
    Config config({ArrayParams::parameters()});
    config.apply_override("array.features.wired_or_loop=true");
    config.apply_override("array.issue_skew=lane");
    config.validate();
  } catch (const std::exception& error) {
    return error.what();
  }
  return "";
}

void work_out_refusals() {
  for (const char* bad : BAD_SETTINGS) g_refusals[bad] = refusal(bad);
  g_refusals["wired_or_loop under skew"] = combination_refusal();
  for (const char* good : GOOD_SETTINGS) g_refusals[good] = refusal(good);
}

TEST(ArrayParams, BadIssueSkewIsRefusedNamingTheKeyAndValue) {
  const std::string& skew = g_refusals.at("array.issue_skew=column");
  EXPECT_NE(skew.find("array.issue_skew"), std::string::npos) << skew;
  EXPECT_NE(skew.find("column"), std::string::npos) << skew;
  for (const char* bad : BAD_SETTINGS) EXPECT_NE(g_refusals.at(bad), "") << bad << " accepted";
  const std::string& wired = g_refusals.at("wired_or_loop under skew");
  EXPECT_NE(wired.find("array.features.wired_or_loop=true with array.issue_skew=lane"), std::string::npos) << wired;
  for (const char* good : GOOD_SETTINGS) EXPECT_EQ(g_refusals.at(good), "") << good;
  const std::string& range = g_refusals.at("array.issue_skew=row array.issue_skew_cycles=1001");
  EXPECT_NE(range.find("array.issue_skew_cycles"), std::string::npos) << range;
  const std::string& lut = g_refusals.at(ROW_LUT_TOO_SLOW);
  for (const char* key : {"array.issue_skew", "array.lut.ports", "array.columns", "array.issue_skew_cycles"})
    EXPECT_NE(lut.find(key), std::string::npos) << lut;
  const ArrayParams defaults = ArrayParams::defaults();
  EXPECT_EQ(defaults.issue_skew_cycles, 0u);
  EXPECT_EQ(defaults.issue_skew, ap::IssueSkew::none);
  EXPECT_FALSE(defaults.lut_enabled());
}

// The J2210 (every switch off) has no table: LUT_ENTRIES reads 0 and the
// table's registers refuse writes, naming the switch.
TEST(ArrayProcessor, WithoutTheSwitchTheTablesRegistersRefuseWrites) {
  Bench& b = *g_bench;
  test::ReportCapture capture;
  test::run_thread([&] {
    EXPECT_EQ(read32(b, AC + regs::LUT_ENTRIES), 0u);
    EXPECT_EQ(write32(b, AC + regs::LUT_INDEX, 0), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(write32(b, AC + regs::LUT_DATA, 7), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(read32(b, AC + regs::LUT_DATA), 0u);
    EXPECT_EQ(read32(b, AC + regs::STATUS) & regs::STATUS_REFUSED, 0u);
  });
  EXPECT_TRUE(capture.contains("the lookup table needs array.features.lut = true"));
}

// The host fills the table through LUT_INDEX and LUT_DATA; a program's lut
// reads it, and under delayed execution the program takes its cycles plus
// the chain's skew (95 cycles with K = 1).
TEST(ArrayProcessor, TheHostFillsTheTableAndASkewedProgramLooksItUp) {
  Bench& b = *g_bench;
  test::ReportCapture capture;
  ap::CuArray& cus = b.blender.core().array();
  for (unsigned l = 0; l < cus.lanes(); ++l) cus.set_reg(l, 3, static_cast<uint8_t>(l % LUT_ENTRIES));
  test::run_thread([&] {
    EXPECT_EQ(read32(b, BLENDER_AC + regs::LUT_ENTRIES), LUT_ENTRIES);
    EXPECT_EQ(write32(b, BLENDER_AC + regs::LUT_INDEX, 0), tlm::TLM_OK_RESPONSE);
    for (unsigned i = 0; i < LUT_ENTRIES; ++i)
      EXPECT_EQ(write32(b, BLENDER_AC + regs::LUT_DATA, 0xabcd0000u | (1000 + i)), tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(read32(b, BLENDER_AC + regs::LUT_INDEX), LUT_ENTRIES);
    // One past the table: refused, naming the index and the key.
    EXPECT_EQ(write32(b, BLENDER_AC + regs::LUT_DATA, 1), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(write32(b, BLENDER_AC + regs::LUT_INDEX, 5), tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(read32(b, BLENDER_AC + regs::LUT_DATA), 1005u);
    EXPECT_EQ(read32(b, BLENDER_AC + regs::LUT_INDEX), 5u) << "a read does not step the index";
    // mset 1, lut 2, halt 1, then the skew: 95.
    const std::vector<uint64_t> words = {op(ap::Opcode::op_mset), op(ap::Opcode::op_lut, reg(0), reg(2)),
                                         op(ap::Opcode::op_halt)};
    for (size_t w = 0; w < words.size(); ++w) {
      const uint64_t address = BLENDER_PROGRAM + w * regs::PROGRAM_WORD_BYTES;
      EXPECT_EQ(write32(b, address, static_cast<uint32_t>(words[w])), tlm::TLM_OK_RESPONSE);
      EXPECT_EQ(write32(b, address + 4, static_cast<uint32_t>(words[w] >> 32)), tlm::TLM_OK_RESPONSE);
    }
    write32(b, BLENDER_AC + regs::IRQ_ENABLE, regs::IRQ_DONE | regs::IRQ_ERROR);
    write32(b, BLENDER_AC + regs::ENTRY, 0);
    const sc_time at = sc_core::sc_time_stamp();
    EXPECT_EQ(write32(b, BLENDER_AC + regs::START, 1), tlm::TLM_OK_RESPONSE);
    // While it runs the table is the CUs': the host's write is refused.
    EXPECT_EQ(write32(b, BLENDER_AC + regs::LUT_INDEX, 0), tlm::TLM_COMMAND_ERROR_RESPONSE);
    if (!b.blender_irq.read()) sc_core::wait(b.blender_irq.posedge_event());
    // The run begins one array clock after START reaches the AC and lasts its cycles.
    EXPECT_EQ(sc_core::sc_time_stamp(), at + CYCLE * (1.0 + 99));
    EXPECT_EQ(read32(b, BLENDER_AC + regs::CYCLES), 1u + 2 + 1 + 95);
  });
  EXPECT_TRUE(capture.contains("LUT_INDEX 64 is beyond the table's 64 entries (array.lut.entries)"));
  for (unsigned l = 0; l < cus.lanes(); ++l) {
    const unsigned entry = 1000 + l % LUT_ENTRIES;
    EXPECT_EQ(cus.reg(l, 0), entry >> 8) << l;
    EXPECT_EQ(cus.reg(l, 1), entry & 0xff) << l;
  }
  const auto stats = b.blender.stats_json(sc_core::sc_time_stamp());
  EXPECT_EQ(stats["issue_skew"]["cycles"], 95);
  EXPECT_EQ(stats["lut"]["lookups"], 96);
  EXPECT_EQ(stats["lut"]["stall_cycles"], 0);
  EXPECT_EQ(stats["lut"]["host_writes"], LUT_ENTRIES);
  EXPECT_EQ(stats["mix"]["lut"], 1);
}

// MorphoSys's machine: each CU counts its own number down and adds a
// 16-bit step per pass; the loop ends when the last CU's count reaches 0
// (30 passes of at most 101), and the interrupt comes at the cycles of the
// passes run. The wired-OR statistics exist on this array only.
TEST(ArrayProcessor, AWiredOrLoopEndsWithTheLastCusCountAndCountsItsExit) {
  Bench& b = *g_bench;
  ap::CuArray& cus = b.morpho.core().array();
  for (unsigned l = 0; l < cus.lanes(); ++l) {
    cus.set_cmem(l, 0, 1);
    cus.set_cmem(l, 1, static_cast<uint8_t>(l == 50 ? 30 : 1 + l % 8));
    for (unsigned r = 2; r < 6; ++r) cus.set_reg(l, r, r < 4 ? 0 : 1);  // r2:r3 = 0, r4:r5 = 0x0101
  }
  const std::vector<uint64_t> words = {
      op(ap::Opcode::op_mset),                                                      // 1
      op(ap::Opcode::op_mov, reg(1), mem(0)),                                       // 3
      op(ap::Opcode::op_mov, reg(0), mem(1)),                                       // 3
      loop(0, 100, 1),                                                              // 1
      op(ap::Opcode::op_add16, reg(2), reg(2), reg(4)),                             // 4 a pass
      op(ap::Opcode::op_sub, reg(0), reg(0), reg(1)),                               // 2 a pass
      op(ap::Opcode::op_mand, {}, reg(static_cast<unsigned>(ap::Cond::nz))),        // 1 a pass
      op(ap::Opcode::op_endloopany, {}, reg(static_cast<unsigned>(ap::Cond::nz))),  // 2 a pass
      op(ap::Opcode::op_halt)};                                                     // 1
  constexpr unsigned PASSES = 30, CYCLES = 1 + 3 + 3 + 1 + PASSES * (2 + 4 + 1 + 2) + 1;
  test::run_thread([&] {
    for (size_t w = 0; w < words.size(); ++w) {
      const uint64_t address = MORPHO_PROGRAM + w * regs::PROGRAM_WORD_BYTES;
      EXPECT_EQ(write32(b, address, static_cast<uint32_t>(words[w])), tlm::TLM_OK_RESPONSE);
      EXPECT_EQ(write32(b, address + 4, static_cast<uint32_t>(words[w] >> 32)), tlm::TLM_OK_RESPONSE);
    }
    write32(b, MORPHO_AC + regs::IRQ_ENABLE, regs::IRQ_DONE | regs::IRQ_ERROR);
    write32(b, MORPHO_AC + regs::ENTRY, 0);
    const sc_time at = sc_core::sc_time_stamp();
    EXPECT_EQ(write32(b, MORPHO_AC + regs::START, 1), tlm::TLM_OK_RESPONSE);
    if (!b.morpho_irq.read()) sc_core::wait(b.morpho_irq.posedge_event());
    EXPECT_EQ(sc_core::sc_time_stamp(), at + CYCLE * (1.0 + CYCLES));
    EXPECT_EQ(read32(b, MORPHO_AC + regs::CYCLES), CYCLES);
    EXPECT_EQ(read32(b, MORPHO_AC + regs::IRQ_STATUS), regs::IRQ_DONE);
  });
  for (unsigned l = 0; l < cus.lanes(); ++l) {
    EXPECT_EQ(cus.reg(l, 2), PASSES) << l;  // 30 x 0x0101
    EXPECT_EQ(cus.reg(l, 3), PASSES) << l;
  }
  const auto stats = b.morpho.stats_json(sc_core::sc_time_stamp());
  EXPECT_EQ(stats["wired_or"]["exits"], 1);
  EXPECT_EQ(stats["wired_or"]["iterations_saved"], 101 - PASSES);
  EXPECT_EQ(stats["mix"]["add16"], PASSES);
  EXPECT_EQ(stats["mix"]["endloopany"], PASSES);
  EXPECT_EQ(stats["mix"]["sub16"], 0);
  EXPECT_EQ(stats["cycles"]["total"], CYCLES);
  uint64_t profile = 0;
  for (const auto& line : stats["profile"]) profile += line["cycles"].get<uint64_t>();
  EXPECT_EQ(profile, CYCLES);
}

TEST(ArrayProcessor, StatisticsAndSummaryRows) {
  Bench& b = *g_bench;
  const sc_time now = sc_core::sc_time_stamp();
  const auto stats = b.array.stats_json(now);
  EXPECT_EQ(stats["programs"], b.array.counters().value("programs"));
  EXPECT_GE(stats["mix"]["mul"].get<uint64_t>(), 100u);
  // Instructions that are not enabled have no counter: a J2210's statistics.
  EXPECT_FALSE(stats["mix"].contains("div"));
  EXPECT_FALSE(stats["mix"].contains("nadd"));
  EXPECT_FALSE(stats["mix"].contains("lut"));
  EXPECT_FALSE(stats["mix"].contains("add16"));
  EXPECT_FALSE(stats["mix"].contains("endloopany"));
  // Nor is there a skew, a table or a wired OR.
  EXPECT_FALSE(stats.contains("issue_skew"));
  EXPECT_FALSE(stats.contains("lut"));
  EXPECT_FALSE(stats.contains("wired_or"));
  EXPECT_GT(stats["cmem"]["bytes_written"].get<uint64_t>(), 0u);
  EXPECT_EQ(stats["programs_by_entry"]["16"]["cycles"], 26);
  // One sample per program run, of its cycles: the program at word 16 ran
  // once, in 26 cycles (bucket 16-31).
  const auto& runs = stats["histograms"]["program_cycles"];
  EXPECT_EQ(runs["count"], stats["programs"]);
  EXPECT_EQ(runs["sum"], stats["cycles"]["total"]);
  uint64_t in_16_to_31 = 0;
  for (const auto& bucket : runs["buckets"])
    if (bucket["low"] == 16) in_16_to_31 = bucket["count"].get<uint64_t>();
  EXPECT_GE(in_16_to_31, 1u);
  // The profile names each word that ran, with its instruction.
  bool found = false;
  for (const auto& line : stats["profile"])
    if (line["word"] == 41) {
      found = true;
      EXPECT_EQ(line["instruction"], "mul r0, r3, r5");
      EXPECT_EQ(line["cycles"].get<uint64_t>() % 40, 0u);
    }
  EXPECT_TRUE(found);
  const SummaryRow row = b.array.summary_row(now);
  EXPECT_NE(row.notes.find("programs"), std::string::npos);
  const auto ciu = b.ciu.stats_json(now);
  EXPECT_GE(ciu["writes"].get<uint64_t>(), 3u);
  EXPECT_GT(ciu["stall_ns"].get<double>(), 0.0);
  EXPECT_EQ(b.check_host.violation_count(), 0u);
}

// The activity of each stage's instructions alone (what the energy of the
// study's passes, without the clears, is computed from): a program of one
// fill and two depth instructions gives each stage its own instructions,
// cycles and CMEM bytes, and the stages add up to the whole.
TEST(ArrayProcessor, StageActivityHoldsEachStagesOwnInstructionsCyclesAndCmemBytes) {
  Bench& b = *g_bench;
  const auto staged = [](uint64_t word, ap::Stage stage) {
    ap::Instruction in = ap::decode(word).instruction;
    in.stage = stage;
    return ap::encode(in);
  };
  const uint64_t add = op(ap::Opcode::op_add, mem(0x205), mem(0x201), mem(0x203));
  const std::vector<uint64_t> program = {staged(add, ap::Stage::fill), staged(add, ap::Stage::depth),
                                         staged(add, ap::Stage::depth),
                                         staged(op(ap::Opcode::op_halt), ap::Stage::depth)};
  const auto by_stage = [&] {
    std::map<std::string, std::map<std::string, double>> counts;
    for (const ArrayProcessor::StageActivity& stage : b.array.stage_activity()) {
      counts[stage.stage]["seconds"] = stage.seconds;
      for (const UnitActivity& unit : stage.units)
        for (const auto& [event, count] : unit.counts) counts[stage.stage][event] = count;
    }
    return counts;
  };
  auto before = by_stage();
  test::run_thread([&] {
    load(b, 200, program);
    start(b, 200);
    wait_irq(b);
    clear_irq(b);
  });
  auto after = by_stage();
  const double lanes = b.array.core().array().lanes();
  // An add of two CMEM operands: 3 cycles, 2 bytes read and 1 written per lane; the halt 1 cycle.
  const auto expect = [&](const std::string& stage, double instructions, double cycles, double reads, double writes) {
    EXPECT_EQ(after[stage]["broadcasts"] - before[stage]["broadcasts"], instructions) << stage;
    EXPECT_EQ(after[stage]["cu_cycles"] - before[stage]["cu_cycles"], lanes * cycles) << stage;
    EXPECT_NEAR(after[stage]["seconds"] - before[stage]["seconds"], cycles * CYCLE.to_seconds(), 1e-15) << stage;
    EXPECT_EQ(after[stage]["cmem_bytes_read"] - before[stage]["cmem_bytes_read"], reads) << stage;
    EXPECT_EQ(after[stage]["cmem_bytes_written"] - before[stage]["cmem_bytes_written"], writes) << stage;
  };
  expect("fill", 1, 3, 2 * lanes, lanes);
  expect("depth", 3, 2 * 3 + 1, 4 * lanes, 2 * lanes);
  // The stages together hold the array's whole CMEM traffic (the cycles and
  // instructions of the earlier tests' runaway programs, stopped before they
  // ran, belong to no stage).
  std::map<std::string, double> sum;
  for (const auto& [stage, counts] : after)
    for (const auto& [event, count] : counts) sum[event] += count;
  for (const UnitActivity& unit : b.array.energy_activity(sc_core::sc_time_stamp()))
    for (const auto& [event, count] : unit.counts) {
      if (event.rfind("cmem_", 0) == 0 || event == "neighbour_transfers") {
        EXPECT_EQ(sum[event], count) << event;
      }
    }
}

int sc_main(int argc, char* argv[]) {
  work_out_refusals();
  g_bench = new Bench("bench");
  return test::run_all_tests(argc, argv);
}

// The AC's broadcasts for the energy model: one per instruction, but a
// multiplication of CMEM operands counts the CMEM-operand additions it
// stands for, its 105 cycles over an addition's 2 + 1: 35 (the register
// mul counts one). In the whole run's activity and in its stage's.
TEST(ArrayProcessor, CmemMultiplyCountsItsAdditionsAsBroadcasts) {
  Bench& b = *g_bench;
  const auto broadcasts = [&] {
    double whole = 0, stages = 0;
    for (const UnitActivity& unit : b.array.energy_activity(sc_core::sc_time_stamp()))
      if (unit.unit == "array_controller") whole = unit.counts.at("broadcasts");
    for (const ArrayProcessor::StageActivity& stage : b.array.stage_activity())
      for (const UnitActivity& unit : stage.units)
        if (unit.unit == "array_controller") stages += unit.counts.at("broadcasts");
    return std::make_pair(whole, stages);
  };
  const std::vector<uint64_t> program = {op(ap::Opcode::op_mulm, mem(0x210), mem(0x201), mem(0x203)),
                                         op(ap::Opcode::op_mul, reg(3), reg(0), reg(2)), op(ap::Opcode::op_halt)};
  const auto before = broadcasts();
  test::run_thread([&] {
    load(b, 240, program);
    start(b, 240);
    wait_irq(b);
    clear_irq(b);
  });
  const auto after = broadcasts();
  EXPECT_DOUBLE_EQ(after.first - before.first, 35.0 + 1 + 1);
  EXPECT_DOUBLE_EQ(after.second - before.second, 35.0 + 1 + 1);
}
