// TLM tests of the ARM922T host model: cost-model charging, data-cache hits
// and line fills over the bus, the posted-write buffer, uncached reads that
// wait for it, interrupts and idle time, bus errors raised into the software,
// DMI re-acquisition after invalidation, and statistics.
#include <functional>

#include "bus/ahb_bus.h"
#include "checker/protocol_checker.h"
#include "host/host.h"
#include "mem/memory.h"
#include "support/bench_params.h"
#include "support/host_program_runner.h"
#include "support/tlm_test_support.h"

using namespace tessera;
using sc_core::SC_NS;
using sc_core::sc_time;

namespace {

const sc_time HOST_CYCLE(5, SC_NS);  // 200 MHz: round numbers
const sc_time BUS_CYCLE(10, SC_NS);
constexpr unsigned MEM_WAIT = 3;
constexpr unsigned DEV_WAIT = 1;
constexpr uint32_t MEM_SIZE = 1u << 20;
constexpr uint32_t DEV_BASE = 0x40000000;
constexpr uint32_t UNMAPPED = 0x90000000;

HostParams host_params() {
  HostParams p = HostParams::defaults();
  p.clock_period = HOST_CYCLE;
  p.op_cycles.fill(1);
  p.op_cycles[static_cast<size_t>(Op::branch)] = 3;
  p.op_cycles[static_cast<size_t>(Op::fdiv)] = 130;
  p.load_cycles = 1;
  p.store_cycles = 1;
  p.dcache_bytes = 8192;
  p.dcache_line_bytes = 32;
  p.dcache_ways = 64;
  p.write_buffer_words = 16;
  p.irq_lines = 4;
  p.cacheable_base = 0;
  p.cacheable_size = MEM_SIZE;
  return p;
}

MemoryParams memory_params(uint32_t size, unsigned wait) {
  return test::bench_memory_params(size, BUS_CYCLE, wait);
}

BusParams bus_params() {
  return test::bench_bus_params(BUS_CYCLE);
}

// A host whose program runs test bodies on request, a bus, system memory
// and an uncached device memory; an interrupt line driven by the test.
struct Bench : sc_core::sc_module {
  SC_HAS_PROCESS(Bench);
  Host host;
  AhbBus bus;
  Memory memory, device;
  ProtocolChecker<32> check_host, check_memory, check_device;
  std::vector<std::unique_ptr<sc_core::sc_signal<bool>>> irq_lines;

  test::HostProgramRunner runner;

  explicit Bench(sc_core::sc_module_name name)
      : sc_core::sc_module(name),
        host("host", host_params()),
        bus("bus", bus_params()),
        memory("memory", memory_params(MEM_SIZE, MEM_WAIT)),
        device("device", memory_params(4096, DEV_WAIT)),
        check_host("check_host"),
        check_memory("check_memory"),
        check_device("check_device") {
    host.out.bind(check_host.in);
    bus.attach(check_host.out, "host", 0);
    bus.map(check_memory.in, 0, MEM_SIZE, "memory");
    bus.map(check_device.in, DEV_BASE, 4096, "device");
    check_memory.out.bind(memory.in);
    check_device.out.bind(device.in);
    for (unsigned i = 0; i < host.irq.size(); ++i) {
      irq_lines.push_back(std::make_unique<sc_core::sc_signal<bool>>(("irq" + std::to_string(i)).c_str()));
      host.irq[i].bind(*irq_lines.back());
    }
    host.set_program(runner.program());
  }

  // Runs `test_body` on the host; returns the simulated time it started.
  sc_time run(test::HostProgramRunner::Body test_body) { return runner.run(std::move(test_body)); }
};

// A host whose program fails on an unmapped read it does not catch.
struct FailingBench {
  Host host{"failing_host", host_params()};
  AhbBus bus{"failing_bus", bus_params()};
  Memory memory{"failing_memory", memory_params(4096, 0)};
  sc_core::sc_signal<bool> irq_line[4];
  FailingBench() {
    bus.attach(host.out, "host", 0);
    bus.map(memory.in, 0, 4096, "memory");
    for (unsigned i = 0; i < 4; ++i) host.irq[i].bind(irq_line[i]);
    host.set_program([](HostApi& api) {
      api.compute(Op::alu, 10);
      return static_cast<int>(api.read32(UNMAPPED));
    });
  }
};

Bench* g_bench = nullptr;
FailingBench* g_failing = nullptr;

sc_time seconds(double s) {
  return sc_time(s, sc_core::SC_SEC);
}
// Rounds a time up to the next bus clock edge.
sc_time bus_edge(const sc_time& t) {
  const uint64_t period = BUS_CYCLE.value();
  return sc_time::from_value((t.value() + period - 1) / period * period);
}

}  // namespace

TEST(Host, ComputeChargesCyclesOfEachOperationClass) {
  double elapsed = 0;
  g_bench->run([&](HostApi& api) {
    const double t0 = api.now_seconds();
    api.compute(Op::alu, 100);
    api.compute(Op::branch, 10);
    api.compute(Op::fdiv, 2);
    elapsed = api.now_seconds() - t0;
  });
  EXPECT_EQ(seconds(elapsed), HOST_CYCLE * (100.0 + 30.0 + 260.0));
}

TEST(Host, CacheMissFillsALineOverTheBusAndLaterHitsCostOneCycle) {
  sc_time miss_done, hit_cost, start_local;
  const uint64_t fills_before = g_bench->bus.initiator_stats()[0].reads;
  g_bench->memory.data()[0x2004] = 0x77;
  g_bench->run([&](HostApi& api) {
    start_local = seconds(api.now_seconds());
    EXPECT_EQ(api.read8(0x2004), 0x77);
    miss_done = seconds(api.now_seconds());
    const double t = api.now_seconds();
    api.read32(0x2008);  // same 32-byte line
    api.read16(0x201e);
    hit_cost = seconds(api.now_seconds() - t);
  });
  // One load cycle, then a line fill: address phase, wait states, 8 beats.
  const sc_time fill = BUS_CYCLE * static_cast<double>(1 + MEM_WAIT + 8);
  EXPECT_EQ(miss_done, bus_edge(start_local + HOST_CYCLE) + fill);
  EXPECT_EQ(hit_cost, HOST_CYCLE * 2.0);
  EXPECT_EQ(g_bench->bus.initiator_stats()[0].reads - fills_before, 1u);
}

TEST(Host, PostedWritesDoNotStallUntilTheWriteBufferIsFull) {
  double sixteen = 0, sixty_four = 0;
  const sc_time stall_before = g_bench->host.stall_time();
  g_bench->run([&](HostApi& api) {
    double t = api.now_seconds();
    for (unsigned i = 0; i < 16; ++i) api.write32(DEV_BASE + 4 * i, i);
    sixteen = api.now_seconds() - t;
    t = api.now_seconds();
    for (unsigned i = 0; i < 64; ++i) api.write32(DEV_BASE + 4 * i, 100 + i);
    sixty_four = api.now_seconds() - t;
  });
  EXPECT_EQ(seconds(sixteen), HOST_CYCLE * 16.0);
  // Draining one word costs 1 + wait + 1 bus cycles; once the buffer is full
  // the host proceeds at the drain rate.
  const sc_time drain = BUS_CYCLE * static_cast<double>(1 + DEV_WAIT + 1);
  EXPECT_GE(seconds(sixty_four), drain * 48.0);
  EXPECT_GT(g_bench->host.stall_time(), stall_before);
  uint32_t last = 0;
  std::memcpy(&last, g_bench->device.data() + 4 * 63, 4);
  EXPECT_EQ(last, 163u);
}

// A span of stores that miss the cache is a train of single 16-bit writes.
// It leaves the write buffer a buffer's worth (16) per bus request, each
// issued when the buffer has room, so that arbitration can serve another
// initiator between two requests; the first request takes the remainder, so
// the core resumes when the last 16 stores are in the buffer. On an idle
// bus the stores are back to back: 1000 stores of 1 + 3 + 1 bus cycles.
TEST(Host, ALongTrainOfStoresLeavesTheBufferABuffersWorthAtATime) {
  const auto stalls_before = g_bench->host.stats_json(sc_core::sc_time_stamp())["write_buffer_stalls"].get<uint64_t>();
  const uint64_t writes_before = g_bench->bus.initiator_stats()[0].writes;
  sc_time start, end;
  g_bench->run([&](HostApi& api) {
    start = seconds(api.now_seconds());
    uint8_t* data = api.store_span(0x40000, 2, 1000);
    std::memset(data, 0x5a, 2000);
    end = seconds(api.now_seconds());
  });
  const sc_time store = BUS_CYCLE * static_cast<double>(1 + MEM_WAIT + 1);
  EXPECT_EQ(end, bus_edge(start + HOST_CYCLE * 1000.0) + store * (1000.0 - 16));
  EXPECT_EQ(g_bench->bus.initiator_stats()[0].writes - writes_before, 1000u);
  // Requests of 8 + 62 x 16 stores: the core waited before each of the 62.
  const auto stalls = g_bench->host.stats_json(sc_core::sc_time_stamp())["write_buffer_stalls"].get<uint64_t>();
  EXPECT_EQ(stalls - stalls_before, 62u);
  EXPECT_EQ(g_bench->memory.data()[0x40000 + 1999], 0x5a);
}

TEST(Host, UncachedReadWaitsForEarlierPostedWrites) {
  uint32_t value = 0;
  double elapsed = 0;
  g_bench->run([&](HostApi& api) {
    const double t = api.now_seconds();
    for (unsigned i = 0; i < 8; ++i) api.write32(DEV_BASE + 0x100, 0xa0 + i);
    value = api.read32(DEV_BASE + 0x100);
    elapsed = api.now_seconds() - t;
  });
  EXPECT_EQ(value, 0xa7u);
  const sc_time access = BUS_CYCLE * static_cast<double>(1 + DEV_WAIT + 1);
  EXPECT_GE(seconds(elapsed), access * 9.0);
}

TEST(Host, WaitIrqSleepsUntilTheLineRisesAndCountsIdleTime) {
  const sc_time idle_before = g_bench->host.idle_time();
  sc_time woke;
  const sc_time raise_after(5, sc_core::SC_US);
  sc_core::sc_spawn([&] {
    sc_core::wait(sc_time(100, sc_core::SC_US) + raise_after);
    g_bench->irq_lines[2]->write(true);
  });
  const sc_time start = g_bench->run([&](HostApi& api) {
    EXPECT_FALSE(api.irq_pending(2));
    api.wait_irq(2);
    woke = seconds(api.now_seconds());
    EXPECT_TRUE(api.irq_pending(2));
  });
  EXPECT_EQ(woke, start + raise_after);
  EXPECT_EQ(g_bench->host.idle_time() - idle_before, raise_after);
  g_bench->irq_lines[2]->write(false);
}

TEST(Host, BusErrorReachesTheSoftwareWithTheAddress) {
  bool caught = false;
  g_bench->run([&](HostApi& api) {
    try {
      api.read32(UNMAPPED);
    } catch (const BusError& e) {
      caught = true;
      EXPECT_EQ(e.address(), UNMAPPED);
      EXPECT_NE(std::string(e.what()).find("0x90000000"), std::string::npos) << e.what();
    }
  });
  EXPECT_TRUE(caught);
}

TEST(Host, MisalignedAccessAndMissingInterruptLineAreErrorsNotCrashes) {
  g_bench->run([&](HostApi& api) {
    EXPECT_THROW(api.read32(0x1002), std::invalid_argument);
    EXPECT_THROW(api.write16(0x1001, 1), std::invalid_argument);
    EXPECT_THROW(api.wait_irq(99), std::out_of_range);
  });
}

TEST(Host, UncaughtBusErrorEndsTheProgramWithAFailureNamingTheAddress) {
  if (!g_failing->host.finished()) sc_core::sc_start(sc_time(10, sc_core::SC_US));
  ASSERT_TRUE(g_failing->host.finished());
  EXPECT_EQ(g_failing->host.exit_code(), 1);
  EXPECT_NE(g_failing->host.failure().find("0x90000000"), std::string::npos) << g_failing->host.failure();
  EXPECT_NE(g_failing->host.failure().find("address error"), std::string::npos) << g_failing->host.failure();
}

TEST(Host, DmiIsRequestedAgainAfterInvalidation) {
  const uint64_t grants_before = g_bench->bus.initiator_stats()[0].dmi_grants;
  g_bench->run([&](HostApi& api) { api.read32(0x3000), api.read32(0x3004); });
  g_bench->memory.invalidate_dmi();
  g_bench->memory.data()[0x3004] = 0x42;
  uint32_t value = 0;
  g_bench->run([&](HostApi& api) { value = api.read32(0x3004); });
  EXPECT_EQ(value & 0xff, 0x42u);
  EXPECT_GE(g_bench->bus.initiator_stats()[0].dmi_grants - grants_before, 1u);
}

TEST(Host, StatisticsSplitBusyStalledAndIdle) {
  const auto stats = g_bench->host.stats_json(sc_core::sc_time_stamp());
  EXPECT_GT(stats["busy_ns"].get<double>(), 0.0);
  EXPECT_GT(stats["stalled_on_bus_ns"].get<double>(), 0.0);
  EXPECT_GT(stats["idle_ns"].get<double>(), 0.0);
  EXPECT_GT(stats["dcache"]["hits"].get<uint64_t>(), 0u);
  EXPECT_GT(stats["dcache"]["misses"].get<uint64_t>(), 0u);
  EXPECT_EQ(stats["operations"]["fdiv"].get<uint64_t>(), 2u);
  const double total =
      stats["busy_ns"].get<double>() + stats["stalled_on_bus_ns"].get<double>() + stats["idle_ns"].get<double>();
  EXPECT_NEAR(total, sc_core::sc_time_stamp().to_seconds() * 1e9, 1e-3);
}

TEST(Host, NoProtocolViolations) {
  EXPECT_EQ(g_bench->check_host.violation_count() + g_bench->check_memory.violation_count() +
                g_bench->check_device.violation_count(),
            0u);
}

int sc_main(int argc, char* argv[]) {
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_time(1, sc_core::SC_US));
  test::ReportCapture quiet;  // the failing bench's error is asserted, not printed
  g_bench = new Bench("bench");
  g_failing = new FailingBench();
  return test::run_all_tests(argc, argv);
}
