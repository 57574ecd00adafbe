// bench_bus: what one loosely-timed transaction through the bus and system
// memory costs in wall time, against the TLM floor: the same initiator loop
// (a tlm_quantumkeeper, b_transport, keeper.set, sync when the quantum is
// used up) bound straight to a target that only copies the data and
// annotates a fixed latency. Three paths, all in one simulation:
//
//   floor        initiator -> FloorTarget
//   bus          initiator -> AhbBus -> FloorTarget
//   bus + memory initiator -> AhbBus -> Memory
//
// Every path annotates the same time per transaction (the floor target's
// latency is the bus's address phase plus the memory's data phase), so the
// keeper synchronises equally often on each. A round times each path on the
// same transactions one after another (the order rotates from round to
// round), so a change in the machine's load hits all of them; the ratios
// are taken within a round. Prints min and median over the rounds; every
// figure is one timed loop divided by its transaction count, never a
// difference of two runs.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <tlm_utils/tlm_quantumkeeper.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <systemc>
#include <tlm>

#include "bench_support.h"
#include "bus/ahb_bus.h"
#include "guarded_main.h"
#include "mem/memory.h"

namespace {

using sc_core::sc_time;

constexpr uint64_t MEMORY_BYTES = 1 << 20;
constexpr uint64_t WINDOW_BYTES = 64 << 10;  // the addresses each loop walks through

struct Options {
  unsigned transactions = 20000;
  unsigned rounds = 101;
  unsigned quantum_ns = 1000;
  bool json = false;  // every round's figures as JSON instead of the table (for bench_speed)
  std::string only;   // one path's loops alone (for a profiler); empty: all three
};

// A target that does what any memory must and nothing more: copy the data,
// annotate a fixed latency.
struct FloorTarget : sc_core::sc_module {
  tlm_utils::simple_target_socket<FloorTarget, 32> in;
  std::vector<uint8_t> data;
  sc_time latency;

  FloorTarget(sc_core::sc_module_name name, sc_time initial_latency)
      : sc_module(name), in("in"), data(MEMORY_BYTES), latency(initial_latency) {
    in.register_b_transport(this, &FloorTarget::b_transport);
  }

  void b_transport(tlm::tlm_generic_payload& gp, sc_time& delay) {
    const uint64_t address = gp.get_address();
    const unsigned length = gp.get_data_length();
    if (address >= data.size() || length > data.size() - address) {
      gp.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
      return;
    }
    if (gp.is_read())
      std::memcpy(gp.get_data_ptr(), data.data() + address, length);
    else
      std::memcpy(data.data() + address, gp.get_data_ptr(), length);
    delay += latency;
    gp.set_response_status(tlm::TLM_OK_RESPONSE);
  }
};

enum Path { floor_path, bus_path, memory_path, path_count };
const char* const PATH_NAMES[path_count] = {"floor", "bus", "bus + memory"};
const char* const PATH_KEYS[path_count] = {"floor", "bus", "memory"};  // --only

struct Kind {
  const char* name;
  tlm::tlm_command command;
  unsigned bytes;
};
const Kind KINDS[] = {
    {"4-byte read", tlm::TLM_READ_COMMAND, 4},
    {"4-byte write", tlm::TLM_WRITE_COMMAND, 4},
    {"64-byte burst read", tlm::TLM_READ_COMMAND, 64},
};
constexpr size_t KIND_COUNT = sizeof KINDS / sizeof KINDS[0];

// ns per transaction, [kind][path][round].
using Timings = std::vector<std::vector<std::vector<double>>>;

struct Driver : sc_core::sc_module {
  SC_HAS_PROCESS(Driver);

  tlm_utils::simple_initiator_socket<Driver, 32> floor_port{"floor_port"};
  tlm_utils::simple_initiator_socket<Driver, 32> bus_port{"bus_port"};
  tlm_utils::simple_initiator_socket<Driver, 32> memory_port{"memory_port"};
  tlm_utils::simple_initiator_socket<Driver, 32>* port[path_count] = {&floor_port, &bus_port, &memory_port};
  // The floor's target and the bus's own, whose latencies follow the
  // transaction's size (set_latencies).
  FloorTarget* floor_target = nullptr;
  FloorTarget* bus_target = nullptr;
  sc_time address_phase, first_access, beat;
  unsigned width_bytes = 4;
  Options options;
  Timings timings;
  std::string error;

  Driver(sc_core::sc_module_name name, const Options& driver_options) : sc_module(name), options(driver_options) {
    SC_THREAD(run);
  }

  // The memory's data phase for `kind`; the floor adds the bus's address
  // phase, so every path annotates the same time per transaction.
  void set_latencies(const Kind& kind) {
    const unsigned beats = (kind.bytes + width_bytes - 1) / width_bytes;
    const sc_time data_phase = first_access + beat * static_cast<double>(beats);
    bus_target->latency = data_phase;
    floor_target->latency = address_phase + data_phase;
  }

  // One timed loop of `options.transactions` transactions: ns each.
  double time_loop(Path path, const Kind& kind) {
    set_latencies(kind);
    uint8_t buffer[64] = {};
    tlm::tlm_generic_payload gp;
    gp.set_command(kind.command);
    gp.set_data_ptr(buffer);
    gp.set_data_length(kind.bytes);
    gp.set_streaming_width(kind.bytes);
    tlm_utils::tlm_quantumkeeper keeper;
    keeper.reset();
    uint64_t address = 0;
    const auto start = std::chrono::steady_clock::now();
    for (unsigned i = 0; i < options.transactions; ++i) {
      gp.set_address(address);
      gp.set_dmi_allowed(false);
      gp.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
      sc_time delay = keeper.get_local_time();
      (*port[path])->b_transport(gp, delay);
      if (gp.is_response_error()) throw std::runtime_error(std::string(PATH_NAMES[path]) + ": transaction failed");
      keeper.set(delay);
      if (keeper.need_sync()) keeper.sync();
      address = (address + kind.bytes) % WINDOW_BYTES;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    keeper.sync();
    return tessera::bench::positive(seconds * 1e9 / options.transactions, PATH_NAMES[path]);
  }

  bool selected(Path path) const { return options.only.empty() || options.only == PATH_KEYS[path]; }

  void run() {
    try {
      timings.assign(KIND_COUNT, std::vector<std::vector<double>>(path_count));
      // A warm-up round, not counted: first touches of the memories and caches.
      for (size_t k = 0; k < KIND_COUNT; ++k)
        for (int p = 0; p < path_count; ++p)
          if (selected(static_cast<Path>(p))) time_loop(static_cast<Path>(p), KINDS[k]);
      for (unsigned r = 0; r < options.rounds; ++r)
        for (size_t k = 0; k < KIND_COUNT; ++k)
          for (unsigned i = 0; i < path_count; ++i) {
            const auto p = static_cast<Path>((i + r) % path_count);
            if (selected(p)) timings[k][p].push_back(time_loop(p, KINDS[k]));
          }
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
};

std::vector<double> ratios(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> r;
  for (size_t i = 0; i < a.size(); ++i) r.push_back(a[i] / b[i]);
  return r;
}

int run(const Options& options) {
  const std::string load_before = tessera::bench::load_average();
  const auto bench_start = std::chrono::steady_clock::now();
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_time(options.quantum_ns, sc_core::SC_NS));

  const tessera::BusParams bus_params = tessera::BusParams::defaults();
  tessera::MemoryParams memory_params = tessera::MemoryParams::defaults();
  memory_params.size_bytes = MEMORY_BYTES;
  memory_params.clock_period = bus_params.clock_period;
  memory_params.width_bytes = bus_params.width_bytes;
  const sc_time period = bus_params.clock_period;

  Driver driver("driver", options);
  FloorTarget floor_target("floor_target", sc_core::SC_ZERO_TIME);
  FloorTarget bus_target("bus_target", sc_core::SC_ZERO_TIME);
  driver.floor_target = &floor_target;
  driver.bus_target = &bus_target;
  driver.address_phase = period * static_cast<double>(bus_params.address_cycles);
  driver.first_access = period * static_cast<double>(memory_params.first_access_cycles);
  driver.beat = period * static_cast<double>(memory_params.beat_cycles);
  driver.width_bytes = memory_params.width_bytes;
  tessera::AhbBus bus("bus", bus_params);
  tessera::AhbBus memory_bus("memory_bus", bus_params);
  tessera::Memory memory("memory", memory_params);
  driver.floor_port.bind(floor_target.in);
  bus.attach(driver.bus_port, "driver", 0);
  bus.map(bus_target.in, 0, MEMORY_BYTES, "target");
  memory_bus.attach(driver.memory_port, "driver", 0);
  memory_bus.map(memory.in, 0, MEMORY_BYTES, "memory");

  sc_core::sc_start();
  if (!driver.error.empty()) throw std::runtime_error(driver.error);
  if (!options.only.empty()) {
    for (size_t k = 0; k < KIND_COUNT; ++k)
      for (int p = 0; p < path_count; ++p)
        if (!driver.timings[k][p].empty())
          std::printf("%s, %s: %.1f ns median\n", KINDS[k].name, PATH_NAMES[p],
                      tessera::bench::min_median(driver.timings[k][p]).median);
    return 0;
  }
  if (options.json) {
    nlohmann::json transactions = nlohmann::json::array();
    for (size_t k = 0; k < KIND_COUNT; ++k)
      transactions.push_back({{"name", KINDS[k].name},
                              {"floor_ns", driver.timings[k][floor_path]},
                              {"bus_ns", driver.timings[k][bus_path]},
                              {"memory_ns", driver.timings[k][memory_path]}});
    std::printf("%s\n", nlohmann::json{{"transactions", transactions}, {"rounds", options.rounds}}.dump().c_str());
    return 0;
  }

  std::printf(
      "bench_bus: %u transactions per timed loop, %u rounds (each path once per round, paired), quantum %u ns; "
      "bus %.0f MHz %u-bit, memory %u + %u cycles per beat\n\n",
      options.transactions, options.rounds, options.quantum_ns, 1e-6 / period.to_seconds(), bus_params.width_bytes * 8,
      memory_params.first_access_cycles, memory_params.beat_cycles);
  std::printf(
      "| transaction | floor ns (min / median) | bus ns (min / median) | bus + memory ns (min / median) | bus / floor "
      "(mins / median) | bus + memory / floor (mins / median) |\n"
      "|---|--:|--:|--:|--:|--:|\n");
  for (size_t k = 0; k < KIND_COUNT; ++k) {
    const auto& t = driver.timings[k];
    const tessera::bench::MinMedian floor = tessera::bench::min_median(t[floor_path]);
    const tessera::bench::MinMedian bus_only = tessera::bench::min_median(t[bus_path]);
    const tessera::bench::MinMedian memory_too = tessera::bench::min_median(t[memory_path]);
    const double bus_ratio = tessera::bench::min_median(ratios(t[bus_path], t[floor_path])).median;
    const double memory_ratio = tessera::bench::min_median(ratios(t[memory_path], t[floor_path])).median;
    std::printf("| %s | %.1f / %.1f | %.1f / %.1f | %.1f / %.1f | %.2f / %.2f | %.2f / %.2f |\n", KINDS[k].name,
                floor.min, floor.median, bus_only.min, bus_only.median, memory_too.min, memory_too.median,
                bus_only.min / floor.min, bus_ratio, memory_too.min / floor.min, memory_ratio);
  }
  std::printf(
      "\nRatios: \"mins\" is the ratio of the two min columns; \"median\" is the median over the rounds of the "
      "ratio within each round (the paths timed one after another on the same transactions).\n%s\n",
      tessera::bench::machine_summary(
          load_before, std::chrono::duration<double>(std::chrono::steady_clock::now() - bench_start).count())
          .c_str());
  return 0;
}

int run_main(int argc, char** argv) {
  Options options;
  CLI::App cli{"bench_bus: one LT transaction through the bus and memory against a bare quantum-keeper loop"};
  cli.add_option("--transactions", options.transactions, "transactions per timed loop")
      ->check(CLI::Range(1000u, 100000000u))
      ->capture_default_str();
  cli.add_option("--rounds", options.rounds, "rounds; min and median are printed")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  cli.add_option("--quantum-ns", options.quantum_ns, "global quantum of the keeper (soc_sim's sim.quantum_ns)")
      ->check(CLI::Range(1u, 1000000u))
      ->capture_default_str();
  cli.add_flag("--json", options.json, "print every round's ns per transaction per path as JSON, not the table");
  cli.add_option("--only", options.only,
                 "time one path alone (floor, bus or memory), for a profiler; prints its medians")
      ->check(CLI::IsMember({PATH_KEYS[floor_path], PATH_KEYS[bus_path], PATH_KEYS[memory_path]}));
  CLI11_PARSE(cli, argc, argv);
  return run(options);
}

}  // namespace

int sc_main(int argc, char* argv[]) {
  return tessera::guarded_main("bench_bus", [&] { return run_main(argc, argv); });
}
