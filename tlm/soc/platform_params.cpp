#include "soc/platform_params.h"

namespace tessera {

MemoryParams platform_memory_params(const Config& config, uint64_t size_bytes) {
  MemoryParams p = MemoryParams::from_config(config);
  const BusParams bus = BusParams::from_config(config);
  p.size_bytes = size_bytes;
  p.clock_period = bus.clock_period;
  p.width_bytes = bus.width_bytes;
  return p;
}

HostParams platform_host_params(const Config& config, uint32_t cacheable_base, uint64_t size_bytes) {
  HostParams p = HostParams::from_config(config);
  p.cacheable_base = cacheable_base;
  p.cacheable_size = static_cast<uint32_t>(size_bytes);
  // A quantum of zero asks for synchronisation on every access: no run-ahead.
  if (config.get_uint("sim.quantum_ns") != 0)
    p.run_ahead = sc_core::sc_time(static_cast<double>(config.get_uint("sim.run_ahead_us")), sc_core::SC_US);
  return p;
}

}  // namespace tessera
