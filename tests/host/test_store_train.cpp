// TLM tests of the host's units (tlm/host/README.md): store trains ("Store
// trains": HostApi::write32_train simulated as a unit, with its words' bus
// requests handed to the bus and the CIU together) and the frame copy
// ("The frame copy": HostApi::copy_words with its blocks in closed form,
// their requests handed to the bus, the memory and a device together) must
// give what the same calls give (HostApi's own versions: the loop of
// compute_cycles and write32; load_span, write_words and compute_cycles per
// block): every time the host reads, every host, bus, CIU and memory
// figure, every CMEM and memory byte. Two benches of each kind run the same
// random programs, one by calls and one by units: with run-ahead off and
// on, with a 200 ns quantum that ends inside most trains, another
// initiator's bursts reserving the bus ahead of the host, a third in a
// process of its own that runs whenever the host lets the kernel run,
// trains into cacheable memory, reads between them, a program on the array
// that the first words wait for; copies of whole blocks, parts of a block
// and sources off a line's start, with dirty lines for their fills to evict
// and lines already in the cache; and copies from a memory whose reads
// schedule something in the kernel.
//
// Bench: host (200 MHz) -> bus (100 MHz) -> memory at 0 (cacheable), the
// AC's registers at 0x800000, its program memory at 0x810000, the CIU's
// window at 0x1000000 and a second, slower memory at 0x4000000 standing
// for the display port (the memories and the CIU each through a forwarder
// that counts what is handed over as units, and can make the reads touch
// the kernel's schedule); a second and a third initiator on the bus.
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
constexpr uint32_t PORT = 0x4000000, PORT_SIZE = 1u << 16;

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

// Between the bus and a target (the CIU, the port's memory): passes
// everything on and counts the trains and words, and the runs of accesses,
// handed over as units.
struct UnitCounter : sc_core::sc_module, tlm::tlm_fw_transport_if<>, DirectTransport {
  tlm::tlm_target_socket<32> in;
  tlm_utils::simple_initiator_socket<UnitCounter, 32> out;
  tlm::tlm_fw_transport_if<>* target = nullptr;
  DirectTransport* direct = nullptr;
  uint64_t trains = 0, words = 0, runs = 0, accesses = 0;
  // While set, every read schedules an event a nanosecond on, grants no
  // DMI and says so (a target whose reads touch the kernel's schedule).
  bool touch_reads = false;
  sc_core::sc_event touched;

  template <typename Target>
  UnitCounter(sc_core::sc_module_name name, Target& t) : sc_core::sc_module(name), in("in"), out("out") {
    in.bind(static_cast<tlm::tlm_fw_transport_if<>&>(*this));
    out.bind(t.in);
  }
  void end_of_elaboration() override {
    target = out.operator->();
    direct = direct_transport_of(target);
  }
  bool touch(tlm::tlm_command command) {
    if (!touch_reads || command != tlm::TLM_READ_COMMAND) return false;
    touched.notify(sc_time(1, SC_NS));
    return true;
  }
  void b_transport(tlm::tlm_generic_payload& gp, sc_time& delay) override {
    target->b_transport(gp, delay);
    if (touch(gp.get_command())) gp.set_dmi_allowed(false);
  }
  void direct_b_transport(tlm::tlm_generic_payload& gp, sc_time& delay, DirectExtras& extras) override {
    direct->direct_b_transport(gp, delay, extras);
    if (touch(gp.get_command())) {
      gp.set_dmi_allowed(false);
      extras.untouched = false;
    }
  }
  bool quote_train(const WordTrain& train, uint64_t first_ticks, TrainQuote& quote) override {
    return direct->quote_train(train, first_ticks, quote);
  }
  void direct_train(const WordTrain& train, const uint64_t* arrivals) override {
    ++trains;
    words += train.count;
    direct->direct_train(train, arrivals);
  }
  bool quote_accesses(tlm::tlm_command command, uint64_t address, unsigned bytes, size_t count, unsigned transfers,
                      uint64_t& latency_ticks, bool& untouched) override {
    if (!direct->quote_accesses(command, address, bytes, count, transfers, latency_ticks, untouched)) return false;
    if (touch_reads && command == tlm::TLM_READ_COMMAND) untouched = false;
    return true;
  }
  void direct_accesses(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned bytes,
                       size_t count) override {
    ++runs;
    accesses += count;
    direct->direct_accesses(command, address, data, bytes, count);
    touch(command);
  }
  unsigned transport_dbg(tlm::tlm_generic_payload& gp) override { return target->transport_dbg(gp); }
  bool get_direct_mem_ptr(tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi) override {
    return target->get_direct_mem_ptr(gp, dmi);
  }
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& phase, sc_time& delay) override {
    return target->nb_transport_fw(gp, phase, delay);
  }
};

struct Bench : sc_core::sc_module {
  SC_HAS_PROCESS(Bench);
  Host host;
  AhbBus bus;
  Memory memory;
  UnitCounter memory_counter;
  ArrayProcessor array;
  Ciu ciu;
  UnitCounter counter;
  Memory port;
  UnitCounter port_counter;
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
        memory_counter("memory_counter", memory),
        array("array", test::bench_array_params(ARRAY_CYCLE)),
        ciu("ciu", ciu_params(), array),
        counter("counter", ciu),
        port("port", test::bench_memory_params(PORT_SIZE, BUS_CYCLE, 40, 4)),
        port_counter("port_counter", port),
        other("other"),
        ticker("ticker") {
    bus.attach(host.out, "host", 0);
    bus.attach(other.out, "other", 1);
    bus.attach(ticker.out, "ticker", 2);
    bus.map(memory_counter.in, 0, MEM_SIZE, "memory");
    bus.map(array.in, AC, 0x1000, "array_regs");
    bus.map(array.program_in, PROGRAM, 0x10000, "array_program");
    bus.map(counter.in, CMEM, ciu.window_bytes(), "array_cmem");
    bus.map(port_counter.in, PORT, PORT_SIZE, "port");
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
  std::vector<uint64_t> seen;            // busy cycles and local time after each step, values read
  std::string host, ciu, bus, memories;  // their statistics, as JSON text
  std::vector<uint8_t> cmem;
  std::vector<uint8_t> memory, port;
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

// What the bench holds after a program: every block's statistics but the
// utilisations (over the run's elapsed time) and the idle time (the benches
// ran one after another), CMEM, both memories.
void collect(Bench& bench, Outcome& outcome) {
  const sc_time now = sc_core::sc_time_stamp();
  nlohmann::json host = bench.host.stats_json(now);
  host.erase("idle_ns");
  host.erase("utilisation");
  outcome.host = host.dump();
  nlohmann::json ciu = bench.ciu.stats_json(now);
  ciu.erase("elapsed_ns");
  outcome.ciu = ciu.dump();
  nlohmann::json bus = bench.bus.stats_json(now);
  bus.erase("utilisation");
  bus.erase("elapsed_ns");
  for (auto& initiator : bus["initiators"]) initiator.erase("utilisation");
  outcome.bus = bus.dump();
  for (Memory* m : {&bench.memory, &bench.port}) {
    nlohmann::json stats = m->stats_json(now);
    stats.erase("utilisation");
    stats.erase("elapsed_ns");
    outcome.memories += stats.dump();
  }
  const ap::CuArray& cus = bench.array.core().array();
  for (unsigned a = 0; a < bench.cmem_bytes(); ++a)
    for (unsigned lane = 0; lane < cus.lanes(); ++lane) outcome.cmem.push_back(cus.cmem(lane, a));
  outcome.memory.assign(bench.memory.data(), bench.memory.data() + MEM_SIZE);
  outcome.port.assign(bench.port.data(), bench.port.data() + PORT_SIZE);
}

// A random program on a bench: after `prologue`, `steps` steps, each some
// compute cycles and then, by a number below 100, another initiator's
// burst (below `bursts`: requested up to 3 us ahead of the host, so that
// the bus is reserved where the host's requests will want it) or the
// program's own `step`; after each the host's busy cycles and local time
// noted, and at the end the write buffer drained.
template <typename Prologue, typename Step>
Outcome run_steps(Bench& bench, unsigned seed, unsigned steps, unsigned bursts, Prologue&& prologue, Step&& step) {
  Outcome outcome;
  bench.runner.run([&](HostApi& api) {
    std::mt19937 random(seed);
    const auto pick = [&](uint32_t n) { return static_cast<uint32_t>(random() % n); };
    const uint64_t start = api.now_cycles();
    bench.ticking = true;
    bench.starts.notify();
    prologue(api);
    const auto note = [&] {
      outcome.seen.push_back(static_cast<HostCore&>(bench.host).busy_cycles());
      outcome.seen.push_back(api.now_cycles() - start);
    };
    for (unsigned k = 0; k < steps; ++k) {
      if (const uint32_t compute = pick(3) == 0 ? pick(300) : pick(4)) api.compute_cycles(compute);
      const unsigned what = pick(100);
      if (what < bursts) {
        uint8_t data[64];
        const sc_time ahead = sc_time::from_value(api.now_cycles() * HOST_CYCLE.value()) - sc_core::sc_time_stamp() +
                              sc_time(pick(3000), SC_NS);
        bench.other.read(0x20000 + 64 * pick(64), data, 8 * (1 + pick(8)), ahead);
      } else {
        step(api, what, pick, random, outcome.seen);
      }
      note();
    }
    static_cast<HostCore&>(bench.host).drain_write_buffer();
    note();
    bench.ticking = false;
  });
  collect(bench, outcome);
  return outcome;
}

// A program of store trains (HostApi::write32_train, by calls or as units)
// into CMEM and memory, with the array started and CMEM read between them.
Outcome run_program(Bench& bench, bool trains, unsigned seed) {
  const uint32_t stride = regs::cmem_offset(1, 0, bench.cmem_bytes());
  return run_steps(bench, seed, 400, 12, load_array_program,
                   [&](HostApi& api, unsigned what, auto& pick, std::mt19937& random, std::vector<uint64_t>& seen) {
                     if (what < 18) {
                       // The array runs (when it is idle): the CIU's words wait for its end.
                       if ((api.read32(AC + regs::STATUS) & regs::STATUS_BUSY) == 0) {
                         api.write32(AC + regs::ENTRY, 0);
                         api.write32(AC + regs::START, 1);
                       }
                     } else if (what < 26) {
                       seen.push_back(api.read32(CMEM + 4 * pick(bench.groups() * bench.cmem_bytes())));
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
                   });
}

// A program of copies (HostApi::copy_words, by calls or as a unit) to the
// port: mostly whole aligned blocks, now and then a part of a block at the
// end or a source off a line's start, with lines read into the cache and
// some made dirty (the fills find them, or evict them) and port reads
// between them.
Outcome run_copy_program(Bench& bench, bool unit, unsigned seed) {
  return run_steps(
      bench, seed, 300, 10, [](HostApi&) {},
      [&](HostApi& api, unsigned what, auto& pick, std::mt19937& random, std::vector<uint64_t>& seen) {
        if (what < 30) {
          const uint32_t line = 0x10000 + 32 * pick(1024);
          seen.push_back(api.read32(line));
          if (pick(2) == 0) api.write32(line + 4 * pick(8), static_cast<uint32_t>(random()));
        } else if (what < 38) {
          seen.push_back(api.read32(PORT + 4 * pick(PORT_SIZE / 4)));
        } else {
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
      });
}

// A program of store spans (HostApi::store_span) into memory: runs of
// elements of 1, 2 or 4 bytes, short and long, that miss the cache and
// leave as posted trains (by post_request, or as a unit), with lines read
// into the cache (the spans' stores then hit them), some made dirty, and
// load spans whose fills evict them.
Outcome run_posts_program(Bench& bench, unsigned seed) {
  return run_steps(
      bench, seed, 300, 10, [](HostApi&) {},
      [&](HostApi& api, unsigned what, auto& pick, std::mt19937& random, std::vector<uint64_t>& seen) {
        if (what < 25) {
          const uint32_t line = 0x10000 + 32 * pick(1024);
          seen.push_back(api.read32(line));
          if (pick(2) == 0) api.write32(line + 4 * pick(8), static_cast<uint32_t>(random()));
        } else if (what < 35) {
          const uint32_t count = 1 + pick(64);
          const uint8_t* data = api.load_span(0x10000 + 4 * pick(8192 - count), 4, count);
          seen.push_back(data[pick(4 * count)]);
        } else {
          const unsigned size = 1u << pick(3);
          const uint32_t count = pick(3) == 0 ? 1 + pick(8) : 1 + pick(pick(4) == 0 ? 600 : 120);
          const uint32_t address = 0x10000 + size * pick((0x8000 - count * size) / size);
          uint8_t* data = api.store_span(address, size, count);
          for (uint32_t k = 0; k < size * count; ++k) data[k] = static_cast<uint8_t>(random());
        }
      });
}

void expect_same(const Outcome& calls, const Outcome& trains) {
  EXPECT_EQ(calls.seen, trains.seen);
  EXPECT_EQ(calls.host, trains.host);
  EXPECT_EQ(calls.ciu, trains.ciu);
  EXPECT_EQ(calls.bus, trains.bus);
  EXPECT_EQ(calls.memories, trains.memories);
  EXPECT_TRUE(calls.cmem == trains.cmem) << "CMEM differs";
  EXPECT_TRUE(calls.memory == trains.memory) << "memory differs";
  EXPECT_TRUE(calls.port == trains.port) << "the port's bytes differ";
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

TEST(FrameCopy, GivesWhatTheCallsGive) {
  for (unsigned seed : {21u, 22u, 23u}) {
    const Outcome calls = run_copy_program(*g_calls, false, seed);
    const Outcome unit = run_copy_program(*g_trains, true, seed);
    expect_same(calls, unit);
  }
  // Without run-ahead, every block's stall for its fill (behind the slow
  // port's burst) reaches the quantum's end, where the host lets the
  // kernel run: each block goes by the calls, and the closed form that
  // steps up to that point and stops must leave everything as they do.
  EXPECT_EQ(g_calls->port_counter.runs, 0u);
}

TEST(FrameCopy, GivesWhatTheCallsGiveWhileTheHostRunsAhead) {
  for (unsigned seed : {24u, 25u, 26u, 27u, 28u, 29u}) {
    const Outcome calls = run_copy_program(*g_calls_ahead, false, seed);
    const Outcome unit = run_copy_program(*g_trains_ahead, true, seed);
    expect_same(calls, unit);
  }
  EXPECT_EQ(g_calls_ahead->port_counter.runs, 0u);
  EXPECT_GT(g_trains_ahead->port_counter.runs, 100u) << "blocks went out as units";
  EXPECT_LT(g_trains_ahead->port_counter.accesses,
            g_trains_ahead->port.stats_json(sc_core::sc_time_stamp())["writes"].get<uint64_t>())
      << "and some one by one (dirty victims, lines in the cache, the bus reserved ahead, parts of blocks)";
}

TEST(FrameCopy, GivesWhatTheCallsGiveFromASourceWhoseReadsScheduleSomething) {
  // Every read of memory schedules an event and grants no DMI: after each
  // fill the host must ask the kernel again (which finds the event), and
  // so stops running ahead where the calls stop. The closed form steps
  // each block up to its fill's stall and gives it back to the calls;
  // a closed form that took the fill as leaving the schedule untouched
  // ran on, and fails this.
  for (Bench* bench : {g_calls_ahead, g_trains_ahead}) bench->memory_counter.touch_reads = true;
  const uint64_t runs = g_trains_ahead->port_counter.runs;
  for (unsigned seed : {30u, 31u, 32u}) {
    const Outcome calls = run_copy_program(*g_calls_ahead, false, seed);
    const Outcome unit = run_copy_program(*g_trains_ahead, true, seed);
    expect_same(calls, unit);
  }
  for (Bench* bench : {g_calls_ahead, g_trains_ahead}) bench->memory_counter.touch_reads = false;
  EXPECT_EQ(g_trains_ahead->port_counter.runs, runs) << "no block went as a unit";
}

TEST(PostedTrain, GivesWhatTheCallsGive) {
  const uint64_t runs = g_calls->memory_counter.runs;
  for (unsigned seed : {41u, 42u, 43u}) {
    const Outcome calls = run_posts_program(*g_calls, seed);
    const Outcome unit = run_posts_program(*g_trains, seed);
    expect_same(calls, unit);
  }
  EXPECT_EQ(g_calls->memory_counter.runs, runs);
}

TEST(PostedTrain, GivesWhatTheCallsGiveWhileTheHostRunsAhead) {
  const uint64_t runs = g_trains_ahead->memory_counter.runs;
  const uint64_t accesses = g_trains_ahead->memory_counter.accesses;
  const uint64_t writes = g_trains_ahead->memory.stats_json(sc_core::sc_time_stamp())["writes"].get<uint64_t>();
  for (unsigned seed : {44u, 45u, 46u, 47u, 48u, 49u}) {
    const Outcome calls = run_posts_program(*g_calls_ahead, seed);
    const Outcome unit = run_posts_program(*g_trains_ahead, seed);
    expect_same(calls, unit);
  }
  EXPECT_GT(g_trains_ahead->memory_counter.runs, runs + 100) << "posted trains went out as units";
  EXPECT_LT(g_trains_ahead->memory_counter.accesses - accesses,
            g_trains_ahead->memory.stats_json(sc_core::sc_time_stamp())["writes"].get<uint64_t>() - writes)
      << "and some stores one request at a time (single stores, victims, the first requests after a sync)";
}

int sc_main(int argc, char* argv[]) {
  // A quantum shorter than most trains: they are cut at its ends.
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_time(200, SC_NS));
  g_calls = new Bench("calls", false);
  g_trains = new Bench("trains", false);
  g_calls_ahead = new Bench("calls_ahead", true);
  g_trains_ahead = new Bench("trains_ahead", true);
  // The calls' benches take nothing as a unit (Host::take_units): not the
  // posted trains either, which the units' take wherever they can.
  g_calls->host.take_units(false);
  g_calls_ahead->host.take_units(false);
  return test::run_all_tests(argc, argv);
}
