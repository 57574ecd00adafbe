// The host's parameters: host.* (the ARM922T's clock, its cost model per
// operation class, the data cache and the write buffer).
#include <string>

#include "host/host.h"
#include "soc/irq_map.h"

namespace tessera {

namespace {

// Operation classes of the cost model and their keys under host.cycles.
struct OpKey {
  Op op;
  const char* key;
};
constexpr OpKey OP_KEYS[] = {
    {Op::alu, "alu"},     {Op::load_use, "load_use"}, {Op::mul, "mul"},     {Op::branch, "branch"},
    {Op::call, "call"},   {Op::fadd, "fadd"},         {Op::fmul, "fmul"},   {Op::fdiv, "fdiv"},
    {Op::fsqrt, "fsqrt"}, {Op::fcmp, "fcmp"},         {Op::fconv, "fconv"},
};

}  // namespace

ParamGroup HostParams::parameters() {
  using param::integer;
  using param::real;
  return {
      "host",
      {
          param::choice("host.model", "native", {"native", "iss"},
                        "how software runs on the host: native (host-compiled, timed by the cost model below) or iss "
                        "(the driver and application cross-compiled for the ARM922T and run on the instruction-set "
                        "simulator with its timing; tlm/host/README.md)"),
          integer("host.iss_instruction_limit", 0, 0, 1e18, "instructions",
                  "host.model=iss: instructions after which a program still running is stopped with an error "
                  "naming the file and the PC (a runaway program); 0: no limit but sim.time_limit_ms"),
          integer("host.iss_heap_mib", 4, 0, 240, "MiB",
                  "host.model=iss: system memory given to the program's C heap (malloc, new) once the part below its "
                  "stacks is used up, taken from the start of the driver's heap (sw_driver/runtime/README.md)"),
          real("host.clock_mhz", 192.0, 1, 2000, "MHz", "ARM922T core clock"),
          integer("host.irq_lines", 8, irq_map::MIN_HOST_LINES, irq_map::MAX_HOST_LINES, "lines",
                  "interrupt inputs of the host"),
          integer("host.cycles.alu", 1, 0, 100, "cycles", "data-processing instruction (ARM9TDMI: 1)"),
          integer("host.cycles.load", 1, 0, 100, "cycles", "LDR/LDRH/LDRB issue, cache hit (ARM9TDMI: 1)"),
          integer("host.cycles.load_use", 1, 0, 100, "cycles",
                  "interlock when a loaded value is used by the next instruction (ARM9TDMI: 1)"),
          integer("host.cycles.store", 1, 0, 100, "cycles", "STR/STRH/STRB issue (ARM9TDMI: 1)"),
          integer("host.cycles.mul", 3, 0, 100, "cycles",
                  "MUL with a 16-bit multiplier (ARM9TDMI: 8 bits per cycle, early termination)"),
          integer("host.cycles.branch", 3, 0, 100, "cycles", "taken branch, pipeline refill (ARM9TDMI: 3)"),
          integer("host.cycles.fadd", 52, 0, 10000, "cycles",
                  "soft-float single add/subtract (measured on the ISS: calib_operations, docs/calibration.md)"),
          integer("host.cycles.fmul", 38, 0, 10000, "cycles", "soft-float single multiply (measured on the ISS)"),
          integer("host.cycles.fdiv", 130, 0, 10000, "cycles", "soft-float single divide (measured on the ISS)"),
          integer("host.cycles.fsqrt", 396, 0, 10000, "cycles",
                  "soft-float single square root, newlib's sqrtf (measured on the ISS)"),
          integer("host.cycles.fcmp", 54, 0, 10000, "cycles", "soft-float compare (measured on the ISS)"),
          integer("host.cycles.fconv", 45, 0, 10000, "cycles",
                  "soft-float conversion to or from integer (measured on the ISS)"),
          integer("host.cycles.call", 9, 0, 100, "cycles",
                  "function call and return overhead, its argument included (measured on the ISS)"),
          integer("host.dcache.size_bytes", 8192, 0, 1048576, "bytes", "data cache size (0: no data cache)"),
          integer("host.dcache.line_bytes", 32, 4, 256, "bytes", "data cache line"),
          integer("host.dcache.ways", 64, 1, 1024, "ways", "data cache associativity (ARM922T: 64)"),
          param::choice("host.dcache.replacement", "round_robin", {"round_robin", "random"},
                        "data cache victim choice: round_robin or random (pseudo-random; the ARM922T's reset "
                        "choice); with host.model=iss the program's CP15 RR bit decides instead"),
          param::choice("host.dcache.write_policy", "write_back", {"write_back", "write_through"},
                        "data cache write policy of system memory (the ARM922T takes it from the page tables' C "
                        "and B bits): write_back (store hits stay in the cache) or write_through (every store "
                        "goes through the write buffer, hits also update the line)"),
          integer("host.write_buffer.entries", 16, 1, 256, "entries",
                  "posted-write buffer depth, in 32-bit data words (ARM922T: 16)"),
          integer("host.write_buffer.addresses", 4, 1, 256, "addresses",
                  "posted-write buffer addresses: one per buffered store, burst or cache line (ARM922T: 4)"),
      },
      [](const Config& config) {
        const int64_t line = config.get_int("host.dcache.line_bytes");
        if (line & (line - 1))
          throw ConfigError("configuration: 'host.dcache.line_bytes' expects a power of two, got " +
                            std::to_string(line));
        const int64_t cache = config.get_int("host.dcache.size_bytes");
        const int64_t ways = config.get_int("host.dcache.ways");
        if (cache != 0 && (cache % (line * ways) != 0))
          throw ConfigError("configuration: impossible combination: host.dcache.size_bytes=" + std::to_string(cache) +
                            " is not a multiple of host.dcache.line_bytes x "
                            "host.dcache.ways = " +
                            std::to_string(line * ways));
        if (cache != 0) {
          const int64_t sets = cache / (line * ways);
          if (sets & (sets - 1))
            throw ConfigError("configuration: impossible combination: the data cache has " + std::to_string(sets) +
                              " sets; host.dcache.size_bytes / (line_bytes x ways) must be a power of two");
        }
      }};
}

HostParams HostParams::from_config(const Config& config) {
  HostParams p;
  p.clock_period = sc_core::sc_time(1e3 / config.get_real("host.clock_mhz"), sc_core::SC_NS);
  for (const OpKey& k : OP_KEYS)
    p.op_cycles[static_cast<size_t>(k.op)] =
        static_cast<unsigned>(config.get_uint(std::string("host.cycles.") + k.key));
  p.load_cycles = static_cast<unsigned>(config.get_uint("host.cycles.load"));
  p.store_cycles = static_cast<unsigned>(config.get_uint("host.cycles.store"));
  p.dcache_bytes = static_cast<unsigned>(config.get_uint("host.dcache.size_bytes"));
  p.dcache_line_bytes = static_cast<unsigned>(config.get_uint("host.dcache.line_bytes"));
  p.dcache_ways = static_cast<unsigned>(config.get_uint("host.dcache.ways"));
  p.dcache_round_robin = config.get_string("host.dcache.replacement") == "round_robin";
  p.write_through = config.get_string("host.dcache.write_policy") == "write_through";
  p.write_buffer_words = static_cast<unsigned>(config.get_uint("host.write_buffer.entries"));
  p.write_buffer_addresses = static_cast<unsigned>(config.get_uint("host.write_buffer.addresses"));
  p.irq_lines = static_cast<unsigned>(config.get_uint("host.irq_lines"));
  p.iss = config.get_string("host.model") == "iss";
  return p;
}

HostParams HostParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
