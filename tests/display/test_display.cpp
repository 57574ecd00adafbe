// TLM tests of the display controller: register access and its errors, port
// mode (host copies, PRESENT shows), DMA mode with its display DMA (swap at
// vertical blank, frame shown after one refresh period, interrupt, achieved
// frame rate) and underruns when the bus cannot keep up. The display DMA on
// its own: test_display_dma.cpp.
#include <cmath>

#include "bus/ahb_bus.h"
#include "checker/protocol_checker.h"
#include "display/display_controller.h"
#include "display/display_regs.h"
#include "mem/memory.h"
#include "tlm_bench/bench_params.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;
namespace regs = display_regs;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);
constexpr unsigned WIDTH = 32, HEIGHT = 16, VBLANK = 4;
constexpr double REFRESH_HZ = 1000.0;  // a 1 ms period keeps the tests short
constexpr uint32_t REGS_BASE = 0x40000000, FRAME_BUFFER_ADDRESS = 0x1000;

DisplayParams display_params(bool dma) {
  DisplayParams p = DisplayParams::defaults();
  p.width = WIDTH;
  p.height = HEIGHT;
  p.format = PixelFormat::rgb565;
  p.dma = dma;
  p.refresh_hz = REFRESH_HZ;
  p.vblank_lines = VBLANK;
  p.clock_period = CYCLE;
  return p;
}

DisplayDmaParams dma_params() {
  DisplayDmaParams p = DisplayDmaParams::defaults();
  p.burst_bytes = 16;
  p.fifo_lines = 1;
  p.line_bytes = WIDTH * 2;
  p.lines = HEIGHT;
  return p;
}

// Port-mode display driven directly by a test initiator.
struct PortBench {
  test::TestInitiator regs_initiator{"port_regs_initiator"}, port_initiator{"port_initiator"};
  ProtocolChecker<32> check_regs{"port_check_regs"}, check_port{"port_check_port"};
  DisplayController display{"port_display", display_params(false)};
  sc_core::sc_signal<bool> irq{"port_irq"};
  std::vector<Frame> frames;
  PortBench() {
    regs_initiator.out.bind(check_regs.in);
    check_regs.out.bind(display.in);
    port_initiator.out.bind(check_port.in);
    check_port.out.bind(display.port_in);
    display.irq.bind(irq);
    display.on_frame([this](const Frame& f) { frames.push_back(f); });
  }
};

// DMA-mode display reading a frame buffer from memory over a bus.
struct DmaBench {
  test::TestInitiator host;
  ProtocolChecker<32> check_host, check_dma, check_memory, check_regs;
  AhbBus bus;
  Memory memory;
  DisplayController display;
  DisplayDma dma;
  sc_core::sc_signal<bool> irq;
  std::vector<Frame> frames;
  std::vector<sc_time> requests;
  DmaBench(const std::string& name, unsigned memory_wait)
      : host((name + "_host").c_str()),
        check_host((name + "_check_host").c_str()),
        check_dma((name + "_check_dma").c_str()),
        check_memory((name + "_check_memory").c_str()),
        check_regs((name + "_check_regs").c_str()),
        bus((name + "_bus").c_str(), test::bench_bus_params(CYCLE)),
        memory((name + "_memory").c_str(), test::bench_memory_params(0x10000, CYCLE, memory_wait)),
        display((name + "_display").c_str(), display_params(true)),
        dma((name + "_display_dma").c_str(), dma_params()),
        irq((name + "_irq").c_str()) {
    host.out.bind(check_host.in);
    bus.attach(check_dma.out, "display_dma", 0);
    bus.attach(check_host.out, "host", 3);
    dma.out.bind(check_dma.in);
    display.connect_dma(dma);
    bus.map(check_memory.in, 0, 0x10000, "memory");
    bus.map(check_regs.in, REGS_BASE, 0x1000, "display_regs");
    bus.map(display.port_in, REGS_BASE + 0x100000, 0x100000, "display_port");
    check_memory.out.bind(memory.in);
    check_regs.out.bind(display.in);
    display.irq.bind(irq);
    display.on_frame([this](const Frame& f) { frames.push_back(f); });
    display.on_request([this](const sc_time& when) { requests.push_back(when); });
  }
  unsigned violations() {
    return check_host.violation_count() + check_dma.violation_count() + check_memory.violation_count() +
           check_regs.violation_count();
  }
};

PortBench* g_port = nullptr;
DmaBench* g_dma = nullptr;
DmaBench* g_starved = nullptr;
DmaBench* g_rate = nullptr;

const sc_time PERIOD(1.0 / REFRESH_HZ, sc_core::SC_SEC);

sc_time next_period_boundary(const sc_time& t) {
  const uint64_t p = PERIOD.value();
  return sc_time::from_value((t.value() / p + 1) * p);
}

void fill_frame_buffer(Memory& memory, uint16_t base_value) {
  for (unsigned i = 0; i < WIDTH * HEIGHT; ++i) {
    const uint16_t v = static_cast<uint16_t>(base_value + i);
    memory.data()[FRAME_BUFFER_ADDRESS + 2 * i] = v & 0xff;
    memory.data()[FRAME_BUFFER_ADDRESS + 2 * i + 1] = v >> 8;
  }
}

}  // namespace

TEST(Display, GeometryRegistersReadBackTheConfiguration) {
  auto& r = g_port->regs_initiator;
  EXPECT_EQ(r.read32(regs::WIDTH), WIDTH);
  EXPECT_EQ(r.read32(regs::HEIGHT), HEIGHT);
  EXPECT_EQ(r.read32(regs::FORMAT), static_cast<uint32_t>(PixelFormat::rgb565));
  EXPECT_EQ(r.read32(regs::MODE), 0u);
}

TEST(Display, BadRegisterAccessesGetErrorResponses) {
  test::ReportCapture reports;
  auto& r = g_port->regs_initiator;
  EXPECT_EQ(r.write32(regs::WIDTH, 1).status, tlm::TLM_COMMAND_ERROR_RESPONSE);
  EXPECT_EQ(r.read32(regs::WIDTH), WIDTH);
  test::TestInitiator::Result result;
  r.read32(regs::SWAP, &result);
  EXPECT_EQ(result.status, tlm::TLM_COMMAND_ERROR_RESPONSE);
  r.read32(0x100, &result);
  EXPECT_EQ(result.status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  r.read32(0x2, &result);
  EXPECT_EQ(result.status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  uint16_t half = 0;
  EXPECT_EQ(r.read(regs::CTRL, reinterpret_cast<uint8_t*>(&half), 2).status, tlm::TLM_BURST_ERROR_RESPONSE);
  EXPECT_TRUE(reports.contains("bad register access"));
}

TEST(Display, PortModeShowsTheFrameWrittenToThePortOnPresent) {
  // Pure primaries, white, black and a mid grey in the first pixels.
  const uint16_t pixels[6] = {0xF800, 0x07E0, 0x001F, 0xFFFF, 0x0000, 0x8410};
  std::vector<uint16_t> frame(WIDTH * HEIGHT, 0x0000);
  std::copy(pixels, pixels + 6, frame.begin());
  frame.back() = 0xFFFF;
  auto& port = g_port->port_initiator;
  EXPECT_EQ(port.write(0, reinterpret_cast<const uint8_t*>(frame.data()), WIDTH * HEIGHT * 2).status,
            tlm::TLM_OK_RESPONSE);
  EXPECT_TRUE(g_port->frames.empty());
  g_port->regs_initiator.write32(regs::PRESENT, 1);
  ASSERT_EQ(g_port->frames.size(), 1u);
  const Frame& f = g_port->frames[0];
  EXPECT_EQ(f.width, WIDTH);
  EXPECT_EQ(f.height, HEIGHT);
  EXPECT_EQ(f.requested_seconds, f.time_seconds);
  auto pixel = [&](unsigned i) {
    return std::vector<int>{f.rgba[4 * i], f.rgba[4 * i + 1], f.rgba[4 * i + 2], f.rgba[4 * i + 3]};
  };
  EXPECT_EQ(pixel(0), (std::vector<int>{255, 0, 0, 255}));
  EXPECT_EQ(pixel(1), (std::vector<int>{0, 255, 0, 255}));
  EXPECT_EQ(pixel(2), (std::vector<int>{0, 0, 255, 255}));
  EXPECT_EQ(pixel(3), (std::vector<int>{255, 255, 255, 255}));
  EXPECT_EQ(pixel(4), (std::vector<int>{0, 0, 0, 255}));
  // 0x8410 holds r=16/31, g=32/63, b=16/31 of full scale.
  EXPECT_NEAR(pixel(5)[0], 16 * 255.0 / 31, 1.0);
  EXPECT_NEAR(pixel(5)[1], 32 * 255.0 / 63, 1.0);
  EXPECT_NEAR(pixel(5)[2], 16 * 255.0 / 31, 1.0);
  EXPECT_EQ(pixel(WIDTH * HEIGHT - 1), (std::vector<int>{255, 255, 255, 255}));
  EXPECT_EQ(g_port->regs_initiator.read32(regs::FRAMES), 1u);
  EXPECT_TRUE(g_port->regs_initiator.read32(regs::IRQ_STATUS) & regs::IRQ_FRAME_PRESENTED);
  g_port->regs_initiator.write32(regs::IRQ_STATUS, regs::IRQ_FRAME_PRESENTED);
  EXPECT_EQ(g_port->regs_initiator.read32(regs::IRQ_STATUS) & regs::IRQ_FRAME_PRESENTED, 0u);
}

TEST(Display, PortWriteOutsideTheFrameIsAnAddressError) {
  test::ReportCapture reports;
  uint32_t v = 0;
  EXPECT_EQ(g_port->port_initiator.write(WIDTH * HEIGHT * 2, reinterpret_cast<uint8_t*>(&v), 4).status,
            tlm::TLM_ADDRESS_ERROR_RESPONSE);
  EXPECT_TRUE(reports.contains("outside"));
}

TEST(Display, SwapTakesEffectAtVerticalBlankAndTheFrameIsShownOnePeriodLater) {
  DmaBench& bench = *g_dma;
  fill_frame_buffer(bench.memory, 0x1234);
  sc_time swap_requested, irq_rose, status_in_vblank;
  uint32_t status_bits = 0;
  sc_core::sc_spawn([&] {
    for (;;) {
      sc_core::wait(bench.irq.posedge_event());
      if (irq_rose == sc_core::SC_ZERO_TIME) irq_rose = sc_core::sc_time_stamp();
    }
  });
  test::run_thread(
      [&] {
        // Request in the middle of a refresh period.
        sc_core::wait(PERIOD / 2.0);
        bench.host.write32(REGS_BASE + regs::BACK_BASE, FRAME_BUFFER_ADDRESS);
        bench.host.write32(REGS_BASE + regs::IRQ_ENABLE, regs::IRQ_SWAP_DONE);
        bench.host.write32(REGS_BASE + regs::CTRL, regs::CTRL_ENABLE);
        swap_requested = sc_core::sc_time_stamp();
        bench.host.write32(REGS_BASE + regs::SWAP, 1);
        EXPECT_TRUE(bench.host.read32(REGS_BASE + regs::STATUS) & regs::STATUS_SWAP_PENDING);
        sc_core::wait(bench.irq.posedge_event());
        sc_core::wait(sc_time(1, sc_core::SC_US));
        status_in_vblank = sc_core::sc_time_stamp();
        status_bits = bench.host.read32(REGS_BASE + regs::STATUS);
        bench.host.write32(REGS_BASE + regs::IRQ_STATUS, regs::IRQ_SWAP_DONE);
      },
      PERIOD * 4.0);
  const sc_time vblank = next_period_boundary(swap_requested);
  EXPECT_EQ(irq_rose, vblank);
  EXPECT_TRUE(status_bits & regs::STATUS_VBLANK);
  EXPECT_FALSE(status_bits & regs::STATUS_SWAP_PENDING);
  EXPECT_FALSE(bench.irq.read());
  ASSERT_EQ(bench.frames.size(), 1u);
  EXPECT_DOUBLE_EQ(bench.frames[0].time_seconds, (vblank + PERIOD).to_seconds());
  // The frame remembers when it was requested; request receivers heard of it then.
  EXPECT_DOUBLE_EQ(bench.frames[0].requested_seconds, swap_requested.to_seconds());
  ASSERT_EQ(bench.requests.size(), 1u);
  EXPECT_EQ(bench.requests[0], swap_requested);
  // The frame buffer held 0x1234 + i at pixel i; check two pixels exactly.
  auto expand5 = [](unsigned v) { return static_cast<int>(std::lround(v * 255.0 / 31)); };
  const uint16_t first = 0x1234, last = static_cast<uint16_t>(0x1234 + WIDTH * HEIGHT - 1);
  EXPECT_NEAR(bench.frames[0].rgba[0], expand5(first >> 11), 1);
  EXPECT_NEAR(bench.frames[0].rgba[2], expand5(first & 31), 1);
  EXPECT_NEAR(bench.frames[0].rgba[4 * (WIDTH * HEIGHT - 1) + 2], expand5(last & 31), 1);
  EXPECT_EQ(bench.host.peek32(REGS_BASE + regs::FRONT_BASE), FRAME_BUFFER_ADDRESS);
  EXPECT_EQ(bench.host.peek32(REGS_BASE + regs::UNDERRUNS), 0u);
  EXPECT_EQ(bench.violations(), 0u);
}

TEST(Display, SwappingEveryPeriodAchievesTheRefreshRate) {
  DmaBench& bench = *g_rate;
  const size_t before = bench.frames.size();
  test::run_thread(
      [&] {
        bench.host.write32(REGS_BASE + regs::IRQ_ENABLE, regs::IRQ_SWAP_DONE);
        bench.host.write32(REGS_BASE + regs::CTRL, regs::CTRL_ENABLE);
        for (unsigned frame = 0; frame < 4; ++frame) {
          fill_frame_buffer(bench.memory, static_cast<uint16_t>(frame * 1000));
          bench.host.write32(REGS_BASE + regs::BACK_BASE, FRAME_BUFFER_ADDRESS);
          bench.host.write32(REGS_BASE + regs::SWAP, 1);
          while (!(bench.host.read32(REGS_BASE + regs::IRQ_STATUS) & regs::IRQ_SWAP_DONE))
            sc_core::wait(bench.irq.posedge_event());
          bench.host.write32(REGS_BASE + regs::IRQ_STATUS, regs::IRQ_SWAP_DONE);
        }
      },
      PERIOD * 8.0);
  ASSERT_EQ(bench.frames.size() - before, 4u);
  for (size_t i = before + 1; i < bench.frames.size(); ++i)
    EXPECT_NEAR(bench.frames[i].time_seconds - bench.frames[i - 1].time_seconds, PERIOD.to_seconds(), 1e-12);
  const auto stats = bench.display.stats_json(sc_core::sc_time_stamp());
  EXPECT_NEAR(stats["achieved_fps"].get<double>(), REFRESH_HZ, 1.0);
  const auto dma = bench.dma.stats_json(sc_core::sc_time_stamp());
  EXPECT_GT(dma["bus"]["bytes_read"].get<uint64_t>(), 4u * WIDTH * HEIGHT * 2 - 1);
  EXPECT_EQ(bench.bus.initiator_stats()[0].name, "display_dma");
  EXPECT_GT(bench.bus.initiator_stats()[0].bytes, 0u);
}

TEST(Display, SlowMemoryCausesUnderruns) {
  DmaBench& bench = *g_starved;
  fill_frame_buffer(bench.memory, 0);
  test::run_thread(
      [&] {
        bench.host.write32(REGS_BASE + regs::BACK_BASE, FRAME_BUFFER_ADDRESS);
        bench.host.write32(REGS_BASE + regs::CTRL, regs::CTRL_ENABLE);
        bench.host.write32(REGS_BASE + regs::SWAP, 1);
      },
      PERIOD * 3.0);
  // A 64-byte line in 16-byte bursts, each 1 + 2000 + 4 cycles, is 80 us
  // of fetching for a 50 us line time.
  EXPECT_GT(bench.host.peek32(REGS_BASE + regs::UNDERRUNS), 0u);
  const auto stats = bench.dma.stats_json(sc_core::sc_time_stamp());
  EXPECT_GT(stats["underrun_frames"].get<uint64_t>(), 0u);
  EXPECT_EQ(stats["underrun_lines"], bench.host.peek32(REGS_BASE + regs::UNDERRUNS));
}

int sc_main(int argc, char* argv[]) {
  g_port = new PortBench();
  g_dma = new DmaBench("dma", 3);
  g_starved = new DmaBench("starved", 2000);
  g_rate = new DmaBench("rate", 3);
  sc_core::sc_start(sc_core::SC_ZERO_TIME);
  return test::run_all_tests(argc, argv);
}
