// TLM tests of the host's store trains (tlm/host/README.md, "Store
// trains"): HostApi::write32_train simulated as a unit, with its words'
// bus requests handed to the bus and the CIU together, must give what the
// same calls one by one give (HostApi's own write32_train, the loop of
// compute_cycles and write32): every time the host reads, every host, bus
// and CIU figure, every CMEM byte. Two benches of each kind run the same
// random programs, one by calls and one by trains: with run-ahead off and
// on, with a 200 ns quantum that ends inside most trains, another
// initiator's bursts reserving the bus ahead of the host, a third in a
// process of its own that runs whenever the host lets the kernel run,
// trains into cacheable memory, reads between them, and a program on the
// array that the first words wait for.
//
// Bench: host (200 MHz) -> bus (100 MHz) -> memory at 0 (cacheable), the
// AC's registers at 0x800000, its program memory at 0x810000, the CIU's
// window at 0x1000000 (through a forwarder that counts the trains handed
// over); a second and a third initiator on the bus.
#include <cstring>
#include <random>

#include <tlm_utils/simple_initiator_socket.h>
#include "array/array_processor.h"
#include "array/array_regs.h"
#include "array/ciu.h"
#include "array/isa/ap_isa.h"

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
namespace regs = array_regs;

namespace {

const sc_time HOST_CYCLE(5, SC_NS);
const sc_time BUS_CYCLE(10, SC_NS);
const sc_time ARRAY_CYCLE(10, SC_NS);
constexpr uint32_t MEM_SIZE = 1u << 20;
constexpr uint32_t AC = 0x800000, PROGRAM = 0x810000, CMEM = 0x1000000;

HostParams host_params(bool run_ahead) {
  HostParams p = test::bench_host_params(HOST_CYCLE, MEM_SIZE);
  if (run_ahead) p.run_ahead = sc_time(5, sc_core::SC_US);
  return p;
}

CiuParams ciu_params() {
  CiuParams p = CiuParams::defaults();
  p.write_cycles = 7;
  p.read_cycles = 11;
  p.clock_period = ARRAY_CYCLE;
  return p;
}

// Between the bus and the CIU: passes everything on and counts the trains
// and words handed over as units.
struct TrainCounter : sc_core::sc_module, tlm::tlm_fw_transport_if<>, DirectTransport {
  tlm::tlm_target_socket<32> in;
  tlm_utils::simple_initiator_socket<TrainCounter, 32> out;
  tlm::tlm_fw_transport_if<>* ciu = nullptr;
  DirectTransport* direct = nullptr;
  uint64_t trains = 0, words = 0;

  TrainCounter(sc_core::sc_module_name name, Ciu& target) : sc_core::sc_module(name), in("in"), out("out") {
    in.bind(static_cast<tlm::tlm_fw_transport_if<>&>(*this));
    out.bind(target.in);
  }
  void end_of_elaboration() override {
    ciu = out.operator->();
    direct = direct_transport_of(ciu);
  }
  void b_transport(tlm::tlm_generic_payload& gp, sc_time& delay) override { ciu->b_transport(gp, delay); }
  void direct_b_transport(tlm::tlm_generic_payload& gp, sc_time& delay, DirectExtras& extras) override {
    direct->direct_b_transport(gp, delay, extras);
  }
  bool quote_train(const WordTrain& train, uint64_t first_ticks, TrainQuote& quote) override {
    return direct->quote_train(train, first_ticks, quote);
  }
  void direct_train(const WordTrain& train, const uint64_t* arrivals) override {
    ++trains;
    words += train.count;
    direct->direct_train(train, arrivals);
  }
  unsigned transport_dbg(tlm::tlm_generic_payload& gp) override { return ciu->transport_dbg(gp); }
  bool get_direct_mem_ptr(tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi) override {
    return ciu->get_direct_mem_ptr(gp, dmi);
  }
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& phase, sc_time& delay) override {
    return ciu->nb_transport_fw(gp, phase, delay);
  }
};

struct Bench : sc_core::sc_module {
  SC_HAS_PROCESS(Bench);
  Host host;
  AhbBus bus;
  Memory memory;
  ArrayProcessor array;
  Ciu ciu;
  TrainCounter counter;
  test::TestInitiator other;
  test::TestInitiator ticker;
  sc_core::sc_signal<bool> irq_lines[4], array_irq;
  test::HostProgramRunner runner;
  bool ticking = false;  // while a program runs
  sc_core::sc_event starts;

  Bench(sc_core::sc_module_name name, bool run_ahead)
      : sc_core::sc_module(name),
        host("host", host_params(run_ahead)),
        bus("bus", test::bench_bus_params(BUS_CYCLE)),
        memory("memory", test::bench_memory_params(MEM_SIZE, BUS_CYCLE, 3)),
        array("array", test::bench_array_params(ARRAY_CYCLE)),
        ciu("ciu", ciu_params(), array),
        counter("counter", ciu),
        other("other"),
        ticker("ticker") {
    bus.attach(host.out, "host", 0);
    bus.attach(other.out, "other", 1);
    bus.attach(ticker.out, "ticker", 2);
    bus.map(memory.in, 0, MEM_SIZE, "memory");
    bus.map(array.in, AC, 0x1000, "array_regs");
    bus.map(array.program_in, PROGRAM, 0x10000, "array_program");
    bus.map(counter.in, CMEM, ciu.window_bytes(), "array_cmem");
    for (unsigned i = 0; i < 4; ++i) host.irq[i].bind(irq_lines[i]);
    array.irq.bind(array_irq);
    host.set_program(runner.program());
    SC_THREAD(tick);
  }

  // A master in a process of its own, as the DMAs and the display are: a
  // read of memory every 800 ns of the kernel's time, or every 25 us where
  // the host may run ahead (so that now and then nothing is scheduled
  // within its 5 us window; the benches start on multiples of both), which
  // runs whenever the host lets the kernel run and finds the bus reserved
  // as far as the host's transactions reach.
  void tick() {
    const sc_time period =
        host.params().run_ahead == sc_core::SC_ZERO_TIME ? sc_time(800, SC_NS) : sc_time(25, sc_core::SC_US);
    for (;;) {
      // Between programs it waits, so that it schedules nothing while
      // another bench runs (whose host looks for a clear window).
      if (!ticking) sc_core::wait(starts);
      const uint64_t now = sc_core::sc_time_stamp().value();
      sc_core::wait(sc_time::from_value(period.value() - now % period.value()));
      uint8_t data[16];
      if (ticking) ticker.read(0x30000, data, sizeof data);
    }
  }

  uint32_t cmem_bytes() const { return array.params().geometry.cmem_bytes; }
  unsigned groups() const { return array.params().geometry.lanes() / regs::CUS_PER_GROUP; }
};

// What a program saw and what the bench holds after it.
struct Outcome {
  std::vector<uint64_t> seen;  // busy cycles and local time after each step, values read
  std::string host, ciu, bus;  // their statistics, as JSON text
  std::vector<uint8_t> cmem;
  std::vector<uint8_t> memory;
};

// A program for the array: 30 nops and a halt, CMEM the CUs' while it runs.
void load_array_program(HostApi& api) {
  for (unsigned w = 0; w <= 30; ++w) {
    ap::Instruction in;
    in.opcode = w < 30 ? ap::Opcode::op_nop : ap::Opcode::op_halt;
    const uint64_t word = ap::encode(in);
    api.write32(PROGRAM + regs::PROGRAM_WORD_BYTES * w, static_cast<uint32_t>(word));
    api.write32(PROGRAM + regs::PROGRAM_WORD_BYTES * w + 4, static_cast<uint32_t>(word >> 32));
  }
}

Outcome run_program(Bench& bench, bool trains, unsigned seed) {
  Outcome outcome;
  const uint32_t stride = regs::cmem_offset(1, 0, bench.cmem_bytes());
  bench.runner.run([&](HostApi& api) {
    std::mt19937 random(seed);
    const auto pick = [&](uint32_t n) { return static_cast<uint32_t>(random() % n); };
    const uint64_t start = api.now_cycles();
    bench.ticking = true;
    bench.starts.notify();
    load_array_program(api);
    const auto note = [&] {
      outcome.seen.push_back(static_cast<HostCore&>(bench.host).busy_cycles());
      outcome.seen.push_back(api.now_cycles() - start);
    };
    for (unsigned step = 0; step < 400; ++step) {
      if (const uint32_t compute = pick(3) == 0 ? pick(300) : pick(4)) api.compute_cycles(compute);
      const unsigned what = pick(100);
      if (what < 12) {
        // Another initiator's burst, requested up to 3 us ahead of the
        // host: the bus is reserved where the host's words will want it.
        uint8_t data[64];
        const sc_time ahead = sc_time::from_value(api.now_cycles() * HOST_CYCLE.value()) - sc_core::sc_time_stamp() +
                              sc_time(pick(3000), SC_NS);
        bench.other.read(0x20000 + 64 * pick(64), data, 8 * (1 + pick(8)), ahead);
      } else if (what < 18) {
        // The array runs (when it is idle): the CIU's words wait for its end.
        if ((api.read32(AC + regs::STATUS) & regs::STATUS_BUSY) == 0) {
          api.write32(AC + regs::ENTRY, 0);
          api.write32(AC + regs::START, 1);
        }
      } else if (what < 26) {
        outcome.seen.push_back(api.read32(CMEM + 4 * pick(bench.groups() * bench.cmem_bytes())));
      } else {
        // A train: into CMEM (group by group, or along a group's
        // addresses), or now and then into cacheable memory.
        const bool memory = what < 32;
        const unsigned count = 1 + pick(memory ? 16 : bench.groups());
        const uint32_t step_bytes = memory ? 4 * (1 + pick(3)) : pick(2) == 0 ? stride : 4;
        const uint32_t first = memory ? 0x10000 + 4 * pick(2048)
                                      : CMEM + 4 * pick(bench.cmem_bytes() - count) +
                                            (step_bytes == 4 ? stride * pick(bench.groups()) : 0);
        std::vector<uint32_t> values(count);
        std::vector<uint64_t> cycles(count);
        for (unsigned k = 0; k < count; ++k) {
          values[k] = static_cast<uint32_t>(random());
          cycles[k] = pick(4) == 0 ? 0 : pick(12);
        }
        if (trains)
          api.write32_train(first, step_bytes, values.data(), cycles.data(), count);
        else
          api.HostApi::write32_train(first, step_bytes, values.data(), cycles.data(), count);
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
  nlohmann::json ciu = bench.ciu.stats_json(sc_core::sc_time_stamp());
  ciu.erase("elapsed_ns");
  outcome.ciu = ciu.dump();
  // Everything but the utilisations (over the run's elapsed time).
  nlohmann::json bus = bench.bus.stats_json(sc_core::sc_time_stamp());
  bus.erase("utilisation");
  bus.erase("elapsed_ns");
  for (auto& initiator : bus["initiators"]) initiator.erase("utilisation");
  outcome.bus = bus.dump();
  const ap::CuArray& cus = bench.array.core().array();
  for (unsigned a = 0; a < bench.cmem_bytes(); ++a)
    for (unsigned lane = 0; lane < cus.lanes(); ++lane) outcome.cmem.push_back(cus.cmem(lane, a));
  outcome.memory.assign(bench.memory.data(), bench.memory.data() + MEM_SIZE);
  return outcome;
}

void expect_same(const Outcome& calls, const Outcome& trains) {
  EXPECT_EQ(calls.seen, trains.seen);
  EXPECT_EQ(calls.host, trains.host);
  EXPECT_EQ(calls.ciu, trains.ciu);
  EXPECT_EQ(calls.bus, trains.bus);
  EXPECT_TRUE(calls.cmem == trains.cmem) << "CMEM differs";
  EXPECT_TRUE(calls.memory == trains.memory) << "memory differs";
}

Bench* g_calls = nullptr;
Bench* g_trains = nullptr;
Bench* g_calls_ahead = nullptr;
Bench* g_trains_ahead = nullptr;

}  // namespace

TEST(StoreTrain, GivesWhatTheCallsOneByOneGive) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Outcome calls = run_program(*g_calls, false, seed);
    const Outcome trains = run_program(*g_trains, true, seed);
    expect_same(calls, trains);
  }
  EXPECT_EQ(g_calls->counter.trains, 0u);
  EXPECT_GT(g_trains->counter.trains, 100u) << "the trains went out as units";
  EXPECT_LT(g_trains->counter.words, g_trains->ciu.stats_json(sc_core::sc_time_stamp())["writes"].get<uint64_t>())
      << "and some words one by one (the array running, the bus reserved ahead)";
}

TEST(StoreTrain, GivesWhatTheCallsGiveWhileTheHostRunsAhead) {
  // Ten programs: among them, words whose stall ends exactly at the
  // run-ahead window's end, where the host's closed-form run must stop.
  for (unsigned seed : {4u, 5u, 6u, 7u, 8u, 9u, 10u, 11u, 12u, 13u}) {
    const Outcome calls = run_program(*g_calls_ahead, false, seed);
    const Outcome trains = run_program(*g_trains_ahead, true, seed);
    expect_same(calls, trains);
  }
  EXPECT_GT(g_trains_ahead->counter.trains, 100u);
  EXPECT_GT(g_trains_ahead->host.stats_json(sc_core::sc_time_stamp())["run_aheads"].get<uint64_t>(), 0u);
}

int sc_main(int argc, char* argv[]) {
  // A quantum shorter than most trains: they are cut at its ends.
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_time(200, SC_NS));
  g_calls = new Bench("calls", false);
  g_trains = new Bench("trains", false);
  g_calls_ahead = new Bench("calls_ahead", true);
  g_trains_ahead = new Bench("trains_ahead", true);
  return test::run_all_tests(argc, argv);
}
