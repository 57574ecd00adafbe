// TLM tests of the interrupt controller: RAW follows the lines, the enables
// select which lines assert IRQ and FIQ, the outputs follow a line at its
// change and an enable write at the access's annotated time, the STATUS
// registers are RAW & ENABLE, read-only registers refuse writes, and each
// access costs one clock cycle.
#include "checker/protocol_checker.h"
#include "intc/intc_regs.h"
#include "intc/interrupt_controller.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;
namespace regs = intc_regs;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);

struct Bench {
  test::TestInitiator cpu{"cpu"};
  ProtocolChecker<32> check{"check"};
  InterruptController intc{"intc", CYCLE, 4};
  sc_core::sc_signal<bool, sc_core::SC_MANY_WRITERS> lines[4];  // each test drives them from its own thread
  sc_core::sc_signal<bool> irq{"irq"}, fiq{"fiq"};
  Bench() {
    cpu.out.bind(check.in);
    check.out.bind(intc.in);
    for (unsigned i = 0; i < 4; ++i) intc.lines[i].bind(lines[i]);
    intc.irq.bind(irq);
    intc.fiq.bind(fiq);
  }
};

Bench* g_bench = nullptr;

TEST(InterruptController, RawShowsTheLinesAndTheEnablesChooseTheOutputs) {
  Bench& b = *g_bench;
  test::run_thread([&] {
    b.lines[1].write(true);
    b.lines[3].write(true);
    sc_core::wait(CYCLE);
    EXPECT_EQ(b.cpu.read32(regs::RAW), 0b1010u);
    EXPECT_FALSE(b.irq.read());  // nothing enabled
    EXPECT_FALSE(b.fiq.read());
    b.cpu.write32(regs::IRQ_ENABLE, 0b0011);
    b.cpu.write32(regs::FIQ_ENABLE, 0b1000);
    sc_core::wait(CYCLE);
    EXPECT_EQ(b.cpu.read32(regs::IRQ_STATUS), 0b0010u);
    EXPECT_EQ(b.cpu.read32(regs::FIQ_STATUS), 0b1000u);
    EXPECT_TRUE(b.irq.read());
    EXPECT_TRUE(b.fiq.read());
    b.lines[1].write(false);  // cleared at its source
    sc_core::wait(CYCLE);
    EXPECT_FALSE(b.irq.read());
    EXPECT_TRUE(b.fiq.read());
    EXPECT_EQ(b.cpu.read32(regs::IRQ_STATUS), 0u);
    b.lines[0].write(true);
    sc_core::wait(CYCLE);
    EXPECT_TRUE(b.irq.read());
    b.cpu.write32(regs::IRQ_ENABLE, 0);
    b.cpu.write32(regs::FIQ_ENABLE, 0);
    for (auto& line : b.lines) line.write(false);
    sc_core::wait(CYCLE);
    EXPECT_FALSE(b.irq.read());
    EXPECT_FALSE(b.fiq.read());
  });
}

TEST(InterruptController, AnEnableWrittenAheadTakesEffectAtItsAnnotatedTime) {
  Bench& b = *g_bench;
  test::run_thread([&] {
    b.lines[2].write(true);
    sc_core::wait(CYCLE);
    const sc_time start = sc_core::sc_time_stamp();
    uint32_t value = 0b0100;
    const auto result = b.cpu.write(regs::IRQ_ENABLE, reinterpret_cast<const uint8_t*>(&value), 4, 5 * CYCLE);
    EXPECT_EQ(result.status, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(result.delay, 6 * CYCLE);  // the offset and one cycle of the access
    sc_core::wait(4 * CYCLE);
    EXPECT_FALSE(b.irq.read());  // not yet: the write is at start + 5 cycles
    sc_core::wait(2 * CYCLE);
    EXPECT_TRUE(b.irq.read());
    EXPECT_GE(sc_core::sc_time_stamp(), start + 5 * CYCLE);
    b.cpu.write32(regs::IRQ_ENABLE, 0);
    b.lines[2].write(false);
    sc_core::wait(CYCLE);
  });
}

TEST(InterruptController, ReadOnlyRegistersRefuseWrites) {
  Bench& b = *g_bench;
  test::run_thread([&] {
    for (uint32_t offset : {regs::RAW, regs::IRQ_STATUS, regs::FIQ_STATUS})
      EXPECT_EQ(b.cpu.write32(offset, 1).status, tlm::TLM_COMMAND_ERROR_RESPONSE) << offset;
    EXPECT_EQ(b.cpu.write32(0x40, 1).status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  });
}

}  // namespace

int sc_main(int argc, char* argv[]) {
  g_bench = new Bench();
  sc_core::sc_start(sc_core::SC_ZERO_TIME);
  return test::run_all_tests(argc, argv);
}
