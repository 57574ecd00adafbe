// From crt0.S to the application: the standard streams, C++'s static
// constructors, the boot information, the AppEnvironment a host-compiled
// application would get from soc_sim, the application, then the driver's
// counters and the exit. ARM only.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "renderers/backends.h"
#include "runtime/runtime.h"
#include "runtime/semihosting_call.h"

extern "C" void __libc_init_array();  // NOLINT(bugprone-reserved-identifier): newlib's

namespace tessera::runtime {

namespace {

// A semihosting file opened for writing, or for reading whole.
class HostFile {
 public:
  HostFile(const char* name, const char* mode) : m_file(std::fopen(name, mode)) {}
  ~HostFile() {
    if (m_file != nullptr) std::fclose(m_file);
  }
  HostFile(const HostFile&) = delete;
  HostFile& operator=(const HostFile&) = delete;
  bool is_open() const { return m_file != nullptr; }
  void write(const std::string& text) {
    if (m_file == nullptr) return;
    std::fwrite(text.data(), 1, text.size(), m_file);
    std::fflush(m_file);
  }
  std::string read_all() {
    std::string text;
    char buffer[4096];
    for (size_t n; m_file != nullptr && (n = std::fread(buffer, 1, sizeof buffer, m_file)) > 0;) text.append(buffer, n);
    return text;
  }

 private:
  std::FILE* m_file;
};

int run() {
  HostFile boot_file(boot_info::BOOT_FILE, "rb");
  if (!boot_file.is_open()) {
    std::fprintf(stderr,
                 "runtime: no boot information (%s): run the program with soc_sim --app program.elf, whose ISS "
                 "launcher provides it\n",
                 boot_info::BOOT_FILE);
    return 1;
  }
  const boot_info::BootInfo boot = boot_info::decode(boot_file.read_all());
  if (boot.program_heap_end > boot.program_heap_base) set_second_heap(boot.program_heap_base, boot.program_heap_end);
  const Config config({ParamGroup{"soc_sim", boot.config, {}}});

  static HostApi host;
  AppEnvironment env;
  env.host = &host;
  env.frames = boot.frames;
  env.frame_buffers[0] = boot.frame_buffers[0];
  env.frame_buffers[1] = boot.frame_buffers[1];
  env.memory_bytes = boot.memory_bytes;
  env.heap_base = boot.heap_base;
  env.heap_end = boot.heap_end;
  env.args = boot.args;
  env.config = &config;
  ActivityCounters counters;
  env.counters = &counters;
  HostFile warnings(boot_info::WARNINGS_FILE, "w");
  env.warn = [&warnings](const std::string& source, const std::string& message) {
    warnings.write(source + "\t" + message + "\n");
  };
  HostFile figures(boot_info::FRAME_FIGURES_FILE, "w");
  env.frame_statistics = [&figures](const std::vector<std::pair<std::string, double>>& values) {
    figures.write(boot_info::encode_figures(values));
  };
  if (!boot.backend.empty()) backends::hand_over(backends::backend(boot.backend), env);

  const int status = tessera_runtime_run(env, boot);

  HostFile counter_file(boot_info::COUNTERS_FILE, "w");
  for (const ActivityCounter& c : counters.all())
    counter_file.write(c.name + "\t" + std::to_string(c.value) + "\t" + c.description + "\n");
  return status;
}

}  // namespace

}  // namespace tessera::runtime

extern "C" [[noreturn]] void tessera_runtime_start() {
  tessera::runtime::open_standard_streams();
  __libc_init_array();
  int status = 1;
  try {
    status = tessera::runtime::run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
  }
  std::exit(status);
}

// The exceptions crt0.S has no use for: r0 is the vector's offset.
extern "C" [[noreturn]] void tessera_runtime_exception(uint32_t vector) {
  static const char* const names[] = {
      "reset", "undefined instruction", "SWI", "prefetch abort", "data abort", "reserved", "IRQ", "FIQ"};
  std::fprintf(stderr, "runtime: unexpected %s exception\n", names[(vector / 4) & 7]);
  std::_Exit(3);
}
