// TLM tests of the rasterizer peripheral (tlm/raster/rasterizer.h): register
// access and its errors, writes refused while busy, one run over a
// hand-built tile table (its pixels in memory, its time, the interrupt), and
// bad input -- a command list outside memory, an unknown opcode -- ending the
// run with an error code, the error interrupt and no crash.
//
// Bench: test initiator -> checker -> bus -> checker -> memory and
// rasterizer registers; rasterizer mem_out -> checker -> bus. Bus, memory and
// rasterizer run at 100 MHz, so every time below is a whole number of 10 ns
// cycles.
#include <algorithm>
#include <cstring>
#include <vector>

#include "bus/ahb_bus.h"
#include "checker/protocol_checker.h"
#include "mem/memory.h"
#include "raster/command_format.h"
#include "raster/raster_regs.h"
#include "raster/rasterizer.h"
#include "tlm_bench/bench_params.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;
namespace regs = raster_regs;
using raster::Opcode;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);
constexpr unsigned WIDTH = 32, HEIGHT = 16;  // one 32x16 tile
constexpr unsigned MEMORY_WAIT = 3;          // memory wait states before the first beat
constexpr uint32_t REGS_BASE = 0x60000000;
constexpr uint32_t MEMORY_SIZE = 0x10000, MEMORY_WINDOW = 0x100000;
constexpr uint32_t TILE_TABLE_ADDRESS = 0x1000, LIST_ADDRESS = 0x1100, STATE_ADDRESS = 0x1200,
                   TRIANGLE_ADDRESS = 0x1300;
constexpr uint32_t COLOR_BUFFER = 0x4000, DEPTH_BUFFER = 0x6000;
constexpr uint32_t BLUE = 0xFFFF0000, RED = 0xFF0000FF;  // R in bits 0-7
constexpr uint16_t BLUE565 = 0x001F, RED565 = 0xF800;

raster::CycleCosts test_costs() {
  raster::CycleCosts c;
  c.command = 1;
  c.setup = 8;
  c.tile_start = 4;
  c.tile_pixel_clear = 0;
  c.fragment = 1;
  c.texel = 1;
  c.tile_write_word = 0;
  return c;
}

// A bench whose bus, memory and rasterizer interface are `beat_bytes` wide.
struct Bench {
  test::TestInitiator host;
  ProtocolChecker<32> check_host, check_mem_out, check_memory, check_regs;
  AhbBus bus;
  Memory memory;
  Rasterizer raster;
  sc_core::sc_signal<bool> irq;

  Bench(const std::string& name, unsigned beat_bytes)
      : host((name + "_host").c_str()),
        check_host((name + "_check_host").c_str()),
        check_mem_out((name + "_check_mem_out").c_str()),
        check_memory((name + "_check_memory").c_str()),
        check_regs((name + "_check_regs").c_str()),
        bus((name + "_bus").c_str(), bus_params(beat_bytes)),
        memory((name + "_memory").c_str(), memory_params(beat_bytes)),
        raster((name + "_raster").c_str(), raster_params(beat_bytes)),
        irq((name + "_irq").c_str()) {
    bus.attach(check_mem_out.out, "raster", 1);
    bus.attach(check_host.out, "host", 3);
    host.out.bind(check_host.in);
    raster.mem_out.bind(check_mem_out.in);
    bus.map(check_memory.in, 0, MEMORY_WINDOW, "sysmem");
    bus.map(check_regs.in, REGS_BASE, 0x1000, "raster_regs");
    check_memory.out.bind(memory.in);
    check_regs.out.bind(raster.in);
    raster.irq.bind(irq);
  }
  static BusParams bus_params(unsigned beat_bytes) {
    BusParams p = test::bench_bus_params(CYCLE);
    p.width_bytes = beat_bytes;
    return p;
  }
  static MemoryParams memory_params(unsigned beat_bytes) {
    MemoryParams p = test::bench_memory_params(MEMORY_SIZE, CYCLE, MEMORY_WAIT);
    p.width_bytes = beat_bytes;
    return p;
  }
  static RasterizerParams raster_params(unsigned beat_bytes) {
    RasterizerParams p = RasterizerParams::defaults();
    p.beat_bytes = beat_bytes;
    p.width = WIDTH;
    p.height = HEIGHT;
    p.costs = test_costs();
    p.clock_period = CYCLE;
    return p;
  }
  size_t violations() const {
    return check_host.violation_count() + check_mem_out.violation_count() + check_memory.violation_count() +
           check_regs.violation_count();
  }
  const BusInitiatorStats& raster_bus() const { return bus.initiator_stats()[0]; }

  void poke(uint32_t address, const void* data, size_t bytes) { std::memcpy(memory.data() + address, data, bytes); }
  void poke32(uint32_t address, uint32_t value) { poke(address, &value, 4); }
  uint16_t color565(unsigned x, unsigned gl_y) {
    // Row 0 in memory is the top row, y = height - 1 in GL.
    const uint32_t address = COLOR_BUFFER + ((HEIGHT - 1 - gl_y) * WIDTH + x) * 2;
    return static_cast<uint16_t>(memory.data()[address] | memory.data()[address + 1] << 8);
  }
  void program(uint32_t tile_table) {
    host.write32(REGS_BASE + regs::TILE_TABLE, tile_table);
    host.write32(REGS_BASE + regs::COLOR_BASE, COLOR_BUFFER);
    host.write32(REGS_BASE + regs::DEPTH_BASE, DEPTH_BUFFER);
    host.write32(REGS_BASE + regs::FORMAT, static_cast<uint32_t>(PixelFormat::rgb565));
    host.write32(REGS_BASE + regs::IRQ_ENABLE, regs::IRQ_DONE | regs::IRQ_ERROR);
    // The test initiator does not wait for its writes; let the bus finish them.
    sc_core::wait(CYCLE * 20.0);
  }
  // Clears the interrupt and the previous run's status bits' effect on irq.
  void acknowledge() { host.write32(REGS_BASE + regs::IRQ_STATUS, regs::IRQ_DONE | regs::IRQ_ERROR); }
};

Bench* g_bench = nullptr;
Bench* g_wide = nullptr;  // a 64-bit bus and rasterizer interface

raster::VertexRecord vertex(unsigned x_q4, unsigned y_q4, uint32_t rgba) {
  return {x_q4 | y_q4 << 16, 0x800000, rgba, 0.0f, 0.0f, 1.0f};
}

// One tile: clear all three buffers to blue, far depth and stencil 0 (every
// mask open, so the core does not load the tile first), a state with every
// colour channel writable and nothing else enabled, one red triangle with its
// right angle at the bottom-left corner and legs of 12.25 pixels. Pixel
// centres (x + 0.5, y + 0.5) lie inside when x + y <= 11: 78 pixels, none on
// an edge, so the fill rule does not matter. The traversal visits the
// centres inside the bounding box: 12 x 12.
constexpr unsigned TRIANGLE_FRAGMENTS = 12 * 13 / 2;
constexpr unsigned TRIANGLE_BOX_PIXELS = 12 * 12;
constexpr uint32_t LIST_WORDS = 8;

void write_scene(Bench& b) {
  const raster::TileEntry tile{LIST_ADDRESS, LIST_WORDS};
  b.poke(TILE_TABLE_ADDRESS, &tile, sizeof tile);
  const uint32_t list[LIST_WORDS] = {static_cast<uint32_t>(Opcode::clear) | (7u << 8),
                                     BLUE,
                                     0xFFFFFF,
                                     0xFu << 8 | 1u << 12 | 0xFFu << 16,
                                     static_cast<uint32_t>(Opcode::state),
                                     STATE_ADDRESS,
                                     static_cast<uint32_t>(Opcode::triangle),
                                     TRIANGLE_ADDRESS};
  b.poke(LIST_ADDRESS, list, sizeof list);
  raster::StateBlock state{};
  state.color_mask = 0xF;
  state.depth_func = 1;  // less; unused, depth test off
  b.poke(STATE_ADDRESS, &state, sizeof state);
  const unsigned leg = 12 * 16 + 4;  // 12.25 in 9.4
  const raster::TriangleRecord triangle{{vertex(0, 0, RED), vertex(leg, 0, RED), vertex(0, leg, RED)}};
  b.poke(TRIANGLE_ADDRESS, &triangle, sizeof triangle);
  std::memset(b.memory.data() + COLOR_BUFFER, 0xAA, WIDTH * HEIGHT * 2);
}

struct RunTimes {
  sc_time started;  // START written
  sc_time irq_rose;
};

// Writes START and sleeps until the interrupt.
RunTimes start_and_wait(Bench& b) {
  RunTimes times;
  times.started = sc_core::sc_time_stamp();
  b.host.write32(REGS_BASE + regs::START, 1);
  sc_core::wait(b.irq.posedge_event());
  times.irq_rose = sc_core::sc_time_stamp();
  return times;
}

}  // namespace

TEST(Rasterizer, RegistersReadBackAndBadAccessesGetErrorResponses) {
  Bench& b = *g_bench;
  test::ReportCapture reports;
  test::run_thread([&] {
    EXPECT_EQ(b.host.read32(REGS_BASE + regs::WIDTH), WIDTH);
    EXPECT_EQ(b.host.read32(REGS_BASE + regs::HEIGHT), HEIGHT);
    EXPECT_EQ(b.host.read32(REGS_BASE + regs::TILE_WIDTH), 32u);
    EXPECT_EQ(b.host.read32(REGS_BASE + regs::TILE_HEIGHT), 16u);
    EXPECT_EQ(b.host.read32(REGS_BASE + regs::RECIP_METHOD), 3u);
    EXPECT_EQ(b.host.read32(REGS_BASE + regs::STATUS), 0u);
    EXPECT_EQ(b.host.read32(REGS_BASE + regs::CTRL), 0u);
    for (uint32_t reg : {regs::TILE_TABLE, regs::COLOR_BASE, regs::DEPTH_BASE}) {
      EXPECT_EQ(b.host.write32(REGS_BASE + reg, 0x1234560 + reg).status, tlm::TLM_OK_RESPONSE);
      EXPECT_EQ(b.host.read32(REGS_BASE + reg), 0x1234560 + reg);
    }
    EXPECT_EQ(b.host.write32(REGS_BASE + regs::FORMAT, static_cast<uint32_t>(PixelFormat::rgba8888)).status,
              tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(b.host.read32(REGS_BASE + regs::FORMAT), static_cast<uint32_t>(PixelFormat::rgba8888));
    EXPECT_EQ(b.host.write32(REGS_BASE + regs::RECIP_METHOD, 1).status, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(b.host.read32(REGS_BASE + regs::RECIP_METHOD), 1u);

    // Out-of-range values, read-only and write-only registers, holes.
    EXPECT_EQ(b.host.write32(REGS_BASE + regs::RECIP_METHOD, 0).status, tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(b.host.write32(REGS_BASE + regs::RECIP_METHOD, 4).status, tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(b.host.read32(REGS_BASE + regs::RECIP_METHOD), 1u);
    EXPECT_EQ(b.host.write32(REGS_BASE + regs::FORMAT, 2).status, tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(b.host.write32(REGS_BASE + regs::WIDTH, 1).status, tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(b.host.write32(REGS_BASE + regs::CYCLES, 1).status, tlm::TLM_COMMAND_ERROR_RESPONSE);
    test::TestInitiator::Result result;
    b.host.read32(REGS_BASE + regs::START, &result);
    EXPECT_EQ(result.status, tlm::TLM_COMMAND_ERROR_RESPONSE);
    b.host.read32(REGS_BASE + 0x100, &result);
    EXPECT_EQ(result.status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
    uint16_t half = 0;
    EXPECT_EQ(b.host.read(REGS_BASE + regs::STATUS, reinterpret_cast<uint8_t*>(&half), 2).status,
              tlm::TLM_BURST_ERROR_RESPONSE);

    b.host.write32(REGS_BASE + regs::RECIP_METHOD, 3);
    b.host.write32(REGS_BASE + regs::FORMAT, static_cast<uint32_t>(PixelFormat::rgb565));
  });
  EXPECT_TRUE(reports.contains("RECIP_METHOD accepts 1, 2 or 3"));
  EXPECT_TRUE(reports.contains("bad register access"));
  EXPECT_FALSE(b.irq.read());
  EXPECT_EQ(b.violations(), 0u);
}

TEST(Rasterizer, RunDrawsTheClearAndTheTriangleInTheExpectedTime) {
  Bench& b = *g_bench;
  write_scene(b);
  const BusInitiatorStats before = b.raster_bus();
  RunTimes times;
  uint32_t status = 0, irq_status = 0, error = 0, triangles = 0, fragments = 0, cycles = 0;
  test::run_thread([&] {
    b.program(TILE_TABLE_ADDRESS);
    times = start_and_wait(b);
    status = b.host.read32(REGS_BASE + regs::STATUS);
    irq_status = b.host.read32(REGS_BASE + regs::IRQ_STATUS);
    error = b.host.read32(REGS_BASE + regs::ERROR_STATUS);
    triangles = b.host.read32(REGS_BASE + regs::TRIANGLES);
    fragments = b.host.read32(REGS_BASE + regs::FRAGMENTS);
    cycles = b.host.read32(REGS_BASE + regs::CYCLES);
    b.acknowledge();
  });
  EXPECT_EQ(status, regs::STATUS_DONE);
  EXPECT_EQ(irq_status, regs::IRQ_DONE);
  EXPECT_EQ(error, static_cast<uint32_t>(raster::RasterError::none));
  EXPECT_EQ(triangles, 1u);
  EXPECT_EQ(fragments, TRIANGLE_FRAGMENTS);
  EXPECT_FALSE(b.irq.read()) << "IRQ_STATUS written back clears the interrupt";

  // Pixels: red where x + y <= 11, the clear colour elsewhere, every pixel of
  // the tile written.
  unsigned wrong = 0;
  for (unsigned y = 0; y < HEIGHT; ++y)
    for (unsigned x = 0; x < WIDTH; ++x) wrong += b.color565(x, y) != (x + y <= 11 ? RED565 : BLUE565);
  EXPECT_EQ(wrong, 0u);
  EXPECT_EQ(b.color565(0, 0), RED565);
  EXPECT_EQ(b.color565(11, 0), RED565);
  EXPECT_EQ(b.color565(12, 0), BLUE565);
  EXPECT_EQ(b.color565(0, 11), RED565);
  EXPECT_EQ(b.color565(0, 12), BLUE565);
  EXPECT_EQ(b.color565(WIDTH - 1, HEIGHT - 1), BLUE565);

  // Bus traffic (the core's access order, tlm/raster/core/README.md): the
  // tile entry (8 bytes); each command's op word, then its other words (8
  // words in all); the state block (48) and the triangle record (72) read;
  // the 32x16 tile written back, colour (RGB565) then depth/stencil (32-bit),
  // one access per row. In bursts of at most 16 words: entry 1, commands
  // 3 + 3, state 1, triangle 2 (16 + 2 words), colour rows 16 x 1 (16 words),
  // depth rows 16 x 2 (32 words).
  const BusInitiatorStats& after = b.raster_bus();
  const uint64_t read_bytes = 8 + LIST_WORDS * 4 + sizeof(raster::StateBlock) + sizeof(raster::TriangleRecord);
  const uint64_t write_bytes = WIDTH * HEIGHT * (2 + 4);
  EXPECT_EQ(after.bytes - before.bytes, read_bytes + write_bytes);
  EXPECT_EQ(after.errors, before.errors);
  const uint64_t transactions = after.transactions - before.transactions;
  EXPECT_EQ(transactions, 1u + 3 + 3 + 1 + 2 + HEIGHT * 1 + HEIGHT * 2);

  // Time. The run starts one rasterizer cycle after START reaches the
  // register; its first fetch then waits one cycle for the bus, which is
  // still busy with that START write (address cycle + one data cycle). Each
  // access is a blocking burst of address_cycles (1) + wait states (3) +
  // one cycle per word; the pipeline's own cycles come from CycleCosts: 3
  // commands, 1 triangle setup, 1 tile start, one cycle per pixel of the
  // triangle's box, loads and write-back free (tile_write_word 0).
  const uint64_t compute = 3 * 1 + 8 + 4 + TRIANGLE_BOX_PIXELS * 1;
  const uint64_t bus = transactions * (1 + MEMORY_WAIT) + (read_bytes + write_bytes) / 4;
  EXPECT_EQ(after.wait_cycles - before.wait_cycles, 1u);
  EXPECT_EQ(after.busy_cycles - before.busy_cycles, bus);
  const uint64_t run_cycles = 1 + compute + bus;
  EXPECT_EQ(times.irq_rose, times.started + CYCLE * static_cast<double>(1 + run_cycles));
  EXPECT_EQ(cycles, run_cycles);
  const auto stats = b.raster.stats_json(sc_core::sc_time_stamp());
  EXPECT_EQ(stats["triangles"], 1);
  EXPECT_EQ(stats["fragments"], TRIANGLE_FRAGMENTS);
  EXPECT_EQ(stats["cycles"]["compute"], compute);
  EXPECT_EQ(stats["bus"]["bytes_read"], read_bytes);
  EXPECT_EQ(stats["bus"]["bytes_written"], write_bytes);
  EXPECT_EQ(b.violations(), 0u);
}

// The same run with a 64-bit interface (raster.beat_bytes = 8) on a 64-bit
// bus: bursts of 16 beats are 128 bytes, so a depth row (128 bytes) and the
// triangle record (72) each take one burst instead of two, and every burst
// moves 8 bytes per beat. The pixels are the same.
TEST(Rasterizer, AWiderInterfaceMovesTheSameDataInFewerLongerBeats) {
  Bench& b = *g_wide;
  write_scene(b);
  const BusInitiatorStats before = b.raster_bus();
  RunTimes times;
  uint32_t cycles = 0;
  test::run_thread([&] {
    b.program(TILE_TABLE_ADDRESS);
    times = start_and_wait(b);
    cycles = b.host.read32(REGS_BASE + regs::CYCLES);
    b.acknowledge();
  });
  unsigned wrong = 0;
  for (unsigned y = 0; y < HEIGHT; ++y)
    for (unsigned x = 0; x < WIDTH; ++x) wrong += b.color565(x, y) != (x + y <= 11 ? RED565 : BLUE565);
  EXPECT_EQ(wrong, 0u);
  // The core's accesses, in bytes (as in the test above), and what each
  // costs in bursts of at most 128 bytes and in 8-byte beats.
  std::vector<unsigned> accesses = {8, 4, 12, 4, 4, 4, 4, sizeof(raster::StateBlock), sizeof(raster::TriangleRecord)};
  for (unsigned row = 0; row < HEIGHT; ++row) accesses.push_back(WIDTH * 2);
  for (unsigned row = 0; row < HEIGHT; ++row) accesses.push_back(WIDTH * 4);
  uint64_t bursts = 0, beats = 0;
  for (unsigned bytes : accesses) {
    for (unsigned offset = 0; offset < bytes; offset += 128) {
      ++bursts;
      beats += (std::min(128u, bytes - offset) + 7) / 8;
    }
  }
  const BusInitiatorStats& after = b.raster_bus();
  EXPECT_EQ(after.transactions - before.transactions, bursts);
  EXPECT_EQ(bursts, 1u + 6 + 1 + 1 + HEIGHT + HEIGHT);
  const uint64_t bus = bursts * (1 + MEMORY_WAIT) + beats;
  EXPECT_EQ(after.busy_cycles - before.busy_cycles, bus);
  const uint64_t run_cycles = 1 + (3 * 1 + 8 + 4 + TRIANGLE_BOX_PIXELS * 1) + bus;
  EXPECT_EQ(cycles, run_cycles);
  EXPECT_EQ(times.irq_rose, times.started + CYCLE * static_cast<double>(1 + run_cycles));
  EXPECT_EQ(b.violations(), 0u);
}

TEST(Rasterizer, WritesWhileBusyAreRefusedExceptTheInterruptRegisters) {
  Bench& b = *g_bench;
  write_scene(b);
  test::ReportCapture reports;
  test::TestInitiator::Result table{}, start{}, enable{}, clear{};
  uint32_t status_while_busy = 0, table_after = 0, status_after = 0;
  test::run_thread([&] {
    b.program(TILE_TABLE_ADDRESS);
    b.host.write32(REGS_BASE + regs::START, 1);
    sc_core::wait(CYCLE * 5.0);
    status_while_busy = b.host.read32(REGS_BASE + regs::STATUS);
    table = b.host.write32(REGS_BASE + regs::TILE_TABLE, 0x2000);
    start = b.host.write32(REGS_BASE + regs::START, 1);
    enable = b.host.write32(REGS_BASE + regs::IRQ_ENABLE, regs::IRQ_DONE | regs::IRQ_ERROR);
    clear = b.host.write32(REGS_BASE + regs::IRQ_STATUS, regs::IRQ_DONE);
    sc_core::wait(b.irq.posedge_event());
    table_after = b.host.read32(REGS_BASE + regs::TILE_TABLE);
    status_after = b.host.read32(REGS_BASE + regs::STATUS);
    b.acknowledge();
  });
  EXPECT_EQ(status_while_busy, regs::STATUS_BUSY);
  EXPECT_EQ(table.status, tlm::TLM_COMMAND_ERROR_RESPONSE);
  EXPECT_EQ(start.status, tlm::TLM_COMMAND_ERROR_RESPONSE);
  EXPECT_EQ(enable.status, tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(clear.status, tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(table_after, TILE_TABLE_ADDRESS);
  EXPECT_EQ(status_after, regs::STATUS_DONE);
  EXPECT_TRUE(reports.contains("written while busy"));
  EXPECT_EQ(b.violations(), 0u);
}

TEST(Rasterizer, ListOutsideMemoryIsABusErrorWithTheAddress) {
  Bench& b = *g_bench;
  constexpr uint32_t OUTSIDE = MEMORY_SIZE + 0x100;  // in the bus window, past the populated memory
  const raster::TileEntry tile{OUTSIDE, 4};
  b.poke(TILE_TABLE_ADDRESS + 0x80, &tile, sizeof tile);
  std::memset(b.memory.data() + COLOR_BUFFER, 0x55, WIDTH * HEIGHT * 2);
  test::ReportCapture reports;
  const uint64_t errors_before = b.raster_bus().errors;
  uint32_t status = 0, irq_status = 0, error = 0, address = 0;
  test::run_thread([&] {
    b.program(TILE_TABLE_ADDRESS + 0x80);
    start_and_wait(b);
    status = b.host.read32(REGS_BASE + regs::STATUS);
    irq_status = b.host.read32(REGS_BASE + regs::IRQ_STATUS);
    error = b.host.read32(REGS_BASE + regs::ERROR_STATUS);
    address = b.host.read32(REGS_BASE + regs::ERROR_ADDRESS);
    b.acknowledge();
  });
  EXPECT_EQ(status, regs::STATUS_ERROR);
  EXPECT_EQ(irq_status, regs::IRQ_ERROR);
  EXPECT_EQ(error, static_cast<uint32_t>(raster::RasterError::bus_error));
  EXPECT_EQ(address, OUTSIDE);
  EXPECT_GT(b.raster_bus().errors, errors_before);
  EXPECT_TRUE(reports.contains("failed (address error)"));
  EXPECT_TRUE(reports.contains("run failed: bus_error"));
  // The tile was not written.
  EXPECT_EQ(b.memory.data()[COLOR_BUFFER], 0x55);
  EXPECT_EQ(b.raster.stats_json(sc_core::sc_time_stamp())["failed_runs"], 1);
  EXPECT_EQ(b.violations(), 0u);
}

TEST(Rasterizer, UnknownOpcodeIsBadOpcodeWithItsAddress) {
  Bench& b = *g_bench;
  write_scene(b);
  // The second command of the list becomes opcode 0x7F.
  b.poke32(LIST_ADDRESS + 16, 0x7F);
  test::ReportCapture reports;
  uint32_t status = 0, error = 0, address = 0;
  bool irq_high = false;
  test::run_thread([&] {
    b.program(TILE_TABLE_ADDRESS);
    start_and_wait(b);
    irq_high = b.irq.read();
    status = b.host.read32(REGS_BASE + regs::STATUS);
    error = b.host.read32(REGS_BASE + regs::ERROR_STATUS);
    address = b.host.read32(REGS_BASE + regs::ERROR_ADDRESS);
    b.acknowledge();
  });
  EXPECT_TRUE(irq_high);
  EXPECT_EQ(status, regs::STATUS_ERROR);
  EXPECT_EQ(error, static_cast<uint32_t>(raster::RasterError::bad_opcode));
  EXPECT_EQ(address, LIST_ADDRESS + 16);
  EXPECT_TRUE(reports.contains("run failed: bad_opcode"));
  EXPECT_EQ(b.violations(), 0u);
}

int sc_main(int argc, char* argv[]) {
  g_bench = new Bench("narrow", 4);
  g_wide = new Bench("wide", 8);
  sc_core::sc_start(sc_core::SC_ZERO_TIME);
  return test::run_all_tests(argc, argv);
}
