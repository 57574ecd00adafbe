// TLM tests of the ARM922T host model: cost-model charging, data-cache hits
// and line fills over the bus, the posted-write buffer (16 words, 4
// addresses), uncached reads that wait for it, write-through and
// write-back, pseudo-random replacement, CP15's C bit and c7's data-side
// operations (HostCore), interrupts and idle time, bus errors raised into
// the software, DMI re-acquisition after invalidation, and statistics.
#include <cmath>
#include <functional>
#include <random>

#include "bus/ahb_bus.h"
#include "checker/protocol_checker.h"
#include "host/host.h"
#include "mem/memory.h"
#include "tlm_bench/bench_block_params.h"
#include "tlm_bench/bench_params.h"
#include "tlm_bench/host_program_runner.h"
#include "tlm_bench/tlm_test_support.h"

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
  return test::bench_host_params(HOST_CYCLE, MEM_SIZE);
}

MemoryParams memory_params(uint32_t size, unsigned wait) {
  return test::bench_memory_params(size, BUS_CYCLE, wait);
}

BusParams bus_params() {
  return test::bench_bus_params(BUS_CYCLE);
}

// A host whose program runs test bodies on request, a bus, system memory
// and an uncached device memory; an interrupt line driven by the test.
// `write_through`: system memory's write policy.
struct Bench : sc_core::sc_module {
  SC_HAS_PROCESS(Bench);
  Host host;
  AhbBus bus;
  Memory memory, device;
  ProtocolChecker<32> check_host, check_memory, check_device;
  std::vector<std::unique_ptr<sc_core::sc_signal<bool>>> irq_lines;

  test::HostProgramRunner runner;

  explicit Bench(sc_core::sc_module_name name, bool write_through = false)
      : sc_core::sc_module(name),
        host("host",
             [&] {
               HostParams p = host_params();
               p.write_through = write_through;
               return p;
             }()),
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
Bench* g_write_through = nullptr;  // system memory write-through
// Two fresh benches for DataHitLines: the same accesses made by calls, and
// served through the granted line where it takes them.
Bench* g_called = nullptr;
Bench* g_served = nullptr;
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

// loads and stores count instructions: an LDM or an STM counts once, through
// the cache or not (its words count in the cache's hits and misses); a span
// counts one per element, each a single access of the host-compiled code.
TEST(Host, AnLdmOrAnStmCountsAsOneLoadOrStoreAndASpanAsOnePerElement) {
  const auto loads = [] { return g_bench->host.counters().value("loads"); };
  const auto stores = [] { return g_bench->host.counters().value("stores"); };
  const auto hits = [] { return g_bench->host.stats_json(sc_core::sc_time_stamp())["dcache"]["hits"].get<uint64_t>(); };
  uint64_t cached_ldm = 0, uncached_ldm = 0, cached_stm = 0, uncached_stm = 0, span = 0, ldm_hits = 0;
  g_bench->run([&](HostApi& api) {
    uint32_t words[6] = {1, 2, 3, 4, 5, 6};
    api.read32(0x5000);  // the line resident
    uint64_t before = loads();
    const uint64_t hits_before = hits();
    api.read_words(0x5000, words, 6);
    cached_ldm = loads() - before;
    ldm_hits = hits() - hits_before;
    before = loads();
    api.read_words(DEV_BASE + 0x300, words, 4);
    uncached_ldm = loads() - before;
    before = stores();
    api.write_words(0x5000, words, 6);
    cached_stm = stores() - before;
    before = stores();
    api.write_words(DEV_BASE + 0x300, words, 4);
    uncached_stm = stores() - before;
    before = loads();
    api.load_span(0x5000, 2, 10);
    span = loads() - before;
  });
  EXPECT_EQ(cached_ldm, 1u);
  EXPECT_EQ(ldm_hits, 6u) << "each word of the LDM hits the cache";
  EXPECT_EQ(uncached_ldm, 1u);
  EXPECT_EQ(cached_stm, 1u);
  EXPECT_EQ(uncached_stm, 1u);
  EXPECT_EQ(span, 10u);
}

// The write buffer holds 4 addresses (ARM922T TRM 4.3): four single stores
// go in without a stall, the fifth waits until the first has left. Each
// device write takes 1 + 1 + 1 bus cycles; the first starts at the bus edge
// after its store cycle, the others queue behind it.
TEST(Host, PostedWritesStallWhenTheFourAddressesAreTaken) {
  sc_time start, four, five;
  const auto stalls_before = g_bench->host.stats_json(sc_core::sc_time_stamp())["write_buffer_stalls"].get<uint64_t>();
  g_bench->run([&](HostApi& api) {
    start = seconds(api.now_seconds());
    for (unsigned i = 0; i < 4; ++i) api.write32(DEV_BASE + 4 * i, i);
    four = seconds(api.now_seconds());
    api.write32(DEV_BASE + 16, 4);
    five = seconds(api.now_seconds());
  });
  const sc_time write = BUS_CYCLE * static_cast<double>(1 + DEV_WAIT + 1);
  EXPECT_EQ(four, start + HOST_CYCLE * 4.0);
  EXPECT_EQ(five, bus_edge(start + HOST_CYCLE) + write);
  const auto stalls = g_bench->host.stats_json(sc_core::sc_time_stamp())["write_buffer_stalls"].get<uint64_t>();
  EXPECT_EQ(stalls - stalls_before, 1u);
  uint32_t last = 0;
  std::memcpy(&last, g_bench->device.data() + 16, 4);
  EXPECT_EQ(last, 4u);
}

// ... and 16 data words: two STMs of 8 words (two addresses) fill it, a
// third store waits until the first burst (1 + 1 + 8 bus cycles) has left.
TEST(Host, PostedBurstsStallWhenTheSixteenWordsAreTaken) {
  sc_time start, sixteen, more;
  g_bench->run([&](HostApi& api) {
    const uint32_t words[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    start = seconds(api.now_seconds());
    api.write_words(DEV_BASE + 0x200, words, 8);
    api.write_words(DEV_BASE + 0x220, words, 8);
    sixteen = seconds(api.now_seconds());
    api.write32(DEV_BASE + 0x240, 9);
    more = seconds(api.now_seconds());
  });
  EXPECT_EQ(sixteen, start + HOST_CYCLE * 18.0);  // (8 + 1) store cycles each
  EXPECT_EQ(more, bus_edge(start + HOST_CYCLE * 9.0) + BUS_CYCLE * static_cast<double>(1 + DEV_WAIT + 8));
}

// A span of stores that miss the cache is a train of single 16-bit writes.
// The buffer holds 4 of them (one address each), so the core resumes when
// the last 4 are in it. The bus sees the train as requests of at most 16
// stores (the buffer's data words), each issued when the one before has
// left the buffer, so that arbitration can serve another initiator between
// two requests; the last request is those 4 stores, the first the
// remainder. On an idle bus the stores are back to back: 1000 stores of
// 1 + 3 + 1 bus cycles.
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
  EXPECT_EQ(end, bus_edge(start + HOST_CYCLE * 1000.0) + store * (1000.0 - 4));
  EXPECT_EQ(g_bench->bus.initiator_stats()[0].writes - writes_before, 1000u);
  // Requests of 4 + 62 x 16 + 4 stores: the core waited before each of the 63 after the first.
  const auto stalls = g_bench->host.stats_json(sc_core::sc_time_stamp())["write_buffer_stalls"].get<uint64_t>();
  EXPECT_EQ(stalls - stalls_before, 63u);
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

// CP15's C bit clear (host.model=iss): a line in the cache is not looked up;
// the read goes to the bus (drain, then 1 + 3 + 1 bus cycles), the write to
// the write buffer (one cycle), and the line is left as it was: clean, and
// a hit once C is set again.
TEST(Host, DataCacheOffMakesEveryAccessUncachedAndKeepsTheContents) {
  const uint32_t line = 0x8000;
  g_bench->memory.data()[line + 4] = 0x31;
  const auto& stats = g_bench->bus.initiator_stats()[0];
  sc_time off_read_start, off_read_end, off_write, on_read;
  uint64_t reads = 0, writes = 0, hits = 0, misses = 0;
  uint32_t value = 0;
  g_bench->run([&](HostApi& api) {
    api.read32(line);  // the line is in the cache
    g_bench->host.set_data_cache_control(false, true);
    reads = stats.reads, writes = stats.writes;
    hits = g_bench->host.stats_json(sc_core::sc_time_stamp())["dcache"]["hits"].get<uint64_t>();
    misses = g_bench->host.data_cache_misses();
    off_read_start = seconds(api.now_seconds());
    value = api.read32(line + 4);
    off_read_end = seconds(api.now_seconds());
    sc_time t = seconds(api.now_seconds());
    api.write32(line + 8, 0x77);
    off_write = seconds(api.now_seconds()) - t;
    g_bench->host.set_data_cache_control(true, true);
    g_bench->host.drain_write_buffer();
    t = seconds(api.now_seconds());
    api.read32(line + 12);
    on_read = seconds(api.now_seconds()) - t;
  });
  EXPECT_EQ(value & 0xff, 0x31u);
  EXPECT_EQ(off_read_end, bus_edge(off_read_start + HOST_CYCLE) + BUS_CYCLE * static_cast<double>(1 + MEM_WAIT + 1));
  EXPECT_EQ(off_write, HOST_CYCLE);
  EXPECT_EQ(on_read, HOST_CYCLE) << "the line stayed in the cache";
  EXPECT_EQ(stats.reads - reads, 1u);
  EXPECT_EQ(stats.writes - writes, 1u);
  EXPECT_EQ(g_bench->memory.data()[line + 8], 0x77);
  EXPECT_EQ(g_bench->host.stats_json(sc_core::sc_time_stamp())["dcache"]["hits"].get<uint64_t>() - hits, 1u);
  EXPECT_EQ(g_bench->host.data_cache_misses() - misses, 0u);
  // The write with the cache off left the line clean: a clean writes nothing.
  g_bench->run([&](HostApi&) { g_bench->host.clean_data_line(line, false); });
  EXPECT_EQ(stats.writes - writes, 1u);
}

// c7's clean D entry posts the dirty half (4 words, one address) to the
// write buffer without a stall; the drain then waits for it: 1 + 3 + 4 bus
// cycles from the bus edge. Cleaning again writes nothing; clean and
// invalidate writes the other half and drops the line.
TEST(Host, CleanPostsTheDirtyHalfAndDrainWaitsForIt) {
  const uint32_t line = 0x9000;
  const auto& stats = g_bench->bus.initiator_stats()[0];
  uint64_t writes = 0, bytes = 0;
  sc_time clean, clean_start, drained, refill;
  g_bench->run([&](HostApi& api) {
    api.read32(line);
    api.write32(line + 20, 0xabcd);  // the second half dirty
    writes = stats.writes, bytes = stats.bytes;
    clean_start = seconds(api.now_seconds());
    g_bench->host.clean_data_line(line + 4, false);
    clean = seconds(api.now_seconds()) - clean_start;
    g_bench->host.drain_write_buffer();
    drained = seconds(api.now_seconds());
    g_bench->host.clean_data_line(line, false);
    api.write32(line, 1);  // the first half dirty
    g_bench->host.clean_data_line(line, true);
    g_bench->host.drain_write_buffer();
    const sc_time t = seconds(api.now_seconds());
    api.read32(line);
    refill = seconds(api.now_seconds()) - t;
  });
  EXPECT_EQ(clean, sc_core::SC_ZERO_TIME);
  EXPECT_EQ(drained, bus_edge(clean_start) + BUS_CYCLE * static_cast<double>(1 + MEM_WAIT + 4));
  EXPECT_GT(refill, HOST_CYCLE) << "clean and invalidate dropped the line";
  EXPECT_EQ(stats.writes - writes, 2u);
  EXPECT_EQ(stats.bytes - bytes, 16u + 16u + 32u) << "two halves written back, one line filled";
  uint32_t written = 0;
  std::memcpy(&written, g_bench->memory.data() + line + 20, 4);
  EXPECT_EQ(written, 0xabcdu);
}

// A span of stores hitting a write-back line dirties every half it covers:
// 16 halfwords over the whole line are a 32-byte write-back, 4 over the
// second half a 16-byte one.
TEST(Host, ASpanHittingALineDirtiesTheHalvesItCovers) {
  const uint32_t line = 0x9800;
  const auto& stats = g_bench->bus.initiator_stats()[0];
  uint64_t bytes = 0;
  g_bench->run([&](HostApi& api) {
    api.read32(line);
    api.read32(line + 32);
    bytes = stats.bytes;
    std::memset(api.store_span(line, 2, 16), 0x22, 32);
    std::memset(api.store_span(line + 48, 2, 4), 0x33, 8);
    g_bench->host.clean_data_line(line, false);
    g_bench->host.clean_data_line(line + 32, false);
  });
  EXPECT_EQ(stats.bytes - bytes, 32u + 16u);
}

// By index: the way in bits 31:26, the set in bits 6:5. Which way holds the
// line depends on the earlier tests' traffic, so every way of its set is
// cleaned: one write-back. Invalidating a line or the whole cache drops
// dirty data without writing it.
TEST(Host, CleanByIndexAndInvalidate) {
  const uint32_t line = 0xa040;  // set (0xa040 / 32) % 4 = 2
  const auto& stats = g_bench->bus.initiator_stats()[0];
  uint64_t writes = 0, bytes = 0, misses = 0;
  g_bench->run([&](HostApi& api) {
    api.read32(line);
    api.write32(line, 5);
    writes = stats.writes, bytes = stats.bytes;
    for (uint32_t way = 0; way < 64; ++way) g_bench->host.clean_data_index(way << 26 | 2u << 5, false);
    g_bench->host.drain_write_buffer();
    api.write32(line + 4, 6);
    g_bench->host.invalidate_data_line(line);
    for (uint32_t way = 0; way < 64; ++way) g_bench->host.clean_data_index(way << 26 | 2u << 5, false);
    api.read32(line + 0x20);
    api.read32(line);
    api.write32(line, 7);
    g_bench->host.invalidate_data_cache();
    misses = g_bench->host.data_cache_misses();
    api.read32(line);
    api.read32(line + 0x20);
  });
  EXPECT_EQ(stats.writes - writes, 1u);
  // Filled after the write-back: line + 0x20, line (invalidated), both again (all invalidated).
  EXPECT_EQ(stats.bytes - bytes, 16u + 4 * 32u) << "one half written back, four lines filled";
  EXPECT_EQ(g_bench->host.data_cache_misses() - misses, 2u) << "both lines invalidated";
}

// A victim's dirty half only is written back (its own burst, one address),
// then the line is filled. The set is emptied first (invalidate), so the 64
// misses of 64 other lines of the set fill every way once, whatever the
// round-robin pointer, and the 65th replaces the first.
TEST(Host, VictimWritesBackItsDirtyHalf) {
  const uint32_t first = 0xc000, way = 128;  // set 0
  const auto& stats = g_bench->bus.initiator_stats()[0];
  uint64_t writes = 0, bytes = 0, writebacks = 0;
  const auto count_writebacks = [] {
    return g_bench->host.stats_json(sc_core::sc_time_stamp())["dcache"]["writebacks"].get<uint64_t>();
  };
  g_bench->run([&](HostApi& api) {
    g_bench->host.invalidate_data_cache();
    api.read32(first);
    api.write32(first + 4, 9);
    writes = stats.writes, bytes = stats.bytes, writebacks = count_writebacks();
    for (uint32_t i = 1; i <= 64; ++i) api.read32(first + i * way);
  });
  EXPECT_EQ(stats.writes - writes, 1u);
  EXPECT_EQ(stats.bytes - bytes, 16u + 64 * 32u);
  EXPECT_EQ(count_writebacks() - writebacks, 1u);
}

// Write-through (host.dcache.write_policy=write_through): a store hit goes
// to the write buffer (one cycle) and updates the line, which stays clean:
// the next read hits, and cleaning writes nothing.
TEST(Host, WriteThroughHitGoesToTheBusAndTheLineStaysClean) {
  const uint32_t line = 0x2000;
  const auto& stats = g_write_through->bus.initiator_stats()[0];
  uint64_t writes = 0, stored = 0;
  sc_time write, read;
  uint32_t value = 0;
  g_write_through->run([&](HostApi& api) {
    api.read32(line);
    writes = stats.writes;
    sc_time t = seconds(api.now_seconds());
    api.write32(line + 4, 0x1234);
    write = seconds(api.now_seconds()) - t;
    stored = stats.writes;
    t = seconds(api.now_seconds());
    value = api.read32(line + 4);
    read = seconds(api.now_seconds()) - t;
    g_write_through->host.clean_data_line(line, true);
  });
  EXPECT_EQ(write, HOST_CYCLE);
  EXPECT_EQ(read, HOST_CYCLE);
  EXPECT_EQ(value, 0x1234u);
  EXPECT_EQ(stored - writes, 1u) << "the store went to the bus";
  EXPECT_EQ(stats.writes - stored, 0u) << "the line was clean";
  uint32_t in_memory = 0;
  std::memcpy(&in_memory, g_write_through->memory.data() + line + 4, 4);
  EXPECT_EQ(in_memory, 0x1234u);
}

// Write-through spans and STMs: the hits are counted, and every element
// leaves through the write buffer; 16 halfword stores into a resident line
// are a train of single writes, 4 in the buffer at a time: the core resumes
// when the last 4 are in, 12 stores of 1 + 3 + 1 bus cycles after the first
// started. An STM of 4 words is one burst.
TEST(Host, WriteThroughSpansAndBurstsGoOutWhole) {
  const uint32_t line = 0x2100;
  const auto& stats = g_write_through->bus.initiator_stats()[0];
  uint64_t writes = 0, bytes = 0, hits = 0;
  sc_time start, end;
  g_write_through->run([&](HostApi& api) {
    api.read32(line);
    writes = stats.writes, bytes = stats.bytes;
    hits = g_write_through->host.stats_json(sc_core::sc_time_stamp())["dcache"]["hits"].get<uint64_t>();
    start = seconds(api.now_seconds());
    std::memset(api.store_span(line, 2, 16), 0x11, 32);
    end = seconds(api.now_seconds());
    const uint32_t words[4] = {1, 2, 3, 4};
    api.write_words(line, words, 4);
  });
  EXPECT_EQ(end, bus_edge(start + HOST_CYCLE * 16.0) + BUS_CYCLE * static_cast<double>(1 + MEM_WAIT + 1) * 12.0);
  EXPECT_EQ(stats.writes - writes, 16u + 1u);
  EXPECT_EQ(stats.bytes - bytes, 32u + 16u);
  EXPECT_EQ(g_write_through->host.stats_json(sc_core::sc_time_stamp())["dcache"]["hits"].get<uint64_t>() - hits,
            16u + 4u);
}

// Pseudo-random replacement (CP15's RR clear, or host.dcache.replacement=
// random): the victim is the LFSR's next value modulo 64 (data_cache.h;
// test_data_cache.cpp works the values out: ways 48, then 56). Set 3 of
// this bench is filled round-robin first, from way 0 (no test before has
// used that set or replaced a line at random), so way i holds line i.
TEST(Host, RandomReplacementEvictsTheLfsrsWay) {
  const uint32_t base = 0x30060, way = 128;  // set 3
  sc_time miss_start, miss_end, hit;
  g_write_through->run([&](HostApi& api) {
    g_write_through->host.set_data_cache_control(true, true);
    for (uint32_t i = 0; i < 64; ++i) api.read32(base + i * way);
    g_write_through->host.set_data_cache_control(true, false);
    api.read32(base + 64 * way);  // replaces line 48
    sc_time t = seconds(api.now_seconds());
    api.read32(base + 47 * way);
    hit = seconds(api.now_seconds()) - t;
    miss_start = seconds(api.now_seconds());
    api.read32(base + 48 * way);
    miss_end = seconds(api.now_seconds());
    g_write_through->host.set_data_cache_control(true, true);
  });
  EXPECT_EQ(hit, HOST_CYCLE);
  EXPECT_EQ(miss_end, bus_edge(miss_start + HOST_CYCLE) + BUS_CYCLE * static_cast<double>(1 + MEM_WAIT + 8))
      << "line 48 was replaced and is filled again";
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

// The ISS launcher reads the busy, stall and miss counters where the host
// keeps them (HostCore::counter_locations), around every load and store:
// they must be what the three calls return, and follow them as they move.
TEST(Host, CounterLocationsReadWhatTheCallsReturn) {
  const HostCore& core = g_bench->host;
  const HostCore::CounterLocations at = core.counter_locations();
  ASSERT_NE(at.busy_cycles, nullptr);
  ASSERT_NE(at.stall_ticks, nullptr);
  ASSERT_NE(at.data_cache_misses, nullptr);
  const auto check = [&] {
    EXPECT_EQ(*at.busy_cycles, core.busy_cycles());
    EXPECT_EQ(static_cast<double>(*at.stall_ticks) / static_cast<double>(at.period_ticks), core.stalled_cycles());
    EXPECT_EQ(*at.data_cache_misses, core.data_cache_misses());
  };
  check();
  const uint64_t busy = core.busy_cycles(), misses = core.data_cache_misses();
  const double stalled = core.stalled_cycles();
  g_bench->run([&](HostApi& api) {
    api.read32(0x6000);  // a line not read before: a miss, a fill it stalls for
    for (unsigned i = 0; i < 6; ++i) api.write32(DEV_BASE + 4 * i, i);  // more stores than the buffer holds
  });
  EXPECT_GT(core.busy_cycles(), busy);
  EXPECT_GT(core.data_cache_misses(), misses);
  EXPECT_GT(core.stalled_cycles(), stalled);
  check();
}

// What the ISS launcher does with each load and store (HostCore's
// DataHitLines): a random mix of loads, stores, LDMs and STMs over more
// lines than the cache holds, each after some compute cycles, with the
// cache invalidated, cleaned and switched off and on between them. Made by
// calls on one bench and, on another, served through the granted line
// where it takes them: every figure of the two hosts, every value loaded,
// the time of each access and memory's contents must be the same.
namespace {

struct Traffic {
  std::vector<uint64_t> seen;  // values loaded and local times, in order
  unsigned served = 0;         // accesses the line took
};

Traffic random_traffic(Bench& bench, bool serve) {
  Traffic traffic;
  HostCore& core = bench.host;
  DataHitLines* hit = serve ? core.data_hit_lines() : nullptr;
  bench.run([&](HostApi& api) {
    std::mt19937 random(2026);
    const auto pick = [&](uint32_t n) { return static_cast<uint32_t>(random() % n); };
    // 16 KiB from 0x10000: twice the cache, so lines are replaced and dirty
    // halves written back; as a program's (its stack, the data it works
    // on), most accesses stay in a few lines, which change now and then.
    uint32_t lines[3] = {0x10000, 0x10020, 0x10040};
    const auto address = [&](unsigned align) {
      uint32_t& line = lines[pick(3)];
      if (pick(8) == 0) line = 0x10000 + pick(512) * 32;
      return line + pick(32 / align) * align;
    };
    const double start = api.now_seconds();
    for (unsigned i = 0; i < 20000; ++i) {
      const uint64_t pending = pick(4) == 0 ? pick(400) : pick(3);
      const auto charge = [&] {
        if (pending != 0) api.compute_cycles(pending);
      };
      const unsigned what = pick(100);
      if (what < 40) {
        const unsigned bytes = 1u << pick(3);
        const uint32_t at = address(bytes);
        uint32_t value = 0;
        if (hit != nullptr && hit->load(at, bytes, pending, value)) {
          ++traffic.served;
        } else {
          charge();
          value = bytes == 4 ? api.read32(at) : bytes == 2 ? api.read16(at) : api.read8(at);
        }
        traffic.seen.push_back(value);
      } else if (what < 80) {
        const unsigned bytes = 1u << pick(3);
        const uint32_t at = address(bytes), value = static_cast<uint32_t>(random());
        if (hit != nullptr && hit->store(at, bytes, pending, value)) {
          ++traffic.served;
        } else {
          charge();
          if (bytes == 4)
            api.write32(at, value);
          else if (bytes == 2)
            api.write16(at, static_cast<uint16_t>(value));
          else
            api.write8(at, static_cast<uint8_t>(value));
        }
      } else if (what < 90) {
        // Up to 16 words from anywhere in a line: a list may reach into
        // the next two lines.
        uint32_t words[16] = {};
        const unsigned count = 1 + pick(16);
        const uint32_t at = (address(4) & ~31u) + 4 * pick(8);
        if (hit != nullptr && hit->load_words(at, words, count, pending)) {
          ++traffic.served;
        } else {
          charge();
          api.read_words(at, words, count);
        }
        traffic.seen.insert(traffic.seen.end(), words, words + count);
      } else if (what < 99) {
        uint32_t words[16];
        const unsigned count = 1 + pick(16);
        for (uint32_t& word : words) word = static_cast<uint32_t>(random());
        const uint32_t at = (address(4) & ~31u) + 4 * pick(8);
        if (hit != nullptr && hit->store_words(at, words, count, pending)) {
          ++traffic.served;
        } else {
          charge();
          api.write_words(at, words, count);
        }
      } else {
        charge();
        switch (pick(4)) {
          case 0: core.invalidate_data_cache(); break;
          case 1: core.clean_data_line(address(4), pick(2) == 0); break;
          case 2: core.invalidate_data_line(address(4)); break;
          default:
            core.set_data_cache_control(false, true);
            api.read32(address(4));
            core.set_data_cache_control(true, true);
        }
      }
      traffic.seen.push_back(core.busy_cycles());
      traffic.seen.push_back(static_cast<uint64_t>(std::llround((api.now_seconds() - start) * 1e12)));
    }
    core.drain_write_buffer();
  });
  return traffic;
}

}  // namespace

TEST(Host, LoadsAndStoresServedInGrantedLinesAreWhatTheHostWouldDo) {
  const Traffic called = random_traffic(*g_called, false);
  const Traffic served = random_traffic(*g_served, true);
  EXPECT_GT(served.served, 5000u) << "the line serves most hits";
  EXPECT_EQ(called.seen, served.seen);
  auto figures = [](Bench& bench) {
    nlohmann::json stats = bench.host.stats_json(sc_core::sc_time_stamp());
    stats.erase("idle_ns");  // the benches ran one after the other: only their idle time differs
    return stats;
  };
  EXPECT_EQ(figures(*g_called), figures(*g_served));
  EXPECT_EQ(g_called->bus.initiator_stats()[0].reads, g_served->bus.initiator_stats()[0].reads);
  EXPECT_EQ(g_called->bus.initiator_stats()[0].writes, g_served->bus.initiator_stats()[0].writes);
  EXPECT_TRUE(std::equal(g_called->memory.data(), g_called->memory.data() + MEM_SIZE, g_served->memory.data()));
}

// The line stops being served the moment a hit there would no longer be one,
// or would no longer be the host's plain hit: replaced by a fill, the cache
// off, the line or the cache invalidated (a clean with invalidate too), the
// memory's direct window withdrawn.
TEST(Host, TheGrantedLineIsRevokedWhenItStopsBeingAPlainHit) {
  Bench& bench = *g_served;
  HostCore& core = bench.host;
  DataHitLines* hit = core.data_hit_lines();
  constexpr uint32_t A = 0x40000;  // in set 0, as A + k * 128 for every k
  uint32_t value = 0;
  const auto granted = [&](HostApi& api) {
    api.read32(A);  // a miss or a hit: afterwards a hit
    api.read32(A);  // a hit: the line granted
    return hit->load(A, 4, 0, value);
  };
  const auto revoked_by = [&](const std::function<void(HostApi&)>& change) {
    bool before = false, after = true;
    bench.run([&](HostApi& api) {
      before = granted(api);
      change(api);
      after = hit->load(A, 4, 0, value);
    });
    EXPECT_TRUE(before);
    return !after;
  };
  EXPECT_TRUE(revoked_by([&](HostApi& api) {
    // After 64 fills of set 0 from A on, the next fill there replaces A
    // (round-robin: the ways in turn).
    core.invalidate_data_cache();
    for (uint32_t k = 0; k < 64; ++k) api.read32(A + 128 * k);
    api.read32(A);
    EXPECT_TRUE(hit->load(A, 4, 0, value)) << "A still resident";
    api.read32(A + 128 * 64);
  })) << "replaced";
  EXPECT_TRUE(revoked_by([&](HostApi&) { core.set_data_cache_control(false, true); })) << "cache off";
  core.set_data_cache_control(true, true);
  EXPECT_TRUE(revoked_by([&](HostApi&) { core.invalidate_data_line(A); })) << "line invalidated";
  EXPECT_TRUE(revoked_by([&](HostApi&) { core.invalidate_data_cache(); })) << "cache invalidated";
  EXPECT_TRUE(revoked_by([&](HostApi&) { core.clean_data_line(A, true); })) << "cleaned and invalidated";
  EXPECT_TRUE(revoked_by([&](HostApi&) { bench.memory.invalidate_dmi(); })) << "direct window withdrawn";
  EXPECT_FALSE(revoked_by([&](HostApi&) { core.clean_data_line(A, false); })) << "a clean alone keeps the line";
  EXPECT_FALSE(revoked_by([&](HostApi& api) { api.read32(A + 128 * 65); })) << "another line's fill";
  EXPECT_FALSE(revoked_by([&](HostApi& api) {
    api.read32(A + 32);  // a fill or a hit,
    api.read32(A + 32);  // then a hit
  })) << "a hit on another line is granted beside it";
  EXPECT_TRUE(hit->load(A + 32, 4, 0, value));
}

// An STM across a line's end, served through the two granted lines, makes
// the second line's half dirty as the host's own write_words does: cleaning
// that line writes it back on the bus (the random traffic above keeps its
// few lines dirty, so it would not see a half left clean).
TEST(Host, AListAcrossTwoGrantedLinesDirtiesBoth) {
  Bench& bench = *g_served;
  HostCore& core = bench.host;
  DataHitLines* hit = core.data_hit_lines();
  constexpr uint32_t A = 0x48000;  // two lines (A, A + 32) no other test touches
  const uint32_t words[4] = {1, 2, 3, 4};
  uint64_t writes_before = 0, writes_after = 0;
  bool served = false;
  bench.run([&](HostApi& api) {
    core.invalidate_data_cache();
    for (int pass = 0; pass < 2; ++pass)  // fills, then hits: both lines granted, clean
      for (uint32_t line : {A, A + 32}) api.read32(line);
    served = hit->store_words(A + 24, words, 4, 0);  // A + 24 .. A + 39
    core.clean_data_line(A, false);
    core.drain_write_buffer();
    writes_before = bench.bus.initiator_stats()[0].writes;
    core.clean_data_line(A + 32, false);
    core.drain_write_buffer();
    writes_after = bench.bus.initiator_stats()[0].writes;
  });
  EXPECT_TRUE(served);
  EXPECT_GT(writes_after, writes_before) << "the second line's first half was written back";
  uint32_t stored[4] = {};
  bench.run([&](HostApi& api) { api.read_words(A + 24, stored, 4); });
  EXPECT_TRUE(std::equal(words, words + 4, stored));
}

TEST(Host, NoProtocolViolations) {
  for (const Bench* bench : {g_bench, g_write_through, g_called, g_served})
    EXPECT_EQ(bench->check_host.violation_count() + bench->check_memory.violation_count() +
                  bench->check_device.violation_count(),
              0u);
}

int sc_main(int argc, char* argv[]) {
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_time(1, sc_core::SC_US));
  test::ReportCapture quiet;  // the failing bench's error is asserted, not printed
  g_bench = new Bench("bench");
  g_write_through = new Bench("write_through_bench", true);
  g_called = new Bench("called_bench");
  g_served = new Bench("served_bench");
  g_failing = new FailingBench();
  return test::run_all_tests(argc, argv);
}
