// bench_raster: the benchmark of the rasterizer (the `raster` back end, the
// SystemC module tlm/raster/rasterizer.{h,cpp} and its functional core).
// Three tables, each measurement in child processes:
//  1. fragments per wall-clock second of soc_sim --backend raster
//     (teapot and fullscreen_rect by default), beside the functional core
//     (TileRasterizer) run natively under the same driver (this program again,
//     with --native-core);
//  2. the datapath's C++ units against their Verilated RTL (bench_rtl,
//     printed as it comes);
//  3. simulated time per frame of every scene on `raster` beside `arm`.
// Then the configuration, the machine and its load average. See README.md
// for the method.
//
//   bench_raster [--frames N] [--repeat R] [--wall-scene NAME ...] [--scene NAME ...]
//                [--vectors V] [--config FILE ...] [--obj FILE] [--work-dir DIR] [--soc-sim PATH]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "guarded_main.h"

#include "apps/gl_apps.h"
#include "host/native_host.h"
#include "raster/core/tile_rasterizer.h"
#include "raster/raster_regs.h"
#include "renderers/backends.h"
#include "scenes/scene.h"
#include "soc/irq_map.h"
#include "soc/memory_map.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace tessera::bench;
using tessera::bytes_per_pixel;
using tessera::pixel_format_from_code;
using tessera::pixel_format_from_name;
using tessera::PixelFormat;

// The built-in scenes, from the driver's registry that soc_sim is built with.
std::vector<std::string> all_scene_names() {
  std::vector<std::string> names;
  for (const auto& scene : tessera::scenes::all_scenes()) names.push_back(scene.name);
  return names;
}

struct Options {
  unsigned frames = 100;
  unsigned repeat = 3;
  std::vector<std::string> wall_scenes = {"teapot", "fullscreen_rect"};
  std::vector<std::string> scenes = all_scene_names();
  uint64_t vectors = 1'000'000;
  std::vector<std::string> config_files;
  std::string obj_file = TESSERA_BENCH_OBJ_FILE;
  std::string work_dir;
  std::string soc_sim;
  std::string bench_rtl;
  std::string self;
  std::string native_core;  // child mode: run this scene's core natively, print JSON
};

std::string format_count(double count) {
  char text[32];
  if (count >= 1e6)
    std::snprintf(text, sizeof text, "%.2f M", count / 1e6);
  else if (count >= 1e3)
    std::snprintf(text, sizeof text, "%.1f k", count / 1e3);
  else
    std::snprintf(text, sizeof text, "%.0f", count);
  return text;
}

// ---------------------------------------------------------------------------
// The functional core natively: the scene runs through the GL front end and
// the raster back end on a NativeHost, and the rasterizer's registers are
// answered here by a TileRasterizer over the same memory. Only the core's
// run() calls are timed, so this is the core's speed without SystemC, the
// host model or the driver.

// The CPU time of this thread: the core's time without the time the thread
// waited for a processor on a loaded machine (as bench_rtl times its units).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

// A RasterPort straight into the native host's memory.
class NativeRasterPort : public tessera::raster::RasterPort {
 public:
  explicit NativeRasterPort(tessera::bench::NativeHost& host) : m_host(host) {}

  bool read(uint32_t address, void* data, unsigned bytes) override {
    try {
      std::memcpy(data, m_host.load_span(address, 1, bytes), bytes);
      return true;
    } catch (const std::exception&) {
      return false;
    }
  }
  bool write(uint32_t address, const void* data, unsigned bytes) override {
    try {
      std::memcpy(m_host.store_span(address, 1, bytes), data, bytes);
      return true;
    } catch (const std::exception&) {
      return false;
    }
  }
  void cycles(uint64_t) override {}

 private:
  tessera::bench::NativeHost& m_host;
};

// NativeHost with the rasterizer's register window (raster_regs.def) in
// front of it. START runs the core at once; the interrupt it raises has
// always happened by the time the driver waits for it.
class RasterNativeHost : public tessera::HostApi {
 public:
  RasterNativeHost(tessera::bench::NativeHost& host, const tessera::raster::RunConfig& geometry, unsigned timed_after)
      : m_host(host), m_port(host), m_core(m_port), m_config(geometry), m_timed_after(timed_after) {}

  void compute(tessera::Op op, uint64_t count) override { m_host.compute(op, count); }
  void compute_cycles(uint64_t cycles) override { m_host.compute_cycles(cycles); }
  uint32_t read32(uint32_t address) override { return is_reg(address) ? read_reg(address) : m_host.read32(address); }
  uint16_t read16(uint32_t address) override { return m_host.read16(address); }
  uint8_t read8(uint32_t address) override { return m_host.read8(address); }
  void write32(uint32_t address, uint32_t value) override {
    if (is_reg(address))
      write_reg(address, value);
    else
      m_host.write32(address, value);
  }
  void write16(uint32_t address, uint16_t value) override { m_host.write16(address, value); }
  void write8(uint32_t address, uint8_t value) override { m_host.write8(address, value); }
  void read_words(uint32_t address, uint32_t* words, unsigned count) override {
    m_host.read_words(address, words, count);
  }
  void write_words(uint32_t address, const uint32_t* words, unsigned count) override {
    m_host.write_words(address, words, count);
  }
  const uint8_t* load_span(uint32_t address, unsigned size, unsigned count) override {
    return m_host.load_span(address, size, count);
  }
  uint8_t* store_span(uint32_t address, unsigned size, unsigned count) override {
    return m_host.store_span(address, size, count);
  }
  void wait_irq(unsigned line) override { m_host.wait_irq(line); }
  bool irq_pending(unsigned line) override { return m_host.irq_pending(line); }
  double now_seconds() const override { return 0.0; }
  double clock_hz() const override { return 0.0; }

  // Frames N..2N-1: runs started after the N-th present; wall time and
  // this thread's CPU time.
  double timed_s = 0, timed_cpu_s = 0;
  uint64_t timed_fragments = 0, timed_runs = 0;

 private:
  static bool is_reg(uint32_t address) {
    return address - tessera::memory_map::raster_regs.base < tessera::memory_map::raster_regs.size;
  }

  uint32_t read_reg(uint32_t address) {
    namespace regs = tessera::raster_regs;
    switch (address - tessera::memory_map::raster_regs.base) {
      case regs::STATUS: return m_status;
      case regs::IRQ_STATUS: return m_irq_status;
      case regs::ERROR_STATUS: return static_cast<uint32_t>(m_last.error);
      case regs::ERROR_ADDRESS: return m_last.error_address;
      case regs::WIDTH: return m_config.width;
      case regs::HEIGHT: return m_config.height;
      case regs::TILE_WIDTH: return m_config.tile_width;
      case regs::TILE_HEIGHT: return m_config.tile_height;
      case regs::TEXTURE_UNITS: return m_config.texture_units;
      case regs::FRAGMENTS: return static_cast<uint32_t>(m_last.fragments);
      case regs::TRIANGLES: return static_cast<uint32_t>(m_last.triangles);
      default: return 0;
    }
  }

  void write_reg(uint32_t address, uint32_t value) {
    namespace regs = tessera::raster_regs;
    switch (address - tessera::memory_map::raster_regs.base) {
      case regs::TILE_TABLE: m_config.tile_table = value; break;
      case regs::COLOR_BASE: m_config.color_base = value; break;
      case regs::DEPTH_BASE: m_config.depth_base = value; break;
      case regs::FORMAT: m_config.color_format = pixel_format_from_code(value).value_or(PixelFormat::rgb565); break;
      case regs::IRQ_STATUS: m_irq_status &= ~value; break;
      case regs::START:
        if (value & 1) start();
        break;
      default: break;
    }
  }

  void start() {
    const bool timed = m_host.present_times().size() >= m_timed_after;
    const auto begin = std::chrono::steady_clock::now();
    const double cpu_begin = thread_cpu_seconds();
    m_last = m_core.run(m_config);
    if (timed) {
      timed_cpu_s += thread_cpu_seconds() - cpu_begin;
      timed_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      timed_fragments += m_last.fragments;
      ++timed_runs;
    }
    const bool error = m_last.error != tessera::raster::RasterError::none;
    m_status = error ? tessera::raster_regs::STATUS_ERROR : tessera::raster_regs::STATUS_DONE;
    m_irq_status |= error ? tessera::raster_regs::IRQ_ERROR : tessera::raster_regs::IRQ_DONE;
  }

  tessera::bench::NativeHost& m_host;
  NativeRasterPort m_port;
  tessera::raster::TileRasterizer m_core;
  tessera::raster::RunConfig m_config;
  unsigned m_timed_after;
  tessera::raster::RunResult m_last;
  uint32_t m_status = 0, m_irq_status = 0;
};

struct CoreResult {
  double seconds = 0, cpu_seconds = 0;
  uint64_t fragments = 0, runs = 0;
};

// Runs `scene` for 2N frames on the raster back end natively, with the
// display, memory and rasterizer geometry of soc_sim's configuration (the
// boot loader's memory layout, as bench_arm_native), and returns the core's
// time and fragments over frames N..2N-1.
CoreResult run_core_natively(const std::string& scene_name, unsigned n, const json& config,
                             const std::vector<std::string>& scene_args) {
  const tessera::scenes::Scene* scene = tessera::scenes::find_scene(scene_name);
  if (!scene) throw std::runtime_error("no built-in scene " + scene_name);
  // json::at: a key soc_sim's configuration no longer has is an error
  // naming it (operator[] on a const json is undefined there).
  const json& display_config = config.at("display");
  const json& raster_config = config.at("raster");
  tessera::bench::NativeDisplay display;
  display.width = display_config.at("width").get<unsigned>();
  display.height = display_config.at("height").get<unsigned>();
  display.format = pixel_format_from_name(display_config.at("format").get<std::string>()).value_or(PixelFormat::rgb565);
  display.dma = display_config.at("dma").get<bool>();
  const uint32_t memory_bytes = config.at("mem").at("size_mib").get<uint32_t>() << 20;
  tessera::raster::RunConfig geometry;
  // The rasterizer draws at the display's size (soc_sim has no raster.width).
  geometry.width = display.width;
  geometry.height = display.height;
  geometry.tile_width = raster_config.at("tile_width").get<unsigned>();
  geometry.tile_height = raster_config.at("tile_height").get<unsigned>();
  geometry.texture_units = raster_config.at("texture_units").get<unsigned>();
  const auto method =
      tessera::raster::parse_recip_method(std::to_string(raster_config.at("recip_method").get<unsigned>()));
  if (method) geometry.recip_method = *method;

  tessera::bench::NativeHost native(memory_bytes, display);
  RasterNativeHost host(native, geometry, n);
  tessera::AppEnvironment env;
  env.host = &host;
  env.frames = 2 * n;
  env.memory_bytes = memory_bytes;
  tessera::backends::hand_over(tessera::backends::backend("raster"), env);
  env.args = scene_args;
  const uint64_t frame_bytes = uint64_t{display.width} * display.height * bytes_per_pixel(display.format);
  const uint64_t frame = (frame_bytes + 4095) / 4096 * 4096;
  env.frame_buffers[0] = static_cast<uint32_t>(env.memory_bytes - 2 * frame);
  env.frame_buffers[1] = static_cast<uint32_t>(env.memory_bytes - frame);
  env.heap_base = std::min<uint32_t>(4u << 20, env.frame_buffers[0]);
  env.heap_end = env.frame_buffers[0];
  const int status = tessera::run_scene_app(env, *scene);
  if (status != 0 || native.present_times().size() != 2 * n)
    throw std::runtime_error("native raster run of " + scene_name + " ended with status " + std::to_string(status) +
                             " after " + std::to_string(native.present_times().size()) + " frames");
  return CoreResult{host.timed_s, host.timed_cpu_s, host.timed_fragments, host.timed_runs};
}

// What one soc_sim run reports that the tables use.
struct RunFigures {
  double simulated_ns = 0;
  double raster_busy_ns = 0;
  double fragments = 0;
  double fragments_written = 0;
  double triangles = 0;
};

// Frames N..2N-1 of one scene on one back end. The counts are the 2N run's
// minus the N run's (the model is deterministic: the same counts every run,
// so the difference is exact); the wall time is taken within each 2N run
// (soc_sim --wall-clock), the best of R, never from two runs.
struct SceneRuns {
  RunFigures n, two_n;
  double wall_per_frame = std::numeric_limits<double>::max();

  double per_frame(double RunFigures::*field, unsigned frames) const { return (two_n.*field - n.*field) / frames; }
  double wall_per_frame_s(unsigned frames) const {
    (void)frames;
    return wall_per_frame;
  }
};

class Bench {
 public:
  explicit Bench(Options options) : m_opt(std::move(options)) {}

  void run();

 private:
  std::vector<std::string> soc_sim_command(const std::string& backend, const std::string& scene, unsigned frames,
                                           const fs::path& out) const;
  SceneRuns measure(const std::string& backend, const std::string& scene, unsigned repeat);
  void print_fragment_table() const;
  void print_frame_time_table() const;

  Options m_opt;
  fs::path m_work;
  unsigned m_run = 0;
  json m_config;
  std::map<std::string, SceneRuns> m_raster, m_arm;
  std::map<std::string, CoreResult> m_core;              // the functional core natively, best of R
  std::map<std::string, std::vector<double>> m_core_ns;  // ns per fragment of each of the R processes
};

std::vector<std::string> Bench::soc_sim_command(const std::string& backend, const std::string& scene, unsigned frames,
                                                const fs::path& out) const {
  std::vector<std::string> command = {m_opt.soc_sim};
  for (const auto& file : m_opt.config_files) command.insert(command.end(), {"--config", file});
  command.insert(command.end(), {"--backend", backend, "--app", scene, "--frames", std::to_string(frames), "--out",
                                 out.string(), "--quiet", "--force", "--wall-clock"});
  if (scene == "obj_viewer") command.insert(command.end(), {"--", m_opt.obj_file});
  return command;
}

SceneRuns Bench::measure(const std::string& backend, const std::string& scene, unsigned repeat) {
  std::fprintf(stderr, "bench_raster: %s on %s ...\n", scene.c_str(), backend.c_str());
  SceneRuns runs;
  // One run of N frames for the counts, then R runs of 2N frames, each
  // timed within itself.
  for (unsigned r = 0; r < repeat + 1; ++r) {
    const unsigned frames = r == 0 ? m_opt.frames : 2 * m_opt.frames;
    const fs::path out = m_work / ("soc_sim_" + std::to_string(m_run++));
    run_child(soc_sim_command(backend, scene, frames, out), m_work / "soc_sim.stdout");
    const json stats = read_json_file(out / "stats.json");
    if (stats["exit_status"] != 0 || stats["frames_written"] != frames)
      throw std::runtime_error("soc_sim " + backend + " " + scene + ": wrote " + stats["frames_written"].dump() +
                               " of " + std::to_string(frames) + " frames");
    const json& s = stats["stats"];
    RunFigures figures;
    figures.simulated_ns = s["simulated_ns"].get<double>();
    if (s.contains("raster")) {
      const json& raster = s["raster"];
      figures.raster_busy_ns = raster["busy_ns"].get<double>();
      figures.fragments = raster["fragments"].get<double>();
      figures.fragments_written = raster["fragments_written"].get<double>();
      figures.triangles = raster["triangles"].get<double>();
    }
    (r == 0 ? runs.n : runs.two_n) = figures;
    if (r > 0) runs.wall_per_frame = std::min(runs.wall_per_frame, per_frame_seconds(stats, m_opt.frames, "wall_ns"));
    fs::remove_all(out);
  }
  return runs;
}

void Bench::print_fragment_table() const {
  const unsigned n = m_opt.frames;
  std::printf("### 1. SystemC rasterizer: fragments per wall-clock second (soc_sim --backend raster)\n\n");
  std::printf(
      "| scene | fragments / frame | written / frame | triangles / frame | soc_sim wall / frame "
      "| fragments / wall s | simulated : wall | core natively: fragments / s | core / soc_sim "
      "| core CPU ns / fragment (min) | (median) |\n");
  std::printf("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
  for (const auto& scene : m_opt.wall_scenes) {
    const SceneRuns& r = m_raster.at(scene);
    const double wall = r.wall_per_frame_s(n);
    const double fragments = r.per_frame(&RunFigures::fragments, n);
    // With few frames on a busy machine the difference can drown in noise.
    const bool valid = wall > 0;
    const CoreResult& core = m_core.at(scene);
    const double core_rate = static_cast<double>(core.fragments) / core.seconds;
    const MinMedian ns = min_median(m_core_ns.at(scene));
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %.1f | %.1f |\n", scene.c_str(),
                format_count(fragments).c_str(), format_count(r.per_frame(&RunFigures::fragments_written, n)).c_str(),
                format_count(r.per_frame(&RunFigures::triangles, n)).c_str(), valid ? format_ms(wall).c_str() : "noise",
                valid ? format_count(fragments / wall).c_str() : "-",
                valid ? format_ratio(r.per_frame(&RunFigures::simulated_ns, n) * 1e-9 / wall).c_str() : "-",
                format_count(core_rate).c_str(), valid ? format_ratio(core_rate / (fragments / wall)).c_str() : "-",
                ns.min, ns.median);
    if (static_cast<double>(core.fragments) != fragments * n)
      std::printf("\n(%s: the native core generated %llu fragments in frames %u..%u, soc_sim %.0f)\n", scene.c_str(),
                  static_cast<unsigned long long>(core.fragments), n, 2 * n - 1, fragments * n);
  }
  std::printf(
      "\nWall time is the whole soc_sim process (host CPU model, bus, memory, display, PNG writing of "
      "every frame, and the rasterizer), not the rasterizer alone. \"fragments\" are those the "
      "rasterizer generated (stats raster.fragments), \"written\" those that passed the tests. "
      "\"core natively\": TileRasterizer::run alone, timed over the same frames with the same driver "
      "on a native host (no SystemC), best of %u processes in wall time; its ns / fragment is that "
      "process's thread CPU time in the core (what a loaded machine inflates least) over its fragments, "
      "min and median over the processes.\n\n",
      m_opt.repeat);
}

void Bench::print_frame_time_table() const {
  const unsigned n = m_opt.frames;
  std::printf("### 3. Simulated time per frame: raster beside arm\n\n");
  std::printf(
      "| scene | raster: simulated / frame | arm: simulated / frame | arm / raster "
      "| rasterizer busy / frame | rasterizer busy share |\n");
  std::printf("|---|--:|--:|--:|--:|--:|\n");
  for (const auto& scene : m_opt.scenes) {
    const SceneRuns& raster = m_raster.at(scene);
    const SceneRuns& arm = m_arm.at(scene);
    const double raster_frame = raster.per_frame(&RunFigures::simulated_ns, n) * 1e-9;
    const double arm_frame = arm.per_frame(&RunFigures::simulated_ns, n) * 1e-9;
    const double busy = raster.per_frame(&RunFigures::raster_busy_ns, n) * 1e-9;
    char share[16];
    std::snprintf(share, sizeof share, "%.0f %%", 100.0 * busy / raster_frame);
    std::printf("| %s | %s | %s | %s | %s | %s |\n", scene.c_str(), format_ms(raster_frame).c_str(),
                format_ms(arm_frame).c_str(), format_ratio(arm_frame / raster_frame).c_str(), format_ms(busy).c_str(),
                share);
  }
  std::printf(
      "\narm / raster above 1: the rasterizer draws the frame in less simulated time than the arm "
      "renderer. \"rasterizer busy\" is raster.busy_ns per frame (the time the rasterizer ran command "
      "lists, its bus waits included); the rest of the frame the host (geometry, binning) and the "
      "display transfer set the pace.\n\n");
}

void Bench::run() {
  const WorkFolder folder(m_opt.work_dir, "bench_raster");
  m_work = folder.path();

  std::vector<std::string> print_config = {m_opt.soc_sim};
  for (const auto& file : m_opt.config_files) print_config.insert(print_config.end(), {"--config", file});
  print_config.push_back("--print-config");
  m_config = json::parse(run_child(print_config, m_work / "config.json").output);
  const json& config = m_config;

  const std::string load_before = load_average();
  const auto start = std::chrono::steady_clock::now();

  // Wall-timed scenes first, R times each; the others once (simulated time is
  // deterministic), on both back ends.
  for (const auto& scene : m_opt.wall_scenes) m_raster[scene] = measure("raster", scene, m_opt.repeat);
  for (const auto& scene : m_opt.scenes) {
    if (!m_raster.count(scene)) m_raster[scene] = measure("raster", scene, 1);
    m_arm[scene] = measure("arm", scene, 1);
  }
  for (const auto& scene : m_opt.wall_scenes) {
    std::fprintf(stderr, "bench_raster: %s, functional core natively ...\n", scene.c_str());
    CoreResult best;
    best.seconds = std::numeric_limits<double>::max();
    const std::vector<std::string> args =
        scene == "obj_viewer" ? std::vector<std::string>{m_opt.obj_file} : std::vector<std::string>{};
    // A child each time: the GL driver's EGL state lives as long as the process.
    std::vector<std::string> command = {m_opt.self, "--native-core", scene, "--frames", std::to_string(m_opt.frames)};
    for (const auto& file : m_opt.config_files) command.insert(command.end(), {"--config", file});
    if (!args.empty()) command.insert(command.end(), {"--obj", args.front()});
    for (unsigned r = 0; r < m_opt.repeat; ++r) {
      const json out = json::parse(run_child(command, m_work / "core.stdout").output);
      const CoreResult core{out["seconds"].get<double>(), out["cpu_seconds"].get<double>(),
                            out["fragments"].get<uint64_t>(), out["runs"].get<uint64_t>()};
      if (core.seconds < best.seconds) best = core;
      m_core_ns[scene].push_back(core.cpu_seconds * 1e9 / static_cast<double>(std::max<uint64_t>(core.fragments, 1)));
    }
    m_core[scene] = best;
  }
  std::fprintf(stderr, "bench_raster: datapath C++ against RTL ...\n");
  const ChildResult rtl =
      run_child({m_opt.bench_rtl, "--vectors", std::to_string(m_opt.vectors)}, m_work / "bench_rtl.stdout");
  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const json& display = config["display"];
  const json& raster = config["raster"];
  if (!m_opt.wall_scenes.empty()) print_fragment_table();
  std::printf("### 2. Datapath units: C++ model against Verilated RTL (bench_rtl)\n\n%s\n", rtl.output.c_str());
  if (!m_opt.scenes.empty()) print_frame_time_table();
  std::printf(
      "Display %ux%u %s, %s mode; rasterizer %u MHz, tiles %ux%u, reciprocal method %u. Per-frame values are "
      "frames %u..%u: counts and simulated times are the run of 2N frames minus that of N=%u (deterministic, so "
      "exact); wall times are timed within each run of 2N frames (soc_sim --wall-clock), the best of %u run(s) "
      "(tables 1 and 2).\n",
      display["width"].get<unsigned>(), display["height"].get<unsigned>(), display["format"].get<std::string>().c_str(),
      display["dma"].get<bool>() ? "DMA" : "port", static_cast<unsigned>(raster["clock_mhz"].get<double>()),
      raster["tile_width"].get<unsigned>(), raster["tile_height"].get<unsigned>(),
      raster["recip_method"].get<unsigned>(), m_opt.frames, 2 * m_opt.frames - 1, m_opt.frames, m_opt.repeat);
  std::printf("%s\n", machine_summary(load_before, total_s).c_str());
}

}  // namespace

static int run_main(int argc, char** argv) {
  Options opt;
  CLI::App cli{"bench_raster: benchmark of the rasterizer (soc_sim raster and arm back ends, datapath C++ vs RTL)"};
  cli.add_option("--frames", opt.frames, "N: runs of N and 2N frames, frames N..2N-1 measured")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cli.add_option("--repeat", opt.repeat, "runs of each wall-time measurement; the best is kept")
      ->check(CLI::Range(1, 20))
      ->capture_default_str();
  cli.add_option("--wall-scene", opt.wall_scenes, "scene(s) for the fragments-per-second table")
      ->check(CLI::IsMember(all_scene_names()))
      ->capture_default_str();
  cli.add_option("--scene", opt.scenes, "scene(s) for the raster-beside-arm table")
      ->check(CLI::IsMember(all_scene_names()))
      ->capture_default_str();
  cli.add_option("--vectors", opt.vectors, "operations per side and round of each datapath unit (bench_rtl)")
      ->check(CLI::Range(uint64_t{1000}, uint64_t{100'000'000}))
      ->capture_default_str();
  cli.add_option("--config", opt.config_files, "soc_sim configuration file(s)")->check(CLI::ExistingFile);
  cli.add_option("--obj", opt.obj_file, "OBJ file for obj_viewer")->check(CLI::ExistingFile)->capture_default_str();
  cli.add_option("--work-dir", opt.work_dir, "folder for soc_sim's output (default: a temporary one, removed)");
  cli.add_option("--soc-sim", opt.soc_sim, "soc_sim to run (default: the one in this build tree)");
  cli.add_option("--native-core", opt.native_core, "(used by bench_raster itself) time the core natively on SCENE")
      ->check(CLI::IsMember(all_scene_names()))
      ->group("");
  CLI11_PARSE(cli, argc, argv);

  const fs::path here = own_directory();
  opt.self = (here / "bench_raster").string();
  if (opt.soc_sim.empty()) opt.soc_sim = (here / "soc_sim").string();
  opt.bench_rtl = (here / "bench_rtl").string();
  for (const auto& program : {opt.soc_sim, opt.bench_rtl})
    if (!fs::exists(program)) {
      std::cerr << "bench_raster: " << program << " not found (build the bench_raster target)\n";
      return 2;
    }
  try {
    if (!opt.native_core.empty()) {
      std::vector<std::string> print_config = {opt.soc_sim};
      for (const auto& file : opt.config_files) print_config.insert(print_config.end(), {"--config", file});
      print_config.push_back("--print-config");
      const WorkFolder folder(opt.work_dir, "bench_raster");
      const json config = json::parse(run_child(print_config, folder.path() / "config.json").output);
      const std::vector<std::string> args =
          opt.native_core == "obj_viewer" ? std::vector<std::string>{opt.obj_file} : std::vector<std::string>{};
      const CoreResult core = run_core_natively(opt.native_core, opt.frames, config, args);
      std::printf("%s\n", json{{"seconds", core.seconds},
                               {"cpu_seconds", core.cpu_seconds},
                               {"fragments", core.fragments},
                               {"runs", core.runs}}
                              .dump()
                              .c_str());
      return 0;
    }
    Bench(opt).run();
  } catch (const std::exception& e) {
    std::cerr << "bench_raster: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_raster", [&] { return run_main(argc, argv); });
}
