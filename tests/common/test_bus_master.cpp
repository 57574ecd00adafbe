// TLM tests of the common bus master (tlm/common/bus_master.h): a transfer
// split into bursts of at most the configured length, issued one after
// another at the initiator's local time (checked to the cycle on an idle
// bus), reads and writes with their counters, the two error policies, the
// quantum keeper synchronising between bursts, and another initiator's
// transfer arbitrated between two bursts.
//
// Bench: master -> checker -> bus (100 MHz) -> checker -> memory whose
// 4 KiB window is populated up to 2 KiB; a test initiator on the same bus.
#include <cstring>
#include <vector>

#include "bus/ahb_bus.h"
#include "checker/protocol_checker.h"
#include "common/bus_master.h"
#include "mem/memory.h"
#include "tlm_bench/bench_params.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);
constexpr unsigned MEMORY_WAIT = 3;
constexpr uint32_t POPULATED = 0x800, WINDOW = 0x1000;

// The block that owns the bus master and its counters.
struct Owner : sc_core::sc_module {
  ActivityCounters counters;
  BusMaster out{"out", counters};
  explicit Owner(sc_core::sc_module_name name) : sc_core::sc_module(name) {}
};

struct Bench {
  Owner owner{"owner"};
  BusMaster& master = owner.out;
  ActivityCounters& counters = owner.counters;
  test::TestInitiator other{"other"};
  ProtocolChecker<32> check_master{"check_master"}, check_other{"check_other"}, check_memory{"check_memory"};
  AhbBus bus{"bus", test::bench_bus_params(CYCLE)};
  Memory memory{"memory", test::bench_memory_params(POPULATED, CYCLE, MEMORY_WAIT)};
  Bench() {
    master.bind(check_master.in);
    bus.attach(check_master.out, "master", 1);
    other.out.bind(check_other.in);
    bus.attach(check_other.out, "other", 0);
    bus.map(check_memory.in, 0, WINDOW, "memory");
    check_memory.out.bind(memory.in);
  }
  uint64_t count(const char* name) const { return counters.value(name); }
};

Bench* g_bench = nullptr;

// A burst of `words` words on an idle bus: address phase, wait states, beats.
sc_time burst(unsigned words) {
  return CYCLE * static_cast<double>(1 + MEMORY_WAIT + words);
}

}  // namespace

TEST(BusMaster, ATransferIsSplitIntoBurstsIssuedOneAfterAnother) {
  Bench& b = *g_bench;
  b.master.configure(16, BusMaster::OnError::stop);
  for (unsigned i = 0; i < 100; ++i) b.memory.data()[0x100 + i] = static_cast<uint8_t>(i);
  std::vector<uint8_t> data(100);
  const uint64_t transactions = b.count("bus.transactions");
  sc_time local, returned;
  bool ok = false;
  const sc_time bus_time_before = b.master.bus_time();
  test::run_thread([&] {
    const sc_time called = sc_core::sc_time_stamp();
    local = sc_time(20, sc_core::SC_NS);
    ok = b.master.transfer(tlm::TLM_READ_COMMAND, 0x100, data.data(), 100, local);
    returned = local;
    // Without a quantum keeper the master never waits: the kernel is where it was.
    EXPECT_EQ(sc_core::sc_time_stamp(), called);
  });
  EXPECT_TRUE(ok);
  for (unsigned i = 0; i < 100; ++i) ASSERT_EQ(data[i], i) << "byte " << i;
  // Six bursts of four words and one of one word, back to back, from the
  // local time given.
  EXPECT_EQ(returned, sc_time(20, sc_core::SC_NS) + burst(4) * 6.0 + burst(1));
  EXPECT_EQ(b.count("bus.transactions") - transactions, 7u);
  EXPECT_EQ(b.master.bus_time() - bus_time_before, burst(4) * 6.0 + burst(1));
  EXPECT_EQ(b.bus.initiator_stats()[0].transactions, b.count("bus.transactions"));
}

TEST(BusMaster, WritesAreCountedAsBytesWritten) {
  Bench& b = *g_bench;
  b.master.configure(64, BusMaster::OnError::stop);
  std::vector<uint8_t> data(128, 0xab);
  const uint64_t written = b.count("bus.bytes_written");
  sc_time local;
  test::run_thread([&] { EXPECT_TRUE(b.master.transfer(tlm::TLM_WRITE_COMMAND, 0x400, data.data(), 128, local)); });
  EXPECT_EQ(local, burst(16) * 2.0);
  EXPECT_EQ(b.count("bus.bytes_written") - written, 128u);
  EXPECT_EQ(b.memory.data()[0x400 + 127], 0xab);
}

TEST(BusMaster, AFailedBurstStopsATransferThatCannotGoOn) {
  Bench& b = *g_bench;
  b.master.configure(16, BusMaster::OnError::stop);
  test::ReportCapture reports;
  std::vector<uint8_t> data(64);
  const uint64_t transactions = b.count("bus.transactions"), errors = b.count("bus.errors"),
                 read = b.count("bus.bytes_read");
  sc_time local;
  bool ok = true;
  // The second burst is the first past the populated memory.
  test::run_thread([&] { ok = b.master.transfer(tlm::TLM_READ_COMMAND, POPULATED - 16, data.data(), 64, local); });
  EXPECT_FALSE(ok);
  EXPECT_EQ(b.count("bus.transactions") - transactions, 2u);
  EXPECT_EQ(b.count("bus.errors") - errors, 1u);
  EXPECT_EQ(b.count("bus.bytes_read") - read, 16u);
  EXPECT_TRUE(reports.contains("read of 16 bytes at 0x00000800 failed (address error)"));
}

TEST(BusMaster, AFailedReadBurstReadsAsZerosWhenTheTransferMustGoOn) {
  Bench& b = *g_bench;
  b.master.configure(16, BusMaster::OnError::zeros_and_continue);
  test::ReportCapture reports;
  std::vector<uint8_t> data(48, 0xee);
  std::memset(b.memory.data() + POPULATED - 16, 0x11, 16);
  const uint64_t transactions = b.count("bus.transactions"), errors = b.count("bus.errors");
  sc_time local;
  bool ok = true;
  test::run_thread([&] { ok = b.master.transfer(tlm::TLM_READ_COMMAND, POPULATED - 16, data.data(), 48, local); });
  EXPECT_FALSE(ok);
  EXPECT_EQ(b.count("bus.transactions") - transactions, 3u);
  EXPECT_EQ(b.count("bus.errors") - errors, 2u);
  EXPECT_EQ(data[0], 0x11);
  EXPECT_EQ(data[16], 0);
  EXPECT_EQ(data[47], 0);
}

TEST(BusMaster, AQuantumKeeperSynchronisesBetweenBursts) {
  Bench& b = *g_bench;
  b.master.configure(16, BusMaster::OnError::stop);
  std::vector<uint8_t> data(16 * 10);
  tlm_utils::tlm_quantumkeeper keeper;
  tlm_utils::tlm_quantumkeeper::set_global_quantum(burst(4) * 3.0);
  sc_time end;
  const sc_time start = test::run_thread([&] {
    keeper.reset();
    sc_time local = keeper.get_local_time();
    EXPECT_TRUE(b.master.transfer(tlm::TLM_READ_COMMAND, 0, data.data(), 160, local, &keeper));
    end = sc_core::sc_time_stamp() + keeper.get_local_time();
    // The keeper has waited for the kernel at least once on the way.
    EXPECT_GT(sc_core::sc_time_stamp(), start);
  });
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_core::SC_ZERO_TIME);
  // Waiting changes nothing on an idle bus: the bursts are still back to back.
  EXPECT_EQ(end, start + burst(4) * 10.0);
}

TEST(BusMaster, AnotherInitiatorIsArbitratedBetweenTwoBursts) {
  Bench& b = *g_bench;
  b.master.configure(16, BusMaster::OnError::stop);
  std::vector<uint8_t> data(16 * 4);
  tlm_utils::tlm_quantumkeeper keeper;
  tlm_utils::tlm_quantumkeeper::set_global_quantum(burst(4));
  sc_time other_done;
  const sc_time start = test::run_thread([&] {
    sc_core::sc_spawn([&] {
      // Asks for the bus while the master's first burst is under way.
      sc_core::wait(CYCLE * 2.0);
      uint32_t word = 0;
      const auto result = b.other.read(0x700, reinterpret_cast<uint8_t*>(&word), 4);
      other_done = sc_core::sc_time_stamp() + result.delay;
    });
    keeper.reset();
    sc_time local = keeper.get_local_time();
    EXPECT_TRUE(b.master.transfer(tlm::TLM_READ_COMMAND, 0, data.data(), 64, local, &keeper));
  });
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_core::SC_ZERO_TIME);
  // The other read waits for the first burst only, then takes its own cycles.
  EXPECT_EQ(other_done, start + burst(4) + burst(1));
}

TEST(BusMaster, NoProtocolViolations) {
  EXPECT_EQ(g_bench->check_master.violation_count() + g_bench->check_other.violation_count() +
                g_bench->check_memory.violation_count(),
            0u);
}

int sc_main(int argc, char* argv[]) {
  g_bench = new Bench();
  return test::run_all_tests(argc, argv);
}
