// TLM tests of the assembled SoC (tlm/soc/soc.h) with its default
// configuration in display DMA mode, the host running test bodies as its
// program: the block list the statistics and traces are gathered over, and
// bus fairness -- a long colour clear by the host (one store_span of a whole
// 320x240 RGB565 frame, 76,800 posted 16-bit stores) takes exactly its bus
// time when the bus is otherwise idle, and while the display DMA scans out,
// the DMA still gets every line on time.
#include <cstring>
#include <set>
#include <string>

#include "display/display_regs.h"
#include "soc/irq_map.h"
#include "soc/memory_map.h"
#include "soc/soc.h"
#include "soc/software_layout.h"
#include "tlm_bench/host_program_runner.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;
namespace regs = display_regs;

namespace {

Config dma_config() {
  Config config(Soc::parameter_groups());
  config.apply_override("display.dma=true");
  return config;
}

uint32_t reg(uint32_t offset) {
  return memory_map::display_regs.base + offset;
}

// The SoC, its host running one test body at a time; between bodies the
// simulation goes on (the display keeps refreshing).
struct Bench {
  Config config = dma_config();
  Soc soc{"soc", config};
  test::HostProgramRunner runner;
  software_layout::Layout layout = software_layout::layout(soc.memory.size(), soc.display.frame_bytes());

  Bench() { soc.set_program(runner.program()); }
  // Runs `test_body` on the host and returns when it has finished.
  void run(test::HostProgramRunner::Body test_body) { runner.run(std::move(test_body)); }
};

Bench* g_bench = nullptr;

sc_time seconds(double s) {
  return sc_time(s, sc_core::SC_SEC);
}

// The clear under test: every pixel of buffer `address` set to `colour`
// with 16-bit stores, as a software renderer clears its colour buffer.
void clear(HostApi& api, uint32_t address, unsigned pixels, uint16_t colour) {
  uint8_t* data = api.store_span(address, 2, pixels);
  for (unsigned i = 0; i < pixels; ++i) std::memcpy(data + 2 * i, &colour, 2);
}

}  // namespace

TEST(Soc, BlocksAreListedOnceEachUnderTheirNames) {
  std::set<std::string> names;
  for (const Block* block : g_bench->soc.blocks()) EXPECT_TRUE(names.insert(block->basename()).second);
  EXPECT_EQ(names,
            (std::set<std::string>{"host", "bus", "memory", "display", "display_dma", "raster", "array", "ciu"}));
  const auto stats = g_bench->soc.recorder().stats_json();
  for (const auto& name : names) EXPECT_TRUE(stats.contains(name)) << name;
}

// With the display DMA not scanning, the clear's time is its own: the host
// charges one store cycle per pixel, posts the stores, and resumes when all
// but the 4 the write buffer holds (one address each) have left; each store
// holds the bus for an address cycle, the memory's 3 wait states and one
// beat.
TEST(Soc, ALongClearOnAnIdleBusTakesItsBusTime) {
  Bench& b = *g_bench;
  const unsigned pixels = b.soc.display.frame_bytes() / 2;
  const sc_time host_cycle = HostParams::from_config(b.config).clock_period;
  const sc_time bus_cycle = BusParams::from_config(b.config).clock_period;
  sc_time start, end;
  b.run([&](HostApi& api) {
    start = seconds(api.now_seconds());
    clear(api, b.layout.frame_buffers[1], pixels, 0x1234);
    end = seconds(api.now_seconds());
  });
  const uint64_t edge = bus_cycle.value();
  const sc_time issued = sc_time::from_value(((start + host_cycle * pixels).value() + edge - 1) / edge * edge);
  EXPECT_EQ(end, issued + bus_cycle * (5.0 * (pixels - 4)));
  EXPECT_EQ(b.soc.display_dma.underrun_lines(), 0u);
}

// The display DMA scans a frame out while the host clears the other buffer:
// the DMA has the highest priority and its lines are due every 64 us, so
// the clear must let it in between its stores. (When the clear was one bus
// request of 4 ms, 51 lines of this frame were late.)
TEST(Soc, TheDisplayDmaMeetsItsDeadlinesDuringALongClear) {
  Bench& b = *g_bench;
  const unsigned pixels = b.soc.display.frame_bytes() / 2;
  const uint64_t dma_busy_before = b.soc.bus.initiator_stats()[1].busy_cycles;
  sc_time start, end;
  b.run([&](HostApi& api) {
    api.write32(reg(regs::IRQ_ENABLE), regs::IRQ_SWAP_DONE);
    api.write32(reg(regs::CTRL), regs::CTRL_ENABLE);
    api.write32(reg(regs::BACK_BASE), b.layout.frame_buffers[0]);
    api.write32(reg(regs::SWAP), 1);
    api.wait_irq(irq_map::display);
    api.write32(reg(regs::IRQ_STATUS), api.read32(reg(regs::IRQ_STATUS)));
    // The swap took effect at the vertical blank: the DMA is about to scan
    // buffer 0 for the next 15 ms, line by line.
    start = seconds(api.now_seconds());
    clear(api, b.layout.frame_buffers[1], pixels, 0x4321);
    end = seconds(api.now_seconds());
    // Until the scan of the period is over.
    api.write32(reg(regs::BACK_BASE), b.layout.frame_buffers[1]);
    api.write32(reg(regs::SWAP), 1);
    api.wait_irq(irq_map::display);
    api.write32(reg(regs::IRQ_STATUS), api.read32(reg(regs::IRQ_STATUS)));
  });
  EXPECT_EQ(b.soc.display_dma.underrun_lines(), 0u) << "lines the display DMA fetched too late";
  EXPECT_GT(b.soc.display_dma.counters().value("lines_fetched"), 0u);
  // The clear waited for the DMA's bursts, and for nothing else.
  const sc_time bus_cycle = BusParams::from_config(b.config).clock_period;
  const sc_time alone = HostParams::from_config(b.config).clock_period * pixels + bus_cycle * (5.0 * (pixels - 16));
  const uint64_t dma_busy = b.soc.bus.initiator_stats()[1].busy_cycles - dma_busy_before;
  EXPECT_GE(end - start, alone);
  EXPECT_LE(end - start, alone + bus_cycle * static_cast<double>(dma_busy + 1));
}

int sc_main(int argc, char* argv[]) {
  test::ReportCapture quiet;
  g_bench = new Bench();
  return test::run_all_tests(argc, argv);
}
