// TLM tests of the common peripheral shape (tlm/common/peripheral.h): the
// register socket with its one-cycle latency, the interrupt registers and
// the line that follows status & enable (at the kernel's time or at an
// annotated time), a block's refused writes (command error, counted,
// reported), bad accesses, debug transport without time, and the block hooks
// (statistics from the activity counters, the summary row).
//
// Bench: test initiator -> protocol checker -> a small peripheral of four
// registers; its interrupt drives a signal the tests watch.
#include <string>
#include <vector>

#include "checker/protocol_checker.h"
#include "common/peripheral.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);
constexpr uint32_t CTRL = 0x0, IRQ_STATUS = 0x4, IRQ_ENABLE = 0x8, GO = 0xC;
constexpr uint32_t IRQ_DONE = 1u << 0, IRQ_LATE = 1u << 1;

// GO raises IRQ_DONE at the access's annotated time and IRQ_LATE 100 ns
// after it; CTRL refuses values above 0xff.
class TestPeripheral : public Peripheral {
 public:
  explicit TestPeripheral(sc_core::sc_module_name name) : Peripheral(name, CYCLE) {
    m_regs.add({"CTRL", CTRL, 0, RegAccess::rw});
    add_irq_registers({"IRQ_STATUS", IRQ_STATUS, 0, RegAccess::w1c}, {"IRQ_ENABLE", IRQ_ENABLE, 0, RegAccess::rw});
    m_regs.add({"GO", GO, 0, RegAccess::wo}, {}, [this](uint32_t) {
      raise_irq(IRQ_DONE, m_regs.access_delay());
      raise_irq(IRQ_LATE, m_regs.access_delay() + sc_time(100, sc_core::SC_NS));
    });
  }
  SummaryRow summary_row(const sc_time&) const override { return {std::nullopt, std::nullopt, "test"}; }

 private:
  const char* write_refusal(const tlm::tlm_generic_payload& gp) const override {
    uint32_t value = 0;
    std::memcpy(&value, gp.get_data_ptr(), 4);
    return gp.is_write() && gp.get_address() == CTRL && value > 0xff ? "CTRL holds 8 bits" : nullptr;
  }
};

struct Bench {
  test::TestInitiator cpu{"cpu"};
  ProtocolChecker<32> check{"check"};
  TestPeripheral peripheral{"peripheral"};
  sc_core::sc_signal<bool> irq{"irq"};
  std::vector<std::pair<sc_time, bool>> edges;  // every change of the line
  Bench() {
    cpu.out.bind(check.in);
    check.out.bind(peripheral.in);
    peripheral.irq.bind(irq);
  }
};

Bench* g_bench = nullptr;

void watch_line() {
  sc_core::sc_spawn([] {
    for (;;) {
      sc_core::wait(g_bench->irq.value_changed_event());
      g_bench->edges.emplace_back(sc_core::sc_time_stamp(), g_bench->irq.read());
    }
  });
}

}  // namespace

TEST(Peripheral, RegisterAccessCostsOneCycleOfTheBlocksClock) {
  auto& cpu = g_bench->cpu;
  test::run_thread([&] {
    const sc_time offset(40, sc_core::SC_NS);
    uint32_t value = 0x5a;
    const auto write = cpu.write(CTRL, reinterpret_cast<uint8_t*>(&value), 4, offset);
    EXPECT_EQ(write.status, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(write.delay, offset + CYCLE);
    test::TestInitiator::Result read;
    EXPECT_EQ(cpu.read32(CTRL, &read), 0x5au);
    EXPECT_EQ(read.delay, CYCLE);
  });
}

TEST(Peripheral, LineFollowsStatusAndEnableAtTheAnnotatedTime) {
  auto& b = *g_bench;
  b.edges.clear();
  sc_time start;
  const sc_time offset(300, sc_core::SC_NS);
  start = test::run_thread([&] {
    // Disabled: a raise sets the status bit, the line stays low.
    b.cpu.write32(GO, 1);
    sc_core::wait(sc_time(1, sc_core::SC_US));
    EXPECT_EQ(b.cpu.read32(IRQ_STATUS), IRQ_DONE | IRQ_LATE);
    EXPECT_FALSE(b.irq.read());
    b.cpu.write32(IRQ_STATUS, IRQ_DONE | IRQ_LATE);
    b.cpu.write32(IRQ_ENABLE, IRQ_DONE | IRQ_LATE);
    sc_core::wait(sc_time(1, sc_core::SC_US));
    // Enabled, GO written 300 ns ahead of the kernel's time: the line rises
    // at that time, not when the call is made.
    uint32_t one = 1;
    b.cpu.write(GO, reinterpret_cast<uint8_t*>(&one), 4, offset);
    EXPECT_FALSE(b.irq.read());
    sc_core::wait(sc_time(1, sc_core::SC_US));
    EXPECT_TRUE(b.irq.read());
    // Clearing one of two pending bits keeps the line high; clearing both
    // drops it.
    b.cpu.write32(IRQ_STATUS, IRQ_DONE);
    sc_core::wait(sc_time(1, sc_core::SC_US));
    EXPECT_TRUE(b.irq.read());
    b.cpu.write32(IRQ_STATUS, IRQ_LATE);
    sc_core::wait(sc_time(1, sc_core::SC_US));
    EXPECT_FALSE(b.irq.read());
  });
  const sc_time go = start + sc_time(2, sc_core::SC_US);
  ASSERT_EQ(b.edges.size(), 2u);
  EXPECT_EQ(b.edges[0], std::make_pair(go + offset, true));
  EXPECT_EQ(b.edges[1], std::make_pair(go + sc_time(2, sc_core::SC_US), false));
}

TEST(Peripheral, DisablingAPendingInterruptDropsTheLine) {
  auto& b = *g_bench;
  b.edges.clear();
  const sc_time start = test::run_thread([&] {
    b.cpu.write32(IRQ_ENABLE, IRQ_DONE);
    b.cpu.write32(GO, 1);
    sc_core::wait(sc_time(1, sc_core::SC_US));
    EXPECT_TRUE(b.irq.read());
    b.cpu.write32(IRQ_ENABLE, 0);
    sc_core::wait(sc_time(1, sc_core::SC_US));
    EXPECT_FALSE(b.irq.read());
    EXPECT_EQ(b.cpu.read32(IRQ_STATUS) & IRQ_DONE, IRQ_DONE);
    b.cpu.write32(IRQ_STATUS, IRQ_DONE | IRQ_LATE);
  });
  ASSERT_EQ(b.edges.size(), 2u);
  EXPECT_EQ(b.edges[0], std::make_pair(start, true));
  EXPECT_EQ(b.edges[1], std::make_pair(start + sc_time(1, sc_core::SC_US), false));
}

// An initiator ahead of the kernel (a host in its quantum) clears the
// interrupt in the same time step in which it rose: the line must still
// fall at the write's own time, so that the pulse exists, in a trace too.
TEST(Peripheral, AClearMovesTheLineAtTheWritesAnnotatedTime) {
  auto& b = *g_bench;
  b.edges.clear();
  const sc_time offset(500, sc_core::SC_NS);
  const sc_time start = test::run_thread([&] {
    b.cpu.write32(IRQ_ENABLE, IRQ_DONE);
    b.cpu.write32(GO, 1);
    sc_core::wait(sc_core::SC_ZERO_TIME);
    sc_core::wait(sc_core::SC_ZERO_TIME);
    EXPECT_TRUE(b.irq.read());
    uint32_t bits = IRQ_DONE | IRQ_LATE;
    b.cpu.write(IRQ_STATUS, reinterpret_cast<uint8_t*>(&bits), 4, offset);
    // The status register changed at once (a later access must see it)...
    EXPECT_EQ(b.cpu.read32(IRQ_STATUS), 0u);
    // ...the line at the write's time.
    EXPECT_TRUE(b.irq.read());
    sc_core::wait(sc_time(1, sc_core::SC_US));
    b.cpu.write32(IRQ_ENABLE, 0);
  });
  ASSERT_EQ(b.edges.size(), 2u);
  EXPECT_EQ(b.edges[0], std::make_pair(start, true));
  EXPECT_EQ(b.edges[1], std::make_pair(start + offset, false));
}

// Changes made out of time order: a clear ahead of the kernel (at +500 ns),
// then, in a later call, a raise at the kernel's time. The registers hold
// what was done last (the bit is pending); once no change is left to come,
// the line agrees with them, so the interrupt is not lost.
TEST(Peripheral, WhenChangesAreMadeOutOfTimeOrderTheLineEndsAsTheRegistersRead) {
  auto& b = *g_bench;
  b.edges.clear();
  const sc_time start = test::run_thread([&] {
    b.cpu.write32(IRQ_ENABLE, IRQ_DONE);
    b.cpu.write32(GO, 1);
    sc_core::wait(sc_time(1, sc_core::SC_US));
    uint32_t bits = IRQ_DONE;
    b.cpu.write(IRQ_STATUS, reinterpret_cast<uint8_t*>(&bits), 4, sc_time(500, sc_core::SC_NS));
    b.cpu.write32(GO, 1);
    sc_core::wait(sc_time(1, sc_core::SC_US));
    EXPECT_EQ(b.cpu.read32(IRQ_STATUS) & IRQ_DONE, IRQ_DONE);
    EXPECT_TRUE(b.irq.read());
    b.cpu.write32(IRQ_ENABLE, 0);
    b.cpu.write32(IRQ_STATUS, IRQ_DONE | IRQ_LATE);
  });
  ASSERT_EQ(b.edges.size(), 2u);
  EXPECT_EQ(b.edges[0], std::make_pair(start, true));
  EXPECT_EQ(b.edges[1], std::make_pair(start + sc_time(2, sc_core::SC_US), false));
}

TEST(Peripheral, RefusedWritesAreCommandErrorsCountedAndReported) {
  auto& b = *g_bench;
  test::ReportCapture reports;
  const uint64_t before = b.peripheral.counters().value("refused_register_writes");
  test::run_thread([&] {
    b.cpu.write32(CTRL, 0x12);
    const auto refused = b.cpu.write32(CTRL, 0x1234);
    EXPECT_EQ(refused.status, tlm::TLM_COMMAND_ERROR_RESPONSE);
    // A refused write still costs its cycle.
    EXPECT_EQ(refused.delay, CYCLE);
    EXPECT_EQ(b.cpu.read32(CTRL), 0x12u);
  });
  EXPECT_EQ(b.peripheral.counters().value("refused_register_writes"), before + 1);
  EXPECT_TRUE(reports.contains("register write at offset 0x00000000 refused: CTRL holds 8 bits"));
  EXPECT_EQ(b.peripheral.stats_json(sc_core::sc_time_stamp())["refused_register_writes"], before + 1);
}

TEST(Peripheral, BadAccessesGetTheRegisterBanksResponses) {
  auto& b = *g_bench;
  test::ReportCapture reports;
  test::run_thread([&] {
    test::TestInitiator::Result result;
    b.cpu.read32(0x40, &result);
    EXPECT_EQ(result.status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
    b.cpu.read32(GO, &result);
    EXPECT_EQ(result.status, tlm::TLM_COMMAND_ERROR_RESPONSE);
  });
  EXPECT_TRUE(reports.contains("bad register access"));
}

TEST(Peripheral, DebugTransportTakesNoTimeAndRunsNoHandler) {
  auto& b = *g_bench;
  b.edges.clear();
  const sc_time before = sc_core::sc_time_stamp();
  uint32_t value = 1;
  EXPECT_EQ(b.cpu.debug(tlm::TLM_WRITE_COMMAND, GO, reinterpret_cast<uint8_t*>(&value), 4), 4u);
  EXPECT_EQ(b.cpu.peek32(GO), 1u);
  EXPECT_EQ(b.cpu.peek32(IRQ_STATUS) & IRQ_DONE, 0u);
  sc_core::sc_start(sc_time(1, sc_core::SC_US));
  EXPECT_TRUE(b.edges.empty());
  EXPECT_EQ(sc_core::sc_time_stamp(), before + sc_time(1, sc_core::SC_US));
}

TEST(Peripheral, SummaryRowAndNoProtocolViolations) {
  const SummaryRow row = g_bench->peripheral.summary_row(sc_core::sc_time_stamp());
  EXPECT_FALSE(row.busy.has_value());
  EXPECT_EQ(row.notes, "test");
  EXPECT_EQ(g_bench->check.violation_count(), 0u);
}

int sc_main(int argc, char* argv[]) {
  g_bench = new Bench();
  watch_line();
  return test::run_all_tests(argc, argv);
}
