// bench_cu_rtl: speed of the array processor's C++ core (ap::CuArray, the
// whole 24 x 4 array, structure-of-arrays) against the Verilated CU
// (rtl_models/array/cu_datapath.sv through its adapter) on the same
// instruction stream. Prints one Markdown table.
//
//   bench_cu_rtl [--instructions N] [--repeat R] [--seed S]
//
// N random lane-work instructions (the generator of the array tests,
// testbench/cosim/random_instruction.h: every opcode equally often, random
// register and CMEM operand forms, loop variables) are drawn once. An
// untimed pass runs them on the C++ array and records, for one inside lane,
// the bytes the array hands that CU (cu_lane_inputs) before each
// instruction. Each timed C++ pass resets the array, restores its CMEM and
// runs the N instructions on all 96 lanes; each timed RTL pass resets the
// CU and runs the same N instructions with the recorded bytes, clocking the
// multiply's 8 steps as the hardware does. The figures are per pass: the
// minimum and the median over R passes. After the last passes the RTL CU's
// registers, flags and mask must equal that lane's in the C++ array.
//
// The fair comparison is per lane: the C++ core does 96 lanes' work per
// instruction, the RTL one CU's, so the table gives C++ lane-instructions
// per second beside RTL CU-instructions per second, and their ratio.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "array/core/cu_array.h"
#include "array/isa/ap_isa.h"
#include "cosim/random_instruction.h"
#include "cu_datapath_adapter.h"
#include "guarded_main.h"

namespace {

using namespace tessera::ap;

struct Options {
  uint64_t instructions = 1'000'000;
  unsigned repeat = 5;
  uint64_t seed = 0xc0be4c;
};

// Row 1, column 5 of the 24 x 4 grid: a CU with all four neighbours.
constexpr unsigned TRACED_LANE = 24 + 5;

struct Stream {
  std::vector<RandomInstruction> instructions;
  std::vector<CuLaneInputs> traced_inputs;  // per instruction, for TRACED_LANE
  std::vector<uint8_t> initial_cmem;        // lane-major, restored before each C++ pass
};

void restore_cmem(CuArray& array, const std::vector<uint8_t>& cmem) {
  array.reset();
  const unsigned bytes = array.geometry().cmem_bytes;
  for (unsigned lane = 0; lane < array.lanes(); ++lane)
    for (unsigned address = 0; address < bytes; ++address)
      array.set_cmem(lane, address, cmem[size_t{lane} * bytes + address]);
}

Stream make_stream(const Options& opt, CuArray& array) {
  std::mt19937_64 rng(opt.seed);
  Stream stream;
  const ArrayGeometry& geometry = array.geometry();
  stream.initial_cmem.resize(size_t{array.lanes()} * geometry.cmem_bytes);
  for (uint8_t& byte : stream.initial_cmem) byte = static_cast<uint8_t>(rng());
  stream.instructions.reserve(opt.instructions);
  for (uint64_t i = 0; i < opt.instructions; ++i)
    stream.instructions.push_back(random_instruction(rng, geometry.registers, geometry.cmem_bytes));
  restore_cmem(array, stream.initial_cmem);
  stream.traced_inputs.reserve(opt.instructions);
  for (const RandomInstruction& r : stream.instructions) {
    stream.traced_inputs.push_back(cu_lane_inputs(array, TRACED_LANE, r.instruction, r.variables));
    const std::string error = array.execute(r.instruction, r.variables, r.active_loops);
    if (!error.empty()) throw std::runtime_error("bench_cu_rtl: the C++ array refused an instruction: " + error);
  }
  return stream;
}

struct Times {
  double min_s = 0, median_s = 0;
};

// Runs `setup` (untimed) then `pass` (timed), `repeat` times.
template <class Setup, class Pass>
Times time_passes(unsigned repeat, Setup&& setup, Pass&& pass) {
  std::vector<double> seconds;
  for (unsigned r = 0; r < repeat; ++r) {
    setup();
    const auto start = std::chrono::steady_clock::now();
    pass();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  const size_t middle = seconds.size() / 2;
  const double median = seconds.size() % 2 == 1 ? seconds[middle] : (seconds[middle - 1] + seconds[middle]) / 2;
  return {seconds.front(), median};
}

std::string format_rate(double per_second) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f M", per_second / 1e6);
  return text;
}

int run(const Options& opt) {
  CuArray array(ArrayGeometry{});
  std::fprintf(stderr, "bench_cu_rtl: drawing %llu instructions ...\n",
               static_cast<unsigned long long>(opt.instructions));
  const Stream stream = make_stream(opt, array);
  const auto n = static_cast<double>(opt.instructions);
  const double lanes = array.lanes();

  const Times cpp = time_passes(
      opt.repeat, [&] { restore_cmem(array, stream.initial_cmem); },
      [&] {
        for (const RandomInstruction& i : stream.instructions)
          array.execute(i.instruction, i.variables, i.active_loops);
      });

  CuDatapathRtl cu;
  uint64_t clock_edges = 0;
  const Times rtl = time_passes(
      opt.repeat,
      [&] {
        cu.reset();
        clock_edges = 0;
      },
      [&] {
        for (size_t i = 0; i < stream.instructions.size(); ++i) {
          const CuLaneInputs& inputs = stream.traced_inputs[i];
          cu.execute(stream.instructions[i].instruction, inputs.operands, inputs.neighbours);
          clock_edges += cu.last_cycles();
        }
      });

  bool agree = cu.flags() == array.flags(TRACED_LANE) && cu.mask() == array.mask(TRACED_LANE);
  for (unsigned k = 0; k < CuDatapathRtl::REGISTERS; ++k) agree = agree && cu.reg(k) == array.reg(TRACED_LANE, k);

  std::printf(
      "| model | instructions/s (min time) | instructions/s (median) | lane-instructions/s (min) | "
      "lane-instructions/s (median) |\n");
  std::printf("|---|--:|--:|--:|--:|\n");
  std::printf("| C++ core, 24 x 4 array | %s | %s | %s | %s |\n", format_rate(n / cpp.min_s).c_str(),
              format_rate(n / cpp.median_s).c_str(), format_rate(n * lanes / cpp.min_s).c_str(),
              format_rate(n * lanes / cpp.median_s).c_str());
  std::printf("| Verilated CU, one lane | %s | %s | %s | %s |\n", format_rate(n / rtl.min_s).c_str(),
              format_rate(n / rtl.median_s).c_str(), format_rate(n / rtl.min_s).c_str(),
              format_rate(n / rtl.median_s).c_str());
  std::printf(
      "\nPer lane, C++ / RTL: %.0fx (min times), %.0fx (median). %llu instructions (seed %#llx), %u passes "
      "each; the RTL clocked %llu edges per pass (%.2f per instruction: the multiply takes 8). RTL lane %u "
      "state after the run %s the C++ array's.\n",
      (n * lanes / cpp.min_s) / (n / rtl.min_s), (n * lanes / cpp.median_s) / (n / rtl.median_s),
      static_cast<unsigned long long>(opt.instructions), static_cast<unsigned long long>(opt.seed), opt.repeat,
      static_cast<unsigned long long>(clock_edges), static_cast<double>(clock_edges) / n, TRACED_LANE,
      agree ? "equals" : "DIFFERS FROM");
  return agree ? 0 : 1;
}

}  // namespace

static int run_main(int argc, char** argv) {
  Options opt;
  CLI::App cli{"bench_cu_rtl: the array's C++ core against the Verilated CU, same instruction stream"};
  cli.add_option("--instructions", opt.instructions, "random instructions per pass")
      ->check(CLI::Range(uint64_t{1}, uint64_t{50'000'000}))
      ->capture_default_str();
  cli.add_option("--repeat", opt.repeat, "passes per model; the minimum and median are printed")
      ->check(CLI::Range(1, 50))
      ->capture_default_str();
  cli.add_option("--seed", opt.seed, "seed of the instruction generator")->capture_default_str();
  CLI11_PARSE(cli, argc, argv);
  return run(opt);
}

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_cu_rtl", [&] { return run_main(argc, argv); });
}
