// bench_iss: how fast the ISS runs real compiled code (issue 15, item 1:
// at least 30 million simulated instructions per wall second with timing and
// caches on). tests/host/iss_programs/compute_rounds.c (compute.c's workload
// 100 times over) built for the ARM922T in ARM and in Thumb state, run four
// ways:
//   - core: ArmCore alone on BareMachine (no timing, no caches), in this
//     process, the run loop timed (loading excluded);
//   - timing: the core with Arm922tTiming (the ARM9TDMI's cycles, the
//     instruction cache on, as iss_run --timing), in this process, likewise;
//   - soc_sim: the whole SoC, `soc_sim --app PROGRAM.elf --no-frames -q` as a
//     child process (the data side through the host's data-cache tag model,
//     write buffer, quantum keeper and bus), the whole process timed:
//     start-up and exit included, so its figure is a lower bound; the row of
//     the one-round program (compute_arm.elf) shows what they cost;
//   - Unicorn: the same ELF on Unicorn (QEMU's translating emulator, the
//     lock-step test's reference), no timing and no caches, in this
//     process, the run loop timed: the yardstick the ISS with timing and
//     caches is measured against (goal: as fast, a paired ratio of at
//     least 1), as soc_sim is against the ISS with timing (goal: 80% of
//     its rate).
// Each round makes every run once, in an order rotating from round to
// round, so that a change in the machine's load hits all alike; prints min
// and median wall time, the MIPS at each, the median CPU time and the MIPS
// per CPU second (what the simulation costs when it has a core: on a loaded
// machine the wall time is more the load's), and the slowdowns as medians
// of the ratios within each round.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <time.h>

#include <unicorn/unicorn.h>
#include <CLI/CLI.hpp>

#include "bench_support.h"
#include "guarded_main.h"
#include "host/iss/arm922t_timing.h"
#include "host/iss/bare_machine.h"
#include "host/iss/cp15.h"

namespace {

namespace fs = std::filesystem;
using namespace tessera::bench;
using tessera::iss::Arm922tTiming;
using tessera::iss::ArmCore;
using tessera::iss::BareMachine;
using tessera::iss::Cp15;
using tessera::iss::ElfImage;

constexpr double GOAL_MIPS = 30;
// The ISS with timing and caches against Unicorn without either, and soc_sim
// against the ISS with timing alone: rates, paired by round.
constexpr double GOAL_UNICORN_RATIO = 1.0;
constexpr double GOAL_SOC_SIM_FRACTION = 0.8;
constexpr uint64_t INSTRUCTION_LIMIT = 1'000'000'000;

struct Run {
  double seconds = 0;      // wall
  double cpu_seconds = 0;  // this thread's CPU time, or the child's (user + system)
  uint64_t instructions = 0;
  std::string console;
};

// Wall and CPU time of a run loop: on a loaded machine the two differ, and
// the CPU time shows what the simulation costs when it has a core.
class Stopwatch {
 public:
  Stopwatch() : m_wall(std::chrono::steady_clock::now()), m_cpu(thread_cpu_seconds()) {}
  double wall_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_wall).count();
  }
  double cpu_seconds() const { return thread_cpu_seconds() - m_cpu; }

 private:
  static double thread_cpu_seconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
  }
  std::chrono::steady_clock::time_point m_wall;
  double m_cpu;
};

void check_exit(const BareMachine& machine, const ElfImage& image) {
  if (!machine.exited() || machine.status() != 0) throw std::runtime_error(image.path + ": did not run to its end");
}

Run run_core(const ElfImage& image) {
  BareMachine machine;
  ArmCore core(machine);
  machine.load(image, core);
  const Stopwatch clock;
  machine.run(core, INSTRUCTION_LIMIT);
  Run run{clock.wall_seconds(), clock.cpu_seconds(), core.instructions(), machine.console()};
  check_exit(machine, image);
  return run;
}

// As iss_run --timing: the instruction cache on from the start, data memory
// without wait states.
Run run_timed(const ElfImage& image) {
  BareMachine machine;
  Arm922tTiming timing;
  tessera::iss::TimedFetch port(machine, &timing);
  ArmCore core(port);
  Cp15 cp15(core, &timing);
  core.set_coprocessors(&cp15);
  timing.attach(&cp15);
  cp15.mcr(15, 0, 1, 0, 0, true, cp15.control() | Cp15::CONTROL_I);
  machine.load(image, core);
  const Stopwatch clock;
  machine.run(
      core, INSTRUCTION_LIMIT, [&]() __attribute__((always_inline)) { timing.step(core.last_step()); });
  Run run{clock.wall_seconds(), clock.cpu_seconds(), core.instructions(), machine.console()};
  check_exit(machine, image);
  return run;
}

// The program on Unicorn: the bare machine's RAM (1 MiB at 0) and its
// console and exit registers as an MMIO page; the exit stops the emulation.
// Unicorn counts no instructions without a hook (which would slow it), so
// the run's count is the ISS's, the console being checked the same.
Run run_unicorn(const ElfImage& image, uint64_t instructions) {
  struct Machine {
    uc_engine* uc = nullptr;
    std::string console;
    bool exited = false;
    uint32_t status = 0;
    ~Machine() {
      if (uc != nullptr) uc_close(uc);
    }
  } machine;
  const auto check = [&](uc_err error, const char* what) {
    if (error != UC_ERR_OK) throw std::runtime_error(std::string("Unicorn: ") + what + ": " + uc_strerror(error));
  };
  constexpr uint32_t RAM_BYTES = 1u << 20, PAGE_BYTES = 0x1000;
  check(uc_open(UC_ARCH_ARM, UC_MODE_ARM, &machine.uc), "uc_open");
  check(uc_ctl_set_cpu_model(machine.uc, UC_CPU_ARM_TI925T), "the CPU model (TI925T: ARMv4T)");
  check(uc_mem_map(machine.uc, 0, RAM_BYTES, UC_PROT_ALL), "mapping the RAM");
  image.check_fits(0, RAM_BYTES, "the bare machine's RAM");
  for (const tessera::iss::ElfSegment& segment : image.segments)
    if (!segment.bytes.empty())
      check(uc_mem_write(machine.uc, segment.address, segment.bytes.data(), segment.bytes.size()), "loading");
  const auto read = [](uc_engine*, uint64_t, unsigned, void*) -> uint64_t { return 0; };
  const auto write = [](uc_engine* uc, uint64_t offset, unsigned, uint64_t value, void* data) {
    auto& m = *static_cast<Machine*>(data);
    if (offset == BareMachine::CONSOLE - BareMachine::CONSOLE) {
      m.console += static_cast<char>(value);
    } else if (offset == BareMachine::EXIT - BareMachine::CONSOLE) {
      m.exited = true;
      m.status = static_cast<uint32_t>(value);
      uc_emu_stop(uc);
    }
  };
  check(uc_mmio_map(machine.uc, BareMachine::CONSOLE, PAGE_BYTES, read, nullptr, write, &machine),
        "mapping the console and exit registers");
  const Stopwatch clock;
  check(uc_emu_start(machine.uc, image.entry, ~uint64_t{0}, 0, 0), "running");
  Run run{clock.wall_seconds(), clock.cpu_seconds(), instructions, machine.console};
  if (!machine.exited || machine.status != 0)
    throw std::runtime_error(image.path + ": did not run to its end on Unicorn");
  return run;
}

struct Series {
  std::string program, run;
  uint64_t instructions = 0;
  std::vector<double> seconds, cpu_seconds;
  void add(const Run& run) {
    seconds.push_back(positive(run.seconds, program + ", " + this->run + ": wall time"));
    cpu_seconds.push_back(positive(run.cpu_seconds, program + ", " + this->run + ": CPU time"));
  }
  double mips(double time) const { return static_cast<double>(instructions) / time / 1e6; }
};

int run_main(int argc, char** argv) {
  CLI::App app{"bench_iss: the ISS's speed on compiled ARM and Thumb code, alone, with timing, in the SoC"};
  int repeat = 5;
  std::string arm_elf = TESSERA_ISS_ROUNDS_ARM_ELF, thumb_elf = TESSERA_ISS_ROUNDS_THUMB_ELF;
  std::string startup_elf = TESSERA_ISS_ARM_ELF;
  std::string soc_sim = (own_directory() / "soc_sim").string(), work_dir;
  app.add_option("--repeat", repeat, "rounds")->check(CLI::Range(1, 1000));
  app.add_option("--arm", arm_elf, "the ARM-state program")->check(CLI::ExistingFile);
  app.add_option("--thumb", thumb_elf, "the Thumb-state program")->check(CLI::ExistingFile);
  app.add_option("--startup-program", startup_elf, "a short program, whose soc_sim run is mostly start-up")
      ->check(CLI::ExistingFile);
  app.add_option("--soc-sim", soc_sim, "the soc_sim to run")->check(CLI::ExistingFile);
  app.add_option("--work-dir", work_dir, "folder for soc_sim's outputs (default: a temporary one, removed)");
  CLI11_PARSE(app, argc, argv);
  try {
    const WorkFolder folder(work_dir, "bench_iss");
    const fs::path& work = folder.path();
    const std::string load_before = load_average();
    const auto begin = std::chrono::steady_clock::now();

    const ElfImage images[3] = {tessera::iss::read_elf(arm_elf), tessera::iss::read_elf(thumb_elf),
                                tessera::iss::read_elf(startup_elf)};
    // A first run of each, untimed: its instructions and its output, which
    // every timed run must repeat (the SoC runs the same instructions when
    // it prints the same).
    Run reference[3];
    for (size_t p = 0; p < 3; ++p) reference[p] = run_core(images[p]);
    const char* states[2] = {"ARM", "Thumb"};
    const char* runs[4] = {"core alone", "core + ARM922T timing (I-cache on)", "soc_sim, whole process",
                           "Unicorn (no timing, no caches)"};
    constexpr size_t RUNS = 4;  // series per state: core, timing, soc_sim, Unicorn; then the start-up row
    std::vector<Series> series;
    for (size_t s = 0; s < 2; ++s)
      for (const char* run : runs)
        series.push_back(
            {fs::path(images[s].path).filename().string() + ", " + states[s], run, reference[s].instructions, {}, {}});
    series.push_back(
        {fs::path(images[2].path).filename().string() + ", ARM (1 round)", runs[2], reference[2].instructions, {}, {}});
    const size_t startup_row = 2 * RUNS;

    const auto checked = [&](const Run& run, size_t p) {
      if (run.console != reference[p].console || run.instructions != reference[p].instructions)
        throw std::runtime_error(images[p].path + ": a run differs from the first");
      return run;
    };
    const auto soc_sim_run = [&](size_t p) {
      const ChildResult child = run_child(
          {soc_sim, "--app", images[p].path, "--no-frames", "-q", "--force", "--out", (work / "out").string()},
          work / "soc_sim.stdout");
      if (child.output != reference[p].console)
        throw std::runtime_error("soc_sim --app " + images[p].path + ": its output differs from the bare machine's");
      return Run{child.wall_s, child.cpu_s, reference[p].instructions, child.output};
    };
    std::vector<std::function<void()>> steps;
    for (size_t s = 0; s < 2; ++s) {
      steps.push_back([&, s] { series[RUNS * s].add(checked(run_core(images[s]), s)); });
      steps.push_back([&, s] { series[RUNS * s + 1].add(checked(run_timed(images[s]), s)); });
      steps.push_back([&, s] { series[RUNS * s + 2].add(soc_sim_run(s)); });
      steps.push_back(
          [&, s] { series[RUNS * s + 3].add(checked(run_unicorn(images[s], reference[s].instructions), s)); });
    }
    steps.push_back([&] { series[startup_row].add(soc_sim_run(2)); });
    for (int r = 0; r < repeat; ++r)
      for (size_t i = 0; i < steps.size(); ++i) steps[(i + static_cast<size_t>(r)) % steps.size()]();
    fs::remove_all(work / "out");

    std::printf(
        "| program | run | instructions | wall min / median (ms) | MIPS at the min / median | CPU median (ms) | MIPS "
        "per CPU second |\n");
    std::printf("|---|---|--:|--:|--:|--:|--:|\n");
    for (const Series& row : series) {
      const MinMedian wall = min_median(row.seconds);
      const double cpu = min_median(row.cpu_seconds).median;
      std::printf("| %s | %s | %llu | %.1f / %.1f | %.1f / %.1f | %.1f | %.1f |\n", row.program.c_str(),
                  row.run.c_str(), static_cast<unsigned long long>(row.instructions), 1e3 * wall.min, 1e3 * wall.median,
                  row.mips(wall.min), row.mips(wall.median), 1e3 * cpu, row.mips(cpu));
    }
    std::printf("\nSlowdowns, medians of the ratios of wall times within each round:");
    for (size_t s = 0; s < 2; ++s)
      std::printf(" %s: timing / core %.2f, soc_sim / timing %.2f%s", states[s],
                  paired_median(series[RUNS * s + 1].seconds, series[RUNS * s].seconds),
                  paired_median(series[RUNS * s + 2].seconds, series[RUNS * s + 1].seconds), s == 0 ? ";" : ".\n");
    // Rates, so that a ratio of at least the goal is met: Unicorn's time over
    // the ISS's is the ISS's rate over Unicorn's. CPU time too: on a loaded
    // machine the wall time is more the load's.
    bool unicorn_met = true, soc_sim_met = true;
    std::printf("Paired rate ratios (medians over the rounds; wall, CPU):");
    for (size_t s = 0; s < 2; ++s) {
      const Series &timed = series[RUNS * s + 1], &whole = series[RUNS * s + 2], &unicorn = series[RUNS * s + 3];
      const double unicorn_wall = paired_median(unicorn.seconds, timed.seconds);
      const double unicorn_cpu = paired_median(unicorn.cpu_seconds, timed.cpu_seconds);
      const double soc_sim_wall = paired_median(timed.seconds, whole.seconds);
      const double soc_sim_cpu = paired_median(timed.cpu_seconds, whole.cpu_seconds);
      unicorn_met = unicorn_met && unicorn_wall >= GOAL_UNICORN_RATIO;
      soc_sim_met = soc_sim_met && soc_sim_wall >= GOAL_SOC_SIM_FRACTION;
      std::printf(" %s: ISS with timing and caches / Unicorn %.2f, %.2f; soc_sim / ISS with timing %.0f%%, %.0f%%%s",
                  states[s], unicorn_wall, unicorn_cpu, 100 * soc_sim_wall, 100 * soc_sim_cpu, s == 0 ? ";" : ".\n");
    }
    bool met = true;
    for (size_t s = 0; s < 2; ++s)
      for (size_t way = 1; way < 3; ++way) {
        const Series& row = series[RUNS * s + way];
        met = met && row.mips(min_median(row.seconds).median) >= GOAL_MIPS;
      }
    std::printf(
        "The ISS's speed goal (at least %.0f MIPS with timing and caches on, wall time at the median, soc_sim's "
        "start-up included): %s. Against Unicorn (at least %.2f times its rate, wall): %s. soc_sim against the ISS "
        "with timing (at least %.0f%% of its rate, wall, start-up included): %s. %d rounds of the %zu runs in "
        "rotating order; CPU time: this thread's (in-process runs), the child's user + system (soc_sim).\n",
        GOAL_MIPS, met ? "met" : "not met", GOAL_UNICORN_RATIO, unicorn_met ? "met" : "not met",
        100 * GOAL_SOC_SIM_FRACTION, soc_sim_met ? "met" : "not met", repeat, steps.size());
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    std::printf("\n%s\n", machine_summary(load_before, total).c_str());
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
