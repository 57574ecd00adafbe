// TLM tests of the host's frame copy (tlm/host/README.md, "The frame
// copy"): HostApi::copy_words simulated with its blocks in closed form and
// their requests handed to the bus, the memory and the device together,
// must give what the same calls give (HostApi's own copy_words: load_span,
// write_words and compute_cycles for each block): every time the host
// reads, every host, bus and target figure, every byte. Two benches of each
// kind run the same random programs, one by calls and one as a unit: with
// run-ahead off and on, a 200 ns quantum, another initiator's bursts
// reserving the bus ahead of the host, a third in a process of its own
// that runs whenever the host lets the kernel run, dirty lines that the
// copy's fills evict, lines it finds in the cache, copies of a part of a
// block and unaligned ones, stores and reads between them.
//
// Bench: host (200 MHz) -> bus (100 MHz) -> memory at 0 (cacheable) and a
// second memory at 0x4000000 standing for the display port (uncacheable,
// slower, counting the copies handed to it as units).
#include <cstring>
#include <random>

#include "bus/ahb_bus.h"
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

const sc_time HOST_CYCLE(5, SC_NS);
const sc_time BUS_CYCLE(10, SC_NS);
constexpr uint32_t MEM_SIZE = 1u << 20;
constexpr uint32_t PORT = 0x4000000, PORT_SIZE = 1u << 16;

HostParams host_params(bool run_ahead) {
  HostParams p = test::bench_host_params(HOST_CYCLE, MEM_SIZE);
  if (run_ahead) p.run_ahead = sc_time(5, sc_core::SC_US);
  return p;
}

// Between the bus and the port's memory: passes everything on and counts
// the blocks handed over as units.
struct CopyCounter : sc_core::sc_module, tlm::tlm_fw_transport_if<>, DirectTransport {
  tlm::tlm_target_socket<32> in;
  tlm_utils::simple_initiator_socket<CopyCounter, 32> out;
  tlm::tlm_fw_transport_if<>* port = nullptr;
  DirectTransport* direct = nullptr;
  uint64_t runs = 0, blocks = 0;

  CopyCounter(sc_core::sc_module_name name, Memory& target) : sc_core::sc_module(name), in("in"), out("out") {
    in.bind(static_cast<tlm::tlm_fw_transport_if<>&>(*this));
    out.bind(target.in);
  }
  void end_of_elaboration() override {
    port = out.operator->();
    direct = direct_transport_of(port);
  }
  void b_transport(tlm::tlm_generic_payload& gp, sc_time& delay) override { port->b_transport(gp, delay); }
  void direct_b_transport(tlm::tlm_generic_payload& gp, sc_time& delay, DirectExtras& extras) override {
    direct->direct_b_transport(gp, delay, extras);
  }
  bool quote_accesses(tlm::tlm_command command, uint64_t address, unsigned bytes, size_t count, uint64_t& latency_ticks,
                      bool& untouched) override {
    return direct->quote_accesses(command, address, bytes, count, latency_ticks, untouched);
  }
  void direct_accesses(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned bytes,
                       size_t count) override {
    ++runs;
    blocks += count;
    direct->direct_accesses(command, address, data, bytes, count);
  }
  unsigned transport_dbg(tlm::tlm_generic_payload& gp) override { return port->transport_dbg(gp); }
  bool get_direct_mem_ptr(tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi) override {
    return port->get_direct_mem_ptr(gp, dmi);
  }
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& phase, sc_time& delay) override {
    return port->nb_transport_fw(gp, phase, delay);
  }
};

struct Bench : sc_core::sc_module {
  SC_HAS_PROCESS(Bench);
  Host host;
  AhbBus bus;
  Memory memory;
  Memory port;
  CopyCounter counter;
  test::TestInitiator other;
  test::TestInitiator ticker;
  sc_core::sc_signal<bool> irq_lines[4];
  test::HostProgramRunner runner;
  bool ticking = false;  // while a program runs
  sc_core::sc_event starts;

  Bench(sc_core::sc_module_name name, bool run_ahead)
      : sc_core::sc_module(name),
        host("host", host_params(run_ahead)),
        bus("bus", test::bench_bus_params(BUS_CYCLE)),
        memory("memory", test::bench_memory_params(MEM_SIZE, BUS_CYCLE, 3)),
        port("port", test::bench_memory_params(PORT_SIZE, BUS_CYCLE, 40, 4)),
        counter("counter", port),
        other("other"),
        ticker("ticker") {
    bus.attach(host.out, "host", 0);
    bus.attach(other.out, "other", 1);
    bus.attach(ticker.out, "ticker", 2);
    bus.map(memory.in, 0, MEM_SIZE, "memory");
    bus.map(counter.in, PORT, PORT_SIZE, "port");
    for (unsigned i = 0; i < 4; ++i) host.irq[i].bind(irq_lines[i]);
    host.set_program(runner.program());
    SC_THREAD(tick);
  }

  // A master in a process of its own: a read of memory every 800 ns of the
  // kernel's time, or every 25 us where the host may run ahead (so that
  // now and then nothing is scheduled within its 5 us window).
  void tick() {
    const sc_time period =
        host.params().run_ahead == sc_core::SC_ZERO_TIME ? sc_time(800, SC_NS) : sc_time(25, sc_core::SC_US);
    for (;;) {
      if (!ticking) sc_core::wait(starts);
      const uint64_t now = sc_core::sc_time_stamp().value();
      sc_core::wait(sc_time::from_value(period.value() - now % period.value()));
      uint8_t data[16];
      if (ticking) ticker.read(0x30000, data, sizeof data);
    }
  }
};

// What a program saw and what the bench holds after it.
struct Outcome {
  std::vector<uint64_t> seen;                       // busy cycles and local time after each step, values read
  std::string host, bus, memory_stats, port_stats;  // their statistics, as JSON text
  std::vector<uint8_t> memory, port;
};

Outcome run_program(Bench& bench, bool unit, unsigned seed) {
  Outcome outcome;
  bench.runner.run([&](HostApi& api) {
    std::mt19937 random(seed);
    const auto pick = [&](uint32_t n) { return static_cast<uint32_t>(random() % n); };
    const uint64_t start = api.now_cycles();
    bench.ticking = true;
    bench.starts.notify();
    const auto note = [&] {
      outcome.seen.push_back(static_cast<HostCore&>(bench.host).busy_cycles());
      outcome.seen.push_back(api.now_cycles() - start);
    };
    for (unsigned step = 0; step < 300; ++step) {
      if (const uint32_t compute = pick(3) == 0 ? pick(300) : pick(4)) api.compute_cycles(compute);
      const unsigned what = pick(100);
      if (what < 10) {
        // Another initiator's burst, requested up to 3 us ahead of the host.
        uint8_t data[64];
        const sc_time ahead = sc_time::from_value(api.now_cycles() * HOST_CYCLE.value()) - sc_core::sc_time_stamp() +
                              sc_time(pick(3000), SC_NS);
        bench.other.read(0x20000 + 64 * pick(64), data, 8 * (1 + pick(8)), ahead);
      } else if (what < 30) {
        // Lines into the cache, some of them dirty: the copy's fills find
        // them, or evict them.
        const uint32_t line = 0x10000 + 32 * pick(1024);
        outcome.seen.push_back(api.read32(line));
        if (pick(2) == 0) api.write32(line + 4 * pick(8), static_cast<uint32_t>(random()));
      } else if (what < 38) {
        outcome.seen.push_back(api.read32(PORT + 4 * pick(PORT_SIZE / 4)));
      } else {
        // A copy: mostly whole aligned blocks, now and then a part of a
        // block at the end, or a source off a line's start.
        const uint32_t words = pick(4) == 0 ? 1 + pick(300) : 8 * (1 + pick(40));
        const uint32_t from = 0x10000 + (pick(8) == 0 ? 4 * pick(8) : 0) + 32 * pick(1024 - 48);
        const uint32_t to = PORT + 4 * pick(PORT_SIZE / 4 - words);
        std::vector<uint64_t> cycles((words + 7) / 8);
        for (auto& c : cycles) c = pick(5) == 0 ? 0 : 40 + pick(20);
        if (unit)
          api.copy_words(to, from, words, cycles.data());
        else
          api.HostApi::copy_words(to, from, words, cycles.data());
      }
      note();
    }
    static_cast<HostCore&>(bench.host).drain_write_buffer();
    note();
    bench.ticking = false;
  });
  nlohmann::json host = bench.host.stats_json(sc_core::sc_time_stamp());
  host.erase("idle_ns");  // the benches ran one after another
  host.erase("utilisation");
  outcome.host = host.dump();
  // Everything but the utilisations (over the run's elapsed time).
  nlohmann::json bus = bench.bus.stats_json(sc_core::sc_time_stamp());
  bus.erase("utilisation");
  bus.erase("elapsed_ns");
  for (auto& initiator : bus["initiators"]) initiator.erase("utilisation");
  outcome.bus = bus.dump();
  for (Memory* m : {&bench.memory, &bench.port}) {
    nlohmann::json stats = m->stats_json(sc_core::sc_time_stamp());
    stats.erase("utilisation");
    stats.erase("elapsed_ns");
    (m == &bench.memory ? outcome.memory_stats : outcome.port_stats) = stats.dump();
  }
  outcome.memory.assign(bench.memory.data(), bench.memory.data() + MEM_SIZE);
  outcome.port.assign(bench.port.data(), bench.port.data() + PORT_SIZE);
  return outcome;
}

void expect_same(const Outcome& calls, const Outcome& unit) {
  EXPECT_EQ(calls.seen, unit.seen);
  EXPECT_EQ(calls.host, unit.host);
  EXPECT_EQ(calls.bus, unit.bus);
  EXPECT_EQ(calls.memory_stats, unit.memory_stats);
  EXPECT_EQ(calls.port_stats, unit.port_stats);
  EXPECT_TRUE(calls.memory == unit.memory) << "memory differs";
  EXPECT_TRUE(calls.port == unit.port) << "the port's bytes differ";
}

Bench* g_calls = nullptr;
Bench* g_unit = nullptr;
Bench* g_calls_ahead = nullptr;
Bench* g_unit_ahead = nullptr;

}  // namespace

TEST(FrameCopy, GivesWhatTheCallsGive) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Outcome calls = run_program(*g_calls, false, seed);
    const Outcome unit = run_program(*g_unit, true, seed);
    expect_same(calls, unit);
  }
  // Without run-ahead, every block's stall for its fill (behind the slow
  // port's burst) reaches the quantum's end, where the host lets the
  // kernel run: each block goes by the calls, and the closed form that
  // steps up to that point and stops must leave everything as they do.
  EXPECT_EQ(g_calls->counter.runs, 0u);
}

TEST(FrameCopy, GivesWhatTheCallsGiveWhileTheHostRunsAhead) {
  for (unsigned seed : {4u, 5u, 6u, 7u, 8u, 9u}) {
    const Outcome calls = run_program(*g_calls_ahead, false, seed);
    const Outcome unit = run_program(*g_unit_ahead, true, seed);
    expect_same(calls, unit);
  }
  EXPECT_EQ(g_calls_ahead->counter.runs, 0u);
  EXPECT_GT(g_unit_ahead->counter.runs, 100u) << "blocks went out as units";
  EXPECT_LT(g_unit_ahead->counter.blocks,
            g_unit_ahead->port.stats_json(sc_core::sc_time_stamp())["writes"].get<uint64_t>())
      << "and some one by one (dirty victims, lines in the cache, the bus reserved ahead, parts of blocks)";
  EXPECT_GT(g_unit_ahead->host.stats_json(sc_core::sc_time_stamp())["run_aheads"].get<uint64_t>(), 0u);
}

int sc_main(int argc, char* argv[]) {
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_time(200, SC_NS));
  g_calls = new Bench("calls", false);
  g_unit = new Bench("unit", false);
  g_calls_ahead = new Bench("calls_ahead", true);
  g_unit_ahead = new Bench("unit_ahead", true);
  return test::run_all_tests(argc, argv);
}
