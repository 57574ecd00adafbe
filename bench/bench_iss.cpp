// bench_iss: how fast the ISS core runs real compiled code, alone (no
// SystemC, no timing, no caches): tests/host/iss_programs/compute.c built
// for the ARM922T in ARM and in Thumb state, on BareMachine. Runs alternate
// (ARM, Thumb, ARM, ...) --repeat times; prints min and median wall time of
// the run loop (loading excluded) and millions of instructions per second.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench_support.h"
#include "guarded_main.h"
#include "host/iss/bare_machine.h"

namespace {

struct Timed {
  double seconds;
  uint64_t instructions;
};

Timed run_once(const tessera::iss::ElfImage& image) {
  tessera::iss::BareMachine machine;
  tessera::iss::ArmCore core(machine);
  machine.load(image, core);
  const auto start = std::chrono::steady_clock::now();
  const bool exited = machine.run(core, 100'000'000);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!exited || machine.status() != 0) throw std::runtime_error(image.path + ": did not run to its end");
  return {seconds, core.instructions()};
}

int run_main(int argc, char** argv) {
  CLI::App app{"bench_iss: the ISS core's speed on compiled ARM and Thumb code"};
  int repeat = 21;
  std::string arm_elf = TESSERA_ISS_ARM_ELF, thumb_elf = TESSERA_ISS_THUMB_ELF;
  app.add_option("--repeat", repeat, "runs of each program, alternating")->check(CLI::Range(1, 100000));
  app.add_option("--arm", arm_elf, "the ARM-state program")->check(CLI::ExistingFile);
  app.add_option("--thumb", thumb_elf, "the Thumb-state program")->check(CLI::ExistingFile);
  CLI11_PARSE(app, argc, argv);
  try {
    const std::string load_before = tessera::bench::load_average();
    const auto begin = std::chrono::steady_clock::now();
    const tessera::iss::ElfImage images[2] = {tessera::iss::read_elf(arm_elf), tessera::iss::read_elf(thumb_elf)};
    std::vector<double> seconds[2];
    uint64_t instructions[2] = {0, 0};
    for (int r = 0; r < repeat; ++r)
      for (int s = 0; s < 2; ++s) {
        const Timed t = run_once(images[s]);
        seconds[s].push_back(t.seconds);
        instructions[s] = t.instructions;
      }
    std::printf("| program | instructions | min wall (ms) | median wall (ms) | MIPS at the median |\n");
    std::printf("|---|---|---|---|---|\n");
    const char* names[2] = {"compute.c, ARM state", "compute.c, Thumb state"};
    for (int s = 0; s < 2; ++s) {
      const tessera::bench::MinMedian times = tessera::bench::min_median(seconds[s]);
      std::printf("| %s | %llu | %.2f | %.2f | %.1f |\n", names[s], static_cast<unsigned long long>(instructions[s]),
                  1e3 * times.min, 1e3 * times.median, static_cast<double>(instructions[s]) / times.median / 1e6);
    }
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    std::printf("\n%s\n", tessera::bench::machine_summary(load_before, total).c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_iss: %s\n", error.what());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_iss", [&] { return run_main(argc, argv); });
}
