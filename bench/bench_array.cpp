// bench_array: how fast the array processor's functional core simulates,
// in CU-instructions (lanes x instructions broadcast) per wall second, on
// a long program with the mix of a tile renderer's inner loop: 16-bit
// additions on CMEM and registers, a compare, mask updates, masked stores,
// a neighbour read and a multiply per line. No SystemC: the core alone, as
// the AC runs it. Prints min and median over repeated runs.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include <CLI/CLI.hpp>

#include "array/core/array_controller.h"
#include "guarded_main.h"

namespace {

using namespace tessera::ap;

Operand reg(unsigned index) {
  return {false, static_cast<uint16_t>(index), 0};
}
Operand mem(unsigned address, unsigned loop = 0) {
  return {true, static_cast<uint16_t>(address), static_cast<uint8_t>(loop)};
}
uint64_t op(Opcode opcode, Operand d = {}, Operand a = {}, Operand b = {}) {
  Instruction in;
  in.opcode = opcode;
  in.d = d;
  in.a = a;
  in.b = b;
  return encode(in);
}
uint64_t loop(unsigned level, unsigned start, unsigned step) {
  return op(Opcode::op_loop, reg(level), reg(start), reg(step));
}
uint64_t mask(Opcode opcode, Cond cond) {
  return op(opcode, {}, reg(static_cast<unsigned>(cond)));
}

// Per line (36 lines, i0) a multiply to start the edge function, then per
// pixel (8 pixels, i1) the edge and depth steps, the tests and the stores.
std::vector<uint64_t> tile_like_program(unsigned repeats) {
  std::vector<uint64_t> p = {loop(0, repeats - 1, 1),
                             loop(1, 35, 1),
                             op(Opcode::op_mul, reg(0), reg(3), reg(5)),
                             loop(2, 14, 2),
                             op(Opcode::op_add, reg(1), reg(1), mem(0x10)),
                             op(Opcode::op_adc, reg(0), reg(0), mem(0x11)),
                             mask(Opcode::op_mmov, Cond::ns),
                             op(Opcode::op_cmp, {}, mem(0x100, 3), reg(6)),
                             op(Opcode::op_cmpc, {}, mem(0x101, 3), reg(7)),
                             mask(Opcode::op_mand, Cond::nc),
                             op(Opcode::op_mov, mem(0x100, 3), reg(6)),
                             op(Opcode::op_mov, mem(0x101, 3), reg(7)),
                             op(Opcode::op_sub, reg(6), reg(6), mem(0x12)),
                             op(Opcode::op_sbc, reg(7), reg(7), mem(0x13)),
                             op(Opcode::op_nget, reg(2), reg(static_cast<unsigned>(Direction::left)), reg(1)),
                             op(Opcode::op_xor, mem(0x200, 3), reg(2), mem(0x14)),
                             op(Opcode::op_endloop),
                             op(Opcode::op_endloop),
                             op(Opcode::op_endloop),
                             op(Opcode::op_halt)};
  return p;
}

struct Options {
  unsigned repeats = 200;
  int runs = 7;
};

int run(const Options& options) {
  const ArrayGeometry geometry;  // the J2210's 24 x 4, 8 registers, 4 KB
  ArrayController controller(geometry, CycleTable::defaults(), 256, uint64_t{1} << 40);
  controller.load(0, tile_like_program(options.repeats));
  std::vector<double> rates;
  uint64_t instructions = 0;
  for (int r = 0; r < options.runs; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const RunResult result = controller.run(0);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!result.ok) {
      std::fprintf(stderr, "bench_array: the program failed: %s\n", result.error.c_str());
      return 1;
    }
    instructions = result.instructions;
    rates.push_back(static_cast<double>(result.instructions) * geometry.lanes() / seconds);
  }
  std::sort(rates.begin(), rates.end());
  std::printf("bench_array: %llu instructions broadcast to %u CUs per run, %d runs\n",
              static_cast<unsigned long long>(instructions), geometry.lanes(), options.runs);
  std::printf("| measure | min | median |\n| --- | --- | --- |\n");
  std::printf("| CU-instructions per second (lanes x instructions) | %.3g | %.3g |\n", rates.front(),
              rates[rates.size() / 2]);
  std::printf("| instructions broadcast per second | %.3g | %.3g |\n", rates.front() / geometry.lanes(),
              rates[rates.size() / 2] / geometry.lanes());
  return 0;
}

int run_main(int argc, char** argv) {
  Options options;
  CLI::App cli{"bench_array: the array processor's functional core, CU-instructions per wall second"};
  cli.add_option("--repeats", options.repeats, "times the 36 x 8-pixel tile loop runs per program")
      ->check(CLI::Range(1u, 100000u))
      ->capture_default_str();
  cli.add_option("--runs", options.runs, "runs; min and median are printed")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  CLI11_PARSE(cli, argc, argv);
  return run(options);
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_array", [&] { return run_main(argc, argv); });
}
