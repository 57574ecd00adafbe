// TLM tests of the display DMA on its own (tlm/display/display_dma.h): the
// test plays the display controller, starting a frame with its line times.
// Each line is fetched no earlier than its line buffer allows and the frame
// is complete at a time checked to the cycle; a deeper line buffer fetches
// earlier; lines that arrive after they are due are underruns; a read error
// fills zeros and is counted; a frame started twice is refused; the
// statistics and the summary row.
//
// Bench: display DMA -> checker -> bus (100 MHz) -> checker -> memory of
// 64 KiB with 3 wait states, in a 128 KiB window. A frame is 4 lines of 64
// bytes (32 RGB565 pixels), fetched in bursts of 16 bytes.
#include <cstring>
#include <stdexcept>

#include "bus/ahb_bus.h"
#include "checker/protocol_checker.h"
#include "display/display_dma.h"
#include "mem/memory.h"
#include "tlm_bench/bench_params.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);
const sc_time US(1, sc_core::SC_US);
constexpr unsigned MEMORY_WAIT = 3, LINE_BYTES = 64, LINES = 4, BURST_BYTES = 16;
constexpr uint32_t POPULATED = 0x10000, WINDOW = 0x20000, FRAME = 0x1000;
// A line on an idle bus: four bursts of address phase, wait states, four beats.
const sc_time LINE_FETCH = CYCLE * (4.0 * (1 + MEMORY_WAIT + 4));

DisplayDmaParams dma_params(unsigned fifo_lines) {
  DisplayDmaParams p = DisplayDmaParams::defaults();
  p.burst_bytes = BURST_BYTES;
  p.fifo_lines = fifo_lines;
  p.line_bytes = LINE_BYTES;
  p.lines = LINES;
  return p;
}

struct Bench {
  DisplayDma dma;
  ProtocolChecker<32> check_dma, check_memory;
  AhbBus bus;
  Memory memory;
  Bench(const std::string& name, unsigned fifo_lines)
      : dma((name + "_dma").c_str(), dma_params(fifo_lines)),
        check_dma((name + "_check_dma").c_str()),
        check_memory((name + "_check_memory").c_str()),
        bus((name + "_bus").c_str(), test::bench_bus_params(CYCLE)),
        memory((name + "_memory").c_str(), test::bench_memory_params(POPULATED, CYCLE, MEMORY_WAIT)) {
    dma.out.bind(check_dma.in);
    bus.attach(check_dma.out, "display_dma", 0);
    bus.map(check_memory.in, 0, WINDOW, "memory");
    check_memory.out.bind(memory.in);
  }
  // Plays the controller: starts a frame whose first line is due
  // `first_due` from now, and returns when it has been fetched.
  sc_time fetch(uint32_t base, sc_time first_due, sc_time line_time) {
    dma.start_frame(base, sc_core::sc_time_stamp() + first_due, line_time);
    sc_core::wait(dma.frame_fetched_event());
    return sc_core::sc_time_stamp();
  }
  uint64_t count(const char* name) const { return dma.counters().value(name); }
};

Bench* g_one_line = nullptr;
Bench* g_two_lines = nullptr;

void fill(Memory& memory, uint32_t base, uint8_t seed) {
  for (unsigned i = 0; i < LINE_BYTES * LINES; ++i) memory.data()[base + i] = static_cast<uint8_t>(seed + i);
}

}  // namespace

TEST(DisplayDma, EachLineIsFetchedOneLineTimeBeforeItIsDue) {
  Bench& b = *g_one_line;
  fill(b.memory, FRAME, 7);
  sc_time done;
  const sc_time start = test::run_thread([&] { done = b.fetch(FRAME, 10 * US, 5 * US); });
  // Line y is due at start + 10 + 5y us and fetched from one line time
  // before: the last line starts at start + 20 us.
  EXPECT_EQ(done, start + 20 * US + LINE_FETCH);
  for (unsigned i = 0; i < LINE_BYTES * LINES; ++i) ASSERT_EQ(b.dma.frame()[i], static_cast<uint8_t>(7 + i)) << i;
  EXPECT_EQ(b.dma.underrun_lines(), 0u);
  EXPECT_EQ(b.count("lines_fetched"), LINES);
  EXPECT_EQ(b.count("frames_fetched"), 1u);
  EXPECT_EQ(b.count("bus.bytes_read"), LINE_BYTES * LINES);
  EXPECT_EQ(b.count("bus.transactions"), LINES * LINE_BYTES / BURST_BYTES);
  EXPECT_EQ(b.bus.initiator_stats()[0].wait_cycles, 0u);
  EXPECT_EQ(b.dma.out.bus_time(), LINE_FETCH * static_cast<double>(LINES));
}

TEST(DisplayDma, ALineBufferOfTwoLinesFetchesOneLineTimeEarlier) {
  Bench& b = *g_two_lines;
  fill(b.memory, FRAME, 1);
  sc_time done;
  const sc_time start = test::run_thread([&] { done = b.fetch(FRAME, 10 * US, 5 * US); });
  EXPECT_EQ(done, start + 15 * US + LINE_FETCH);
  EXPECT_EQ(b.dma.underrun_lines(), 0u);
}

TEST(DisplayDma, LinesThatArriveAfterTheyAreDueAreUnderruns) {
  Bench& b = *g_one_line;
  const uint64_t lines = b.count("underrun_lines"), frames = b.count("underrun_frames");
  sc_time done;
  // A line time of 200 ns is shorter than the 320 ns a line takes: every
  // line is late, and each starts when the one before has arrived.
  const sc_time line_time(200, sc_core::SC_NS);
  const sc_time start = test::run_thread([&] { done = b.fetch(FRAME, US, line_time); });
  EXPECT_EQ(done, start + US - line_time + LINE_FETCH * static_cast<double>(LINES));
  EXPECT_EQ(b.count("underrun_lines") - lines, LINES);
  EXPECT_EQ(b.count("underrun_frames") - frames, 1u);
}

TEST(DisplayDma, AReadErrorFillsZerosCountsAndTheRestIsStillFetched) {
  Bench& b = *g_one_line;
  test::ReportCapture reports;
  const uint32_t base = POPULATED - 2 * LINE_BYTES;  // lines 2 and 3 lie outside memory
  fill(b.memory, base - 2 * LINE_BYTES, 0x40);
  const uint64_t errors = b.count("bus.errors"), lines = b.count("lines_fetched");
  test::run_thread([&] { b.fetch(base, 10 * US, 5 * US); });
  EXPECT_EQ(b.count("bus.errors") - errors, 2 * LINE_BYTES / BURST_BYTES);
  EXPECT_EQ(b.count("lines_fetched") - lines, LINES);
  EXPECT_EQ(b.dma.frame()[0], static_cast<uint8_t>(0x40 + 2 * LINE_BYTES));
  EXPECT_EQ(b.dma.frame()[2 * LINE_BYTES], 0);
  EXPECT_EQ(b.dma.frame()[LINES * LINE_BYTES - 1], 0);
  EXPECT_TRUE(reports.contains("read of 16 bytes at 0x00010000 failed (address error)"));
}

TEST(DisplayDma, AFrameStartedBeforeTheLastOneIsFetchedIsRefused) {
  Bench& b = *g_one_line;
  test::run_thread([&] {
    b.dma.start_frame(FRAME, sc_core::sc_time_stamp() + 10 * US, 5 * US);
    EXPECT_THROW(b.dma.start_frame(FRAME, sc_core::sc_time_stamp() + 10 * US, 5 * US), std::logic_error);
    sc_core::wait(b.dma.frame_fetched_event());
  });
}

TEST(DisplayDma, StatisticsAndSummaryRow) {
  Bench& b = *g_one_line;
  const sc_time now = sc_core::sc_time_stamp();
  const auto stats = b.dma.stats_json(now);
  EXPECT_EQ(stats["burst_bytes"], BURST_BYTES);
  EXPECT_EQ(stats["fifo_lines"], 1);
  EXPECT_EQ(stats["lines_fetched"], b.count("lines_fetched"));
  EXPECT_DOUBLE_EQ(stats["busy_ns"].get<double>(), b.dma.out.bus_time().to_seconds() * 1e9);
  const SummaryRow row = b.dma.summary_row(now);
  ASSERT_TRUE(row.busy.has_value());
  EXPECT_EQ(*row.busy, b.dma.out.bus_time());
  EXPECT_NE(row.notes.find(std::to_string(b.count("underrun_lines")) + " underrun lines"), std::string::npos)
      << row.notes;
  EXPECT_EQ(g_one_line->check_dma.violation_count() + g_one_line->check_memory.violation_count() +
                g_two_lines->check_dma.violation_count() + g_two_lines->check_memory.violation_count(),
            0u);
}

int sc_main(int argc, char* argv[]) {
  g_one_line = new Bench("one_line", 1);
  g_two_lines = new Bench("two_lines", 2);
  return test::run_all_tests(argc, argv);
}
