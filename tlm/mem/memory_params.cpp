// System memory's parameters: mem.*.
#include "mem/memory.h"

namespace tessera {

ParamGroup MemoryParams::parameters() {
  return {"mem",
          {
              param::integer("mem.size_mib", 16, 1, 256, "MiB", "system memory size"),
              param::integer("mem.first_access_cycles", 3, 0, 64, "bus cycles",
                             "wait states before the first beat of an access (calibrated, see docs/calibration.md)"),
              param::integer("mem.beat_cycles", 1, 1, 16, "bus cycles", "cycles per data beat of a burst"),
          },
          {}};
}

MemoryParams MemoryParams::from_config(const Config& config) {
  MemoryParams p;
  p.size_bytes = config.get_uint("mem.size_mib") << 20;
  p.first_access_cycles = static_cast<unsigned>(config.get_uint("mem.first_access_cycles"));
  p.beat_cycles = static_cast<unsigned>(config.get_uint("mem.beat_cycles"));
  return p;
}

MemoryParams MemoryParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
