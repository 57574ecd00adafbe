// TLM tests of the AHB-style bus: decode, wait states, bursts, arbitration
// order, contention between initiators, error responses, DMI and debug
// transport, statistics. A base-protocol checker sits on every socket.
#include <cstring>
#include <memory>

#include <tlm_utils/simple_target_socket.h>

#include "bus/ahb_bus.h"
#include "checker/protocol_checker.h"
#include "common/direct_transport.h"
#include "common/schedule_untouched.h"
#include "common/transfer_train.h"
#include "mem/memory.h"
#include "tlm_bench/bench_params.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::SC_NS;
using sc_core::sc_time;
using test::TestInitiator;

namespace {

const sc_time CYCLE(10, SC_NS);    // 100 MHz bus: times are easy to read
constexpr unsigned FAST_WAIT = 2;  // wait states of the fast memory
constexpr unsigned SLOW_WAIT = 5;
constexpr uint64_t FAST_BASE = 0x0000;
constexpr uint64_t SLOW_BASE = 0x10000;
constexpr uint64_t SLOW_POPULATED = 0x4000;  // the slow window is 0x10000 bytes, only 16 KiB populated
constexpr uint64_t UNMAPPED = 0xF0000000;
constexpr uint64_t PROBE_BASE = 0x20000;

// A target that notes the delay each access arrives with and adds one cycle.
struct ProbeTarget : sc_core::sc_module {
  tlm_utils::simple_target_socket<ProbeTarget, 32> in;
  std::vector<sc_time> arrivals;  // sc_time_stamp() + delay at each call
  explicit ProbeTarget(sc_core::sc_module_name name) : sc_core::sc_module(name), in("in") {
    in.register_b_transport(this, &ProbeTarget::b_transport);
  }
  void b_transport(tlm::tlm_generic_payload& gp, sc_time& delay) {
    arrivals.push_back(sc_core::sc_time_stamp() + delay);
    delay += CYCLE;
    gp.set_response_status(tlm::TLM_OK_RESPONSE);
  }
};

// Three initiators (A highest priority) and two memories, every socket
// behind a protocol checker.
struct Bench {
  AhbBus bus;
  Memory fast, slow;
  ProbeTarget probe;
  TestInitiator a, b, c;
  ProtocolChecker<32> check_a, check_b, check_c, check_fast, check_slow;

  Bench(const char* name, Arbitration arbitration)
      : bus((std::string(name) + "_bus").c_str(), params(arbitration)),
        fast((std::string(name) + "_fast").c_str(), memory(0x10000, FAST_WAIT)),
        slow((std::string(name) + "_slow").c_str(), memory(SLOW_POPULATED, SLOW_WAIT)),
        probe((std::string(name) + "_probe").c_str()),
        a((std::string(name) + "_a").c_str()),
        b((std::string(name) + "_b").c_str()),
        c((std::string(name) + "_c").c_str()),
        check_a((std::string(name) + "_check_a").c_str()),
        check_b((std::string(name) + "_check_b").c_str()),
        check_c((std::string(name) + "_check_c").c_str()),
        check_fast((std::string(name) + "_check_fast").c_str()),
        check_slow((std::string(name) + "_check_slow").c_str()) {
    a.out.bind(check_a.in);
    b.out.bind(check_b.in);
    c.out.bind(check_c.in);
    bus.attach(check_a.out, "a", 0);
    bus.attach(check_b.out, "b", 1);
    bus.attach(check_c.out, "c", 2);
    bus.map(check_fast.in, FAST_BASE, 0x10000, "fast");
    bus.map(check_slow.in, SLOW_BASE, 0x10000, "slow");
    bus.map(probe.in, PROBE_BASE, 0x100, "probe");
    check_fast.out.bind(fast.in);
    check_slow.out.bind(slow.in);
  }
  static BusParams params(Arbitration arbitration) {
    BusParams p = BusParams::defaults();
    p.clock_period = CYCLE;
    p.arbitration = arbitration;
    p.width_bytes = 4;
    p.address_cycles = 1;
    p.error_cycles = 2;
    return p;
  }
  static MemoryParams memory(uint64_t size, unsigned wait) { return test::bench_memory_params(size, CYCLE, wait); }
  unsigned violations() {
    return check_a.violation_count() + check_b.violation_count() + check_c.violation_count() +
           check_fast.violation_count() + check_slow.violation_count();
  }
};

// A target with two doors: its socket (the forward interface) and
// DirectTransport (common/direct_transport.h); both serve an access alike
// (FAST_WAIT cycles, the data copied), each counts its calls.
struct TwoDoorTarget : sc_core::sc_module, public tlm::tlm_fw_transport_if<>, public DirectTransport {
  tlm::tlm_target_socket<32> in;
  uint8_t bytes[64] = {};
  unsigned socket_calls = 0, direct_calls = 0;
  explicit TwoDoorTarget(sc_core::sc_module_name name) : sc_core::sc_module(name), in("in") {
    in.bind(static_cast<tlm::tlm_fw_transport_if<>&>(*this));
  }
  void serve(tlm::tlm_generic_payload& gp, sc_time& delay) {
    uint8_t* at = bytes + gp.get_address();
    if (gp.is_write())
      std::memcpy(at, gp.get_data_ptr(), gp.get_data_length());
    else
      std::memcpy(gp.get_data_ptr(), at, gp.get_data_length());
    delay += CYCLE * static_cast<double>(FAST_WAIT);
    gp.set_response_status(tlm::TLM_OK_RESPONSE);
  }
  // Each door also reports the train's count it was given and says its
  // access scheduled nothing (DirectExtras, or the payload's extensions).
  unsigned last_transfers = 0;
  void b_transport(tlm::tlm_generic_payload& gp, sc_time& delay) override {
    ++socket_calls;
    serve(gp, delay);
    last_transfers = transfers_of(gp);
    mark_schedule_untouched(gp);
  }
  void direct_b_transport(tlm::tlm_generic_payload& gp, sc_time& delay, DirectExtras& extras) override {
    ++direct_calls;
    serve(gp, delay);
    last_transfers = extras.transfers;
    extras.untouched = true;
  }
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase&, sc_time&) override {
    gp.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return tlm::TLM_COMPLETED;
  }
  bool get_direct_mem_ptr(tlm::tlm_generic_payload&, tlm::tlm_dmi&) override { return false; }
  unsigned transport_dbg(tlm::tlm_generic_payload&) override { return 0; }
};

// One initiator; a two-door target on the bus itself and one behind a
// protocol checker (which has only a socket).
struct DoorsBench {
  AhbBus bus;
  TestInitiator a;
  TwoDoorTarget direct, checked;
  ProtocolChecker<32> check;
  DoorsBench()
      : bus("doors_bus", Bench::params(Arbitration::fixed_priority)),
        a("doors_a"),
        direct("doors_direct"),
        checked("doors_checked"),
        check("doors_check") {
    bus.attach(a.out, "a", 0);
    bus.map(direct.in, 0x0, 0x40, "direct");
    bus.map(check.in, 0x100, 0x40, "checked");
    check.out.bind(checked.in);
  }
};

Bench* g_fixed = nullptr;
DoorsBench* g_doors = nullptr;
Bench* g_round_robin = nullptr;
Bench* g_histogram = nullptr;  // for the wait histogram's test alone: its counts start at 0

// Cycles of one access: address phase + wait states + one per beat.
sc_time access(unsigned wait, unsigned beats) {
  return CYCLE * static_cast<double>(1 + wait + beats);
}

}  // namespace

TEST(AhbBus, SingleReadTakesAddressPhaseWaitStatesAndOneBeat) {
  Bench& bench = *g_fixed;
  sc_time done;
  const sc_time start = test::run_thread([&] {
    uint32_t value = 0;
    auto r = bench.a.read(FAST_BASE + 0x100, reinterpret_cast<uint8_t*>(&value), 4);
    EXPECT_EQ(r.status, tlm::TLM_OK_RESPONSE);
    sc_core::wait(r.delay);
    done = sc_core::sc_time_stamp();
  });
  EXPECT_EQ(done, start + access(FAST_WAIT, 1));
  EXPECT_EQ(bench.violations(), 0u);
}

TEST(AhbBus, BurstTakesOneCyclePerBeatAndTargetWaitStates) {
  Bench& bench = *g_fixed;
  sc_time fast_done, slow_done;
  uint8_t data[32];
  for (unsigned i = 0; i < 32; ++i) data[i] = static_cast<uint8_t>(i * 7);
  const sc_time start = test::run_thread([&] {
    auto w = bench.a.write(FAST_BASE + 0x200, data, 32);
    EXPECT_EQ(w.status, tlm::TLM_OK_RESPONSE);
    sc_core::wait(w.delay);
    fast_done = sc_core::sc_time_stamp();
    auto s = bench.a.write(SLOW_BASE + 0x40, data, 32);
    sc_core::wait(s.delay);
    slow_done = sc_core::sc_time_stamp();
  });
  EXPECT_EQ(fast_done, start + access(FAST_WAIT, 8));
  EXPECT_EQ(slow_done, fast_done + access(SLOW_WAIT, 8));
  EXPECT_EQ(std::memcmp(bench.fast.data() + 0x200, data, 32), 0);
  EXPECT_EQ(std::memcmp(bench.slow.data() + 0x40, data, 32), 0);
}

TEST(AhbBus, FixedPriorityServesSimultaneousRequestsByPriority) {
  Bench& bench = *g_fixed;
  sc_time done_a, done_b, done_c;
  const sc_time start = test::run_thread([&] {
    // Started lowest priority first, so call order is not what decides.
    auto issue = [](TestInitiator& initiator, sc_time& done) {
      return [&initiator, &done] {
        uint32_t v;
        auto r = initiator.read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4);
        sc_core::wait(r.delay);
        done = sc_core::sc_time_stamp();
      };
    };
    sc_core::sc_spawn(issue(bench.c, done_c));
    sc_core::sc_spawn(issue(bench.b, done_b));
    sc_core::sc_spawn(issue(bench.a, done_a));
  });
  const sc_time one = access(FAST_WAIT, 1);
  EXPECT_EQ(done_a, start + one);
  EXPECT_EQ(done_b, start + one * 2.0);
  EXPECT_EQ(done_c, start + one * 3.0);
  EXPECT_EQ(bench.violations(), 0u);
}

TEST(AhbBus, RoundRobinRotatesPastTheLastGrantedInitiator) {
  Bench& bench = *g_round_robin;
  std::vector<std::string> order;
  auto simultaneous = [&] {
    auto issue = [&order](TestInitiator& initiator, const char* name) {
      return [&initiator, &order, name] {
        uint32_t v;
        auto r = initiator.read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4);
        sc_core::wait(r.delay);
        order.push_back(name);
      };
    };
    sc_core::sc_spawn(issue(bench.a, "a"));
    sc_core::sc_spawn(issue(bench.b, "b"));
    sc_core::sc_spawn(issue(bench.c, "c"));
  };
  auto alone = [&](TestInitiator& initiator) {
    test::run_thread([&] {
      uint32_t v;
      sc_core::wait(initiator.read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4).delay);
    });
  };
  alone(bench.a);  // a was granted last: b is next in turn
  test::run_thread(simultaneous);
  EXPECT_EQ(order, (std::vector<std::string>{"b", "c", "a"}));
  order.clear();
  alone(bench.b);  // now c is next in turn
  test::run_thread(simultaneous);
  EXPECT_EQ(order, (std::vector<std::string>{"c", "a", "b"}));
  EXPECT_EQ(bench.violations(), 0u);
}

TEST(AhbBus, ContendingInitiatorWaitsForTheBusAndIsCharged) {
  Bench& bench = *g_fixed;
  const BusInitiatorStats before_b = bench.bus.initiator_stats()[1];
  sc_time done_a, done_b;
  const sc_time start = test::run_thread([&] {
    sc_core::sc_spawn([&] {
      uint8_t data[32] = {};
      auto r = bench.a.read(FAST_BASE, data, 32);  // 8 beats from the start
      sc_core::wait(r.delay);
      done_a = sc_core::sc_time_stamp();
    });
    sc_core::sc_spawn([&] {
      // b runs 2 cycles ahead in its quantum and wants the bus while a has it.
      uint32_t v;
      auto r = bench.b.read(FAST_BASE + 4, reinterpret_cast<uint8_t*>(&v), 4, CYCLE * 2.0);
      sc_core::wait(r.delay);
      done_b = sc_core::sc_time_stamp();
    });
  });
  EXPECT_EQ(done_a, start + access(FAST_WAIT, 8));
  EXPECT_EQ(done_b, done_a + access(FAST_WAIT, 1));
  const BusInitiatorStats& after_b = bench.bus.initiator_stats()[1];
  EXPECT_EQ(after_b.transactions - before_b.transactions, 1u);
  EXPECT_EQ(after_b.wait_cycles - before_b.wait_cycles, 1 + FAST_WAIT + 8 - 2);
  EXPECT_EQ(after_b.busy_cycles - before_b.busy_cycles, 1 + FAST_WAIT + 1);
}

TEST(AhbBus, InitiatorAheadInTimeDoesNotBlockOneBehind) {
  Bench& bench = *g_fixed;
  sc_time done_a, done_b;
  const sc_time start = test::run_thread([&] {
    uint32_t v;
    const sc_time now = sc_core::sc_time_stamp();
    // a is 50 cycles ahead; b's later call is for an earlier time and fits
    // in the idle bus before a's transfer.
    auto ra = bench.a.read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4, CYCLE * 50.0);
    auto rb = bench.b.read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4, CYCLE * 10.0);
    done_a = now + ra.delay;
    done_b = now + rb.delay;
  });
  EXPECT_EQ(done_a, start + CYCLE * 50.0 + access(FAST_WAIT, 1));
  EXPECT_EQ(done_b, start + CYCLE * 10.0 + access(FAST_WAIT, 1));
}

// An initiator far ahead leaves many reservations with gaps between them
// (more than the timeline keeps before it prunes); one behind still gets the
// first gap long enough for it, wherever that is.
TEST(AhbBus, ManyReservationsAheadLeaveTheirGapsToAnInitiatorBehind) {
  Bench& bench = *g_fixed;
  constexpr unsigned COUNT = 150;  // reservations of 1 + FAST_WAIT + 1 = 4 cycles, every 10 cycles
  sc_time start, done_short, done_long, done_after;
  test::run_thread([&] {
    uint32_t v;
    start = sc_core::sc_time_stamp();
    for (unsigned k = 0; k < COUNT; ++k)
      bench.a.read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4, CYCLE * (100.0 + 10.0 * k));
    // Cycle 855 is in the gap [854, 860) after the 76th: 4 cycles fit.
    done_short = start + bench.b.read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4, CYCLE * 855.0).delay;
    // 8 beats (11 cycles) fit in no gap: after the last reservation.
    uint8_t line[32];
    done_long = start + bench.c.read(FAST_BASE, line, 32, CYCLE * 300.0).delay;
    // Once the kernel is past them all, a request is placed at once.
    sc_core::wait(CYCLE * 2000.0);
    done_after = sc_core::sc_time_stamp() + bench.b.read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4).delay;
    sc_core::wait(done_after - sc_core::sc_time_stamp());
  });
  EXPECT_EQ(done_short, start + CYCLE * 859.0);
  EXPECT_EQ(done_long, start + CYCLE * (100.0 + 10.0 * (COUNT - 1) + 4 + 11));
  EXPECT_EQ(done_after, start + CYCLE * 2000.0 + access(FAST_WAIT, 1));
  EXPECT_EQ(bench.violations(), 0u);
}

// A synchronised request waits a delta cycle for the others of its instant
// only when there can be others: alone, it is served at once (with the
// same grant, FixedPriorityServesSimultaneousRequestsByPriority checks the
// others).
TEST(AhbBus, ALoneSynchronisedRequestIsServedWithoutADeltaCycle) {
  Bench& bench = *g_fixed;
  uint64_t deltas = 0;
  sc_time delay;
  test::run_thread([&] {
    uint32_t v;
    const uint64_t before = sc_core::sc_delta_count();
    delay = bench.a.read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4).delay;
    deltas = sc_core::sc_delta_count() - before;
    sc_core::wait(delay);
  });
  EXPECT_EQ(deltas, 0u);
  EXPECT_EQ(delay, access(FAST_WAIT, 1));
}

// A loosely-timed target must see an access at the initiator's local time
// (a register write that starts something starts then), not at the kernel's
// time, which lags by up to a quantum.
TEST(AhbBus, TargetSeesTheAccessAtTheInitiatorsAnnotatedTime) {
  Bench& bench = *g_fixed;
  bench.probe.arrivals.clear();
  sc_time start, done;
  test::run_thread([&] {
    start = sc_core::sc_time_stamp();
    uint32_t value = 1;
    // 35 ns ahead: the request is at the next bus edge, 40 ns.
    const auto r = bench.a.write(PROBE_BASE, reinterpret_cast<uint8_t*>(&value), 4, sc_time(35, SC_NS));
    EXPECT_EQ(r.status, tlm::TLM_OK_RESPONSE);
    done = start + r.delay;
  });
  ASSERT_EQ(bench.probe.arrivals.size(), 1u);
  EXPECT_EQ(bench.probe.arrivals[0], start + sc_time(40, SC_NS));
  // Address phase and the target's one cycle (one beat), after the request.
  EXPECT_EQ(done, start + sc_time(40, SC_NS) + 2 * CYCLE);
}

TEST(AhbBus, UnmappedAddressGetsAddressErrorAndAWarningNamingInitiator) {
  Bench& bench = *g_fixed;
  test::ReportCapture reports;
  const uint64_t errors_before = bench.bus.initiator_stats()[2].errors;
  tlm::tlm_response_status status = tlm::TLM_INCOMPLETE_RESPONSE;
  sc_time done;
  const sc_time start = test::run_thread([&] {
    uint32_t v;
    auto r = bench.c.read(UNMAPPED, reinterpret_cast<uint8_t*>(&v), 4);
    status = r.status;
    sc_core::wait(r.delay);
    done = sc_core::sc_time_stamp();
  });
  EXPECT_EQ(status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  EXPECT_EQ(done, start + CYCLE * 3.0);  // address phase + two-cycle error response
  EXPECT_EQ(bench.bus.initiator_stats()[2].errors - errors_before, 1u);
  EXPECT_TRUE(reports.contains("unmapped read by c at 0xf0000000")) << testing::PrintToString(reports.messages());
}

TEST(AhbBus, TargetErrorInsideAMappedWindowIsPassedBack) {
  Bench& bench = *g_fixed;
  test::ReportCapture reports;
  tlm::tlm_response_status status = tlm::TLM_INCOMPLETE_RESPONSE;
  test::run_thread([&] {
    uint32_t v = 0;
    status = bench.a.write(SLOW_BASE + SLOW_POPULATED, reinterpret_cast<uint8_t*>(&v), 4).status;
  });
  EXPECT_EQ(status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  EXPECT_EQ(bench.violations(), 0u);
}

TEST(AhbBus, DmiIsTranslatedToBusAddressesAndInvalidationReachesInitiators) {
  Bench& bench = *g_fixed;
  tlm::tlm_generic_payload gp;
  gp.set_command(tlm::TLM_READ_COMMAND);
  gp.set_address(SLOW_BASE + 0x123);
  tlm::tlm_dmi dmi;
  ASSERT_TRUE(bench.a.out->get_direct_mem_ptr(gp, dmi));
  EXPECT_EQ(gp.get_address(), SLOW_BASE + 0x123);  // the bus restores the address
  EXPECT_EQ(dmi.get_start_address(), SLOW_BASE);
  EXPECT_EQ(dmi.get_end_address(), SLOW_BASE + SLOW_POPULATED - 1);
  EXPECT_EQ(dmi.get_dmi_ptr(), bench.slow.data());
  EXPECT_TRUE(dmi.is_read_write_allowed());
  // Latency of a single beat: wait states + beat, plus the bus's address phase.
  EXPECT_EQ(dmi.get_read_latency(), access(SLOW_WAIT, 1));

  bench.b.invalidations.clear();
  bench.slow.invalidate_dmi();
  ASSERT_EQ(bench.b.invalidations.size(), 1u);
  EXPECT_EQ(bench.b.invalidations[0].first, SLOW_BASE);
  EXPECT_EQ(bench.b.invalidations[0].second, SLOW_BASE + SLOW_POPULATED - 1);

  gp.set_address(UNMAPPED);
  EXPECT_FALSE(bench.a.out->get_direct_mem_ptr(gp, dmi));
  EXPECT_EQ(bench.violations(), 0u);
}

TEST(AhbBus, DebugTransportReachesTargetWithoutTime) {
  Bench& bench = *g_fixed;
  const sc_time before = sc_core::sc_time_stamp();
  uint8_t in[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_EQ(bench.a.debug(tlm::TLM_WRITE_COMMAND, SLOW_BASE + 0x80, in, 8), 8u);
  uint8_t out[8] = {};
  EXPECT_EQ(bench.c.debug(tlm::TLM_READ_COMMAND, SLOW_BASE + 0x80, out, 8), 8u);
  EXPECT_EQ(std::memcmp(in, out, 8), 0);
  EXPECT_EQ(std::memcmp(bench.slow.data() + 0x80, in, 8), 0);
  EXPECT_EQ(bench.a.debug(tlm::TLM_READ_COMMAND, UNMAPPED, out, 8), 0u);
  EXPECT_EQ(sc_core::sc_time_stamp(), before);
}

TEST(AhbBus, StatisticsCountTransactionsBytesAndUtilisation) {
  AhbBus& bus = g_fixed->bus;
  const BusInitiatorStats before = bus.initiator_stats()[0];
  const uint64_t bus_busy_before = bus.busy_cycles();
  test::run_thread([&] {
    uint8_t data[16] = {};
    for (int i = 0; i < 3; ++i) sc_core::wait(g_fixed->a.write(FAST_BASE + 0x400, data, 16).delay);
    sc_core::wait(g_fixed->a.read(FAST_BASE + 0x400, data, 16).delay);
  });
  const BusInitiatorStats& after = bus.initiator_stats()[0];
  EXPECT_EQ(after.transactions - before.transactions, 4u);
  EXPECT_EQ(after.writes - before.writes, 3u);
  EXPECT_EQ(after.reads - before.reads, 1u);
  EXPECT_EQ(after.bytes - before.bytes, 64u);
  EXPECT_EQ(after.beats - before.beats, 16u);
  EXPECT_EQ(after.busy_cycles - before.busy_cycles, 4u * (1 + FAST_WAIT + 4));
  EXPECT_EQ(bus.busy_cycles() - bus_busy_before, 4u * (1 + FAST_WAIT + 4));
  const auto json = bus.stats_json(sc_core::sc_time_stamp());
  const double utilisation = json["initiators"]["a"]["utilisation"].get<double>();
  EXPECT_GT(utilisation, 0.0);
  EXPECT_LT(utilisation, 1.0);
  EXPECT_DOUBLE_EQ(json["clock_mhz"].get<double>(), 100.0);
}

TEST(AhbBus, WaitHistogramHasEachAccessWaitInItsPowerOfTwoBucket) {
  Bench& bench = *g_histogram;
  const auto simultaneous = [&] {
    for (TestInitiator* initiator : {&bench.a, &bench.b, &bench.c})
      sc_core::sc_spawn([initiator] {
        uint32_t v;
        sc_core::wait(initiator->read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4).delay);
      });
  };
  // Twice three single reads at once under fixed priority: each takes
  // 1 + FAST_WAIT + 1 = 4 cycles, so a waits 0, b 4 and c 8; then c alone, 0.
  test::run_thread(simultaneous);
  test::run_thread(simultaneous);
  test::run_thread([&] {
    uint32_t v;
    sc_core::wait(bench.c.read(FAST_BASE, reinterpret_cast<uint8_t*>(&v), 4).delay);
  });
  const nlohmann::json waits = bench.bus.stats_json(sc_core::sc_time_stamp())["histograms"]["wait_cycles"];
  EXPECT_EQ(waits["a"]["count"], 2u);
  EXPECT_EQ(waits["a"]["max"], 0u);
  EXPECT_EQ(waits["a"]["buckets"], nlohmann::json::parse(R"([{"low": 0, "high": 0, "count": 2}])"));
  EXPECT_EQ(waits["b"]["buckets"], nlohmann::json::parse(R"([{"low": 4, "high": 7, "count": 2}])"));
  EXPECT_EQ(waits["b"]["min"], 4u);
  EXPECT_EQ(waits["c"]["buckets"],
            nlohmann::json::parse(R"([{"low": 0, "high": 0, "count": 1}, {"low": 8, "high": 15, "count": 2}])"));
  EXPECT_EQ(waits["c"]["sum"], 16u);
  EXPECT_EQ(waits["c"]["min"], 0u);
  EXPECT_EQ(waits["c"]["max"], 8u);
  // The histogram's sum is the initiator's wait_cycles.
  EXPECT_EQ(waits["c"]["sum"], bench.bus.initiator_stats()[2].wait_cycles);
}

TEST(AhbBus, ATargetThatIsADirectTransportIsCalledThroughItAndAnyOtherThroughItsSocket) {
  DoorsBench& bench = *g_doors;
  const uint32_t word = 0x12345678;
  sc_time direct_write, direct_read, checked_write, checked_read;
  uint32_t direct_value = 0, checked_value = 0;
  test::run_thread([&] {
    const auto w = bench.a.write32(0x8, word);
    sc_core::wait(w.delay);
    direct_write = w.delay;
    TestInitiator::Result r{};
    direct_value = bench.a.read32(0x8, &r);
    sc_core::wait(r.delay);
    direct_read = r.delay;
    const auto cw = bench.a.write32(0x108, word);
    sc_core::wait(cw.delay);
    checked_write = cw.delay;
    checked_value = bench.a.read32(0x108, &r);
    sc_core::wait(r.delay);
    checked_read = r.delay;
  });
  EXPECT_EQ(bench.direct.direct_calls, 2u);
  EXPECT_EQ(bench.direct.socket_calls, 0u);
  EXPECT_EQ(bench.checked.direct_calls, 0u);
  EXPECT_EQ(bench.checked.socket_calls, 2u);
  // Either door, the same access: the data and the time.
  EXPECT_EQ(direct_value, word);
  EXPECT_EQ(checked_value, word);
  // The address phase, then the target's latency (longer than the beat).
  EXPECT_EQ(direct_write, CYCLE * (1.0 + FAST_WAIT));
  EXPECT_EQ(direct_read, CYCLE * (1.0 + FAST_WAIT));
  EXPECT_EQ(checked_write, direct_write);
  EXPECT_EQ(checked_read, direct_read);
  EXPECT_EQ(bench.check.violation_count(), 0u);
}

// A payload's train count and its target's "untouched" cross the bus
// whichever door the target has: a socket initiator's extensions become
// DirectExtras for a direct target, and its "untouched" comes back in the
// payload's extension; a target behind a checker reads and sets the
// extensions themselves.
TEST(AhbBus, TheTrainAndUntouchedCrossEitherDoor) {
  DoorsBench& bench = *g_doors;
  const auto access = [&](uint64_t address, unsigned transfers) {
    uint8_t data[12] = {};
    tlm::tlm_generic_payload gp;
    gp.set_command(tlm::TLM_WRITE_COMMAND);
    gp.set_address(address);
    gp.set_data_ptr(data);
    gp.set_data_length(sizeof data);
    gp.set_streaming_width(sizeof data);
    auto* train = new TransferTrain;
    train->transfers = transfers;
    gp.set_extension(train);
    auto* untouched = new ScheduleUntouched;
    gp.set_extension(untouched);
    sc_time delay = sc_core::SC_ZERO_TIME;
    bench.a.out->b_transport(gp, delay);
    sc_core::wait(delay);
    return untouched->untouched;  // the payload deletes its extensions
  };
  bool direct_untouched = false, checked_untouched = false;
  test::run_thread([&] {
    direct_untouched = access(0x10, 3);
    checked_untouched = access(0x110, 3);
  });
  EXPECT_EQ(bench.direct.last_transfers, 3u);
  EXPECT_EQ(bench.checked.last_transfers, 3u);
  EXPECT_TRUE(direct_untouched);
  EXPECT_TRUE(checked_untouched);
}

int sc_main(int argc, char* argv[]) {
  g_fixed = new Bench("fixed", Arbitration::fixed_priority);
  g_doors = new DoorsBench();
  g_histogram = new Bench("histogram", Arbitration::fixed_priority);
  g_round_robin = new Bench("rr", Arbitration::round_robin);
  return test::run_all_tests(argc, argv);
}
