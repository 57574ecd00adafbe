// TLM tests of the z-buffer unit (tlm/zbuf/zbuf_unit.h) beside an array on a
// bus: its registers, the window's refusal, a clear and its time, a program
// whose zsend fills the planes, the colour window waiting for the program,
// writes refused while it runs; and the configuration's refusals, naming
// the key.
//
// Bench: initiator -> bus (100 MHz) -> AC registers at 0, program memory at
// 0x10000, z-buffer registers at 0x3000, colour window at 0x100000. The
// array clock is also 100 MHz.
#include <cstring>
#include <map>
#include <string>

#include "array/array_processor.h"
#include "array/array_regs.h"
#include "bus/ahb_bus.h"
#include "tlm_bench/bench_params.h"
#include "tlm_bench/tlm_test_support.h"
#include "zbuf/zbuf_regs.h"
#include "zbuf/zbuf_unit.h"

using namespace tessera;
using sc_core::sc_time;
namespace zregs = zbuf_regs;
namespace aregs = array_regs;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);
constexpr uint64_t AC = 0x0, PROGRAM = 0x10000, ZBUF = 0x3000, COLOUR = 0x100000;
constexpr unsigned ENTRIES = 4096, LANES = 96;

ArrayParams array_params() {
  Config config({ArrayParams::parameters()});
  config.apply_override("array.features.zsend=true");
  ArrayParams p = ArrayParams::from_config(config);
  p.clock_period = CYCLE;
  p.program_words = 64;
  return p;
}

ZbufParams zbuf_params() {
  ZbufParams p = ZbufParams::defaults();
  p.enabled = true;
  p.core.entries = ENTRIES;
  p.core.ports = 2;
  p.core.pair_halves_only = true;
  p.clock_period = CYCLE;
  return p;
}

struct Bench : sc_core::sc_module {
  test::TestInitiator host;
  AhbBus bus;
  ArrayProcessor array;
  ZbufUnit zbuf;
  sc_core::sc_signal<bool> irq;
  explicit Bench(sc_core::sc_module_name name)
      : sc_core::sc_module(name),
        host("host"),
        bus("bus", test::bench_bus_params(CYCLE)),
        array("array", array_params()),
        zbuf("zbuf", zbuf_params(), array) {
    bus.attach(host.out, "host", 0);
    bus.map(array.in, AC, 0x1000, "array_regs");
    bus.map(array.program_in, PROGRAM, 0x10000, "array_program");
    bus.map(zbuf.in, ZBUF, 0x1000, "zbuf_regs");
    bus.map(zbuf.colour_in, COLOUR, 0x20000, "zbuf_colour");
    array.irq.bind(irq);
    array.core().set_pixel_port(&zbuf);
  }
};

Bench* g_bench = nullptr;

tlm::tlm_response_status write32(uint64_t address, uint32_t value) {
  const auto result = g_bench->host.write32(address, value);
  sc_core::wait(result.delay);
  return result.status;
}
uint32_t read32(uint64_t address, sc_time* delay = nullptr) {
  test::TestInitiator::Result result{};
  const uint32_t value = g_bench->host.read32(address, &result);
  if (delay != nullptr) *delay = result.delay;
  sc_core::wait(result.delay);
  return value;
}

uint64_t zsend_r0_r4() {
  ap::Instruction in;
  in.opcode = ap::Opcode::op_zsend;
  in.a = {false, 0, 0};
  in.b = {false, 4, 0};
  return ap::encode(in);
}
uint64_t halt() {
  ap::Instruction in;
  in.opcode = ap::Opcode::op_halt;
  return ap::encode(in);
}

}  // namespace

TEST(ZbufUnit, RegistersShowTheConfiguration) {
  test::run_thread([&] {
    EXPECT_EQ(read32(ZBUF + zregs::ID), zregs::ID_VALUE);
    EXPECT_EQ(read32(ZBUF + zregs::ENTRIES), ENTRIES);
    EXPECT_EQ(read32(ZBUF + zregs::PORTS), 2u | zregs::PORTS_PAIR_HALVES_ONLY);
    EXPECT_EQ(read32(ZBUF + zregs::CLEAR_DEPTH), 0xffffu);
    EXPECT_EQ(read32(ZBUF + zregs::STATUS), 0u);
  });
}

TEST(ZbufUnit, AWindowBeyondTheEntriesIsRefusedNamingTheKey) {
  test::ReportCapture capture;
  test::run_thread([&] {
    EXPECT_EQ(write32(ZBUF + zregs::FRAME_SIZE, 65u | 64u << 16), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_NE(read32(ZBUF + zregs::STATUS) & zregs::STATUS_REFUSED, 0u);
    EXPECT_EQ(write32(ZBUF + zregs::FRAME_SIZE, 64u | 64u << 16), tlm::TLM_OK_RESPONSE);
  });
  EXPECT_TRUE(capture.contains("zbuf.entries"));
  EXPECT_EQ(g_bench->zbuf.core().width(), 64u);
  EXPECT_EQ(g_bench->zbuf.core().height(), 64u);
}

TEST(ZbufUnit, AClearTakesAnEntryPerPortPerCycleAndTheWindowWaitsForIt) {
  test::run_thread([&] {
    EXPECT_EQ(write32(ZBUF + zregs::FRAME_ORIGIN, 0), tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(write32(ZBUF + zregs::FRAME_SIZE, 16u | 8u << 16), tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(write32(ZBUF + zregs::CLEAR_DEPTH, 0x8000), tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(write32(ZBUF + zregs::CLEAR_COLOUR, 0x1234), tlm::TLM_OK_RESPONSE);
    // The command reaches the unit as the write starts (the bus adds its
    // cycle to the response); 128 entries, 2 ports: 64 cycles.
    const sc_time issued = sc_core::sc_time_stamp();
    EXPECT_EQ(write32(ZBUF + zregs::CONTROL, zregs::CONTROL_CLEAR), tlm::TLM_OK_RESPONSE);
    const sc_time done = issued + CYCLE * 64.0;
    EXPECT_NE(read32(ZBUF + zregs::STATUS) & zregs::STATUS_BUSY, 0u);
    // A second clear meanwhile is refused.
    EXPECT_EQ(write32(ZBUF + zregs::CONTROL, zregs::CONTROL_CLEAR), tlm::TLM_COMMAND_ERROR_RESPONSE);
    sc_time delay;
    const sc_time asked = sc_core::sc_time_stamp();
    EXPECT_EQ(read32(COLOUR + 4, &delay), 0x12341234u);
    // Waited for the clear, then one word's cycle and the bus's.
    EXPECT_EQ(asked + delay, done + CYCLE * 2.0);
    EXPECT_EQ(read32(ZBUF + zregs::STATUS) & zregs::STATUS_BUSY, 0u);
  });
  EXPECT_EQ(g_bench->zbuf.core().depth(127), 0x8000);
  EXPECT_EQ(g_bench->zbuf.core().depth(128), 0xffff);  // beyond the window
}

TEST(ZbufUnit, AProgramsSendsFillThePlanesAndTheWindowWaitsForTheProgram) {
  Bench& b = *g_bench;
  ap::CuArray& cus = b.array.core().array();
  // CU l sends (l % 16, l / 16), z = 100 - l, colour 0xc000 + l: 96 pixels
  // of a 16 x 8 window, two per pair: 48 cycles.
  for (unsigned lane = 0; lane < LANES; ++lane) {
    const uint16_t values[4] = {static_cast<uint16_t>(lane % 16), static_cast<uint16_t>(lane / 16),
                                static_cast<uint16_t>(100 - lane), static_cast<uint16_t>(0xc000 + lane)};
    for (unsigned i = 0; i < 4; ++i) {
      cus.set_reg(lane, 2 * i, static_cast<uint8_t>(values[i] >> 8));
      cus.set_reg(lane, 2 * i + 1, static_cast<uint8_t>(values[i]));
    }
  }
  test::run_thread([&] {
    ASSERT_EQ(write32(ZBUF + zregs::FRAME_SIZE, 16u | 8u << 16), tlm::TLM_OK_RESPONSE);
    ASSERT_EQ(write32(ZBUF + zregs::CLEAR_COLOUR, 0), tlm::TLM_OK_RESPONSE);
    ASSERT_EQ(write32(ZBUF + zregs::CONTROL, zregs::CONTROL_CLEAR), tlm::TLM_OK_RESPONSE);
    sc_core::wait(CYCLE * 100.0);
    const uint64_t words[2] = {zsend_r0_r4(), halt()};
    for (unsigned w = 0; w < 2; ++w) {
      ASSERT_EQ(write32(PROGRAM + 8 * w, static_cast<uint32_t>(words[w])), tlm::TLM_OK_RESPONSE);
      ASSERT_EQ(write32(PROGRAM + 8 * w + 4, static_cast<uint32_t>(words[w] >> 32)), tlm::TLM_OK_RESPONSE);
    }
    write32(AC + aregs::ENTRY, 0);
    const sc_time at = sc_core::sc_time_stamp();
    ASSERT_EQ(write32(AC + aregs::START, 1), tlm::TLM_OK_RESPONSE);
    // The run begins a clock after START reaches the AC and takes 2 (zsend)
    // + 46 (the halt's wait for the port) + 1 cycles.
    const sc_time end = b.array.busy_until();
    EXPECT_EQ(end, at + CYCLE * (1.0 + 49));
    EXPECT_NE(read32(ZBUF + zregs::STATUS) & zregs::STATUS_BUSY, 0u);
    EXPECT_EQ(write32(ZBUF + zregs::CONTROL, zregs::CONTROL_CLEAR), tlm::TLM_COMMAND_ERROR_RESPONSE);
    sc_time delay;
    const sc_time asked = sc_core::sc_time_stamp();
    // Entries 34 and 35: CUs 34 and 35, low entry in the low half.
    EXPECT_EQ(read32(COLOUR + 2 * 34, &delay), (0xc000u + 34) | (0xc000u + 35) << 16);
    EXPECT_EQ(asked + delay, end + CYCLE * 2.0);
    EXPECT_EQ(read32(AC + aregs::CYCLES), 49u);
    EXPECT_EQ(read32(ZBUF + zregs::PIXELS), 96u);
    EXPECT_EQ(read32(ZBUF + zregs::WRITTEN), 96u);
    EXPECT_EQ(read32(ZBUF + zregs::PORT_CYCLES), 48u);
  });
  EXPECT_EQ(b.zbuf.core().depth(95), 100 - 95);
  const nlohmann::json array_stats = b.array.stats_json(sc_core::sc_time_stamp());
  EXPECT_EQ(array_stats["zbuf"]["stall_cycles"], 46u);
  const nlohmann::json stats = b.zbuf.stats_json(sc_core::sc_time_stamp());
  EXPECT_EQ(stats["pixels"], 96u);
  EXPECT_EQ(stats["port_cycles"], 48u);
  const EnergyActivity energy = b.zbuf.energy_activity(sc_core::sc_time_stamp());
  ASSERT_EQ(energy.size(), 1u);
  EXPECT_EQ(energy[0].unit, "zbuf");
  EXPECT_EQ(energy[0].counts.at("pixels"), 96.0);
}

// The same program under row-sequential issue (K = 4, set on the core): the
// halt waits in row r for its row's pixels (taken to 12 (r + 1)), 34 cycles
// for row 3, and the last row halts 3 x 4 cycles after the first: 2 + 34 + 1
// + 12 = 49, the time of the interrupt.
TEST(ZbufUnit, UnderRowSkewTheProgramEndsWhenTheLastRowHasHalted) {
  Bench& b = *g_bench;
  b.array.core().set_issue_skew(ap::IssueSkew::row, 4);
  const uint64_t stalls = b.array.core().activity().zbuf_stall_cycles;
  test::run_thread([&] {
    const sc_time at = sc_core::sc_time_stamp();
    ASSERT_EQ(write32(AC + aregs::START, 1), tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(b.array.busy_until(), at + CYCLE * (1.0 + 49));
    sc_core::wait(b.array.busy_until() - sc_core::sc_time_stamp());
    EXPECT_EQ(read32(AC + aregs::CYCLES), 49u);
    EXPECT_EQ(read32(ZBUF + zregs::PIXELS), 2 * 96u);
  });
  EXPECT_EQ(b.array.core().activity().zbuf_stall_cycles - stalls, 34u);
  EXPECT_EQ(b.array.core().activity().skew_cycles, 12u);
  b.array.core().set_issue_skew(ap::IssueSkew::none, 0);
}

TEST(ZbufUnit, BadColourWindowAccessesAreAddressErrors) {
  test::ReportCapture capture;
  test::run_thread([&] {
    uint32_t value = 0;
    EXPECT_EQ(g_bench->host.read(COLOUR + 1, reinterpret_cast<uint8_t*>(&value), 4).status,
              tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(g_bench->host.read(COLOUR + 2 * ENTRIES, reinterpret_cast<uint8_t*>(&value), 4).status,
              tlm::TLM_ADDRESS_ERROR_RESPONSE);
  });
  EXPECT_TRUE(capture.contains("colour window"));
}

namespace {

// The refusals the test checks, worked out in sc_main before the
// simulation: an exception thrown on sc_main's stack after the kernel ran
// trips AddressSanitizer (the kernel's coroutine stacks).
std::map<std::string, std::string> g_refusals;

std::string joined(const std::vector<std::string>& settings) {
  std::string key;
  for (const std::string& setting : settings) key += setting + ";";
  return key;
}

std::string refusal_now(const std::vector<std::string>& settings) {
  try {
    Config config({ArrayParams::parameters(), ZbufParams::parameters()});
    for (const std::string& setting : settings) config.apply_override(setting);
    config.validate();
    (void)ZbufParams::from_config(config);
  } catch (const std::exception& error) {
    return error.what();
  }
  return {};
}

const std::vector<std::vector<std::string>> REFUSAL_CASES = {
    {"zbuf.enabled=true", "zbuf.entries=65536", "zbuf.ports=1"},
    {"zbuf.entries=65537"},
    {"zbuf.entries=0"},
    {"zbuf.ports=0"},
    {"array.features.zsend=true"},
    {"array.features.zsend=true", "zbuf.enabled=true", "array.issue_skew=lane"},
    {"array.features.zsend=true", "zbuf.enabled=true", "array.issue_skew=row"},
    {"array.features.zsend=true", "zbuf.enabled=true"}};

std::string refusal(const std::vector<std::string>& settings) {
  return g_refusals.at(joined(settings));
}

}  // namespace

TEST(ZbufParams, BadConfigurationsAreRefusedNamingTheKey) {
  EXPECT_EQ(refusal({"zbuf.enabled=true", "zbuf.entries=65536", "zbuf.ports=1"}), "");
  EXPECT_NE(refusal({"zbuf.entries=65537"}).find("zbuf.entries"), std::string::npos);
  EXPECT_NE(refusal({"zbuf.entries=0"}).find("zbuf.entries"), std::string::npos);
  EXPECT_NE(refusal({"zbuf.ports=0"}).find("zbuf.ports"), std::string::npos);
  const std::string no_unit = refusal({"array.features.zsend=true"});
  EXPECT_NE(no_unit.find("zbuf.enabled"), std::string::npos) << no_unit;
  const std::string skew = refusal({"array.features.zsend=true", "zbuf.enabled=true", "array.issue_skew=lane"});
  EXPECT_NE(skew.find("array.issue_skew=lane"), std::string::npos) << skew;
  // Row-sequential issue has its reservation per row.
  EXPECT_EQ(refusal({"array.features.zsend=true", "zbuf.enabled=true", "array.issue_skew=row"}), "");
  EXPECT_EQ(refusal({"array.features.zsend=true", "zbuf.enabled=true"}), "");
  // Off by default: no unit, no zsend.
  const ZbufParams defaults = ZbufParams::defaults();
  EXPECT_FALSE(defaults.enabled);
  EXPECT_EQ(defaults.core.entries, 65536u);
  EXPECT_EQ(defaults.core.ports, 2u);
  EXPECT_FALSE(defaults.core.pair_halves_only);
}

int sc_main(int argc, char* argv[]) {
  for (const std::vector<std::string>& settings : REFUSAL_CASES) g_refusals[joined(settings)] = refusal_now(settings);
  g_bench = new Bench("bench");
  return test::run_all_tests(argc, argv);
}
