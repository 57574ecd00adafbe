// The bus's parameters: bus.*.
#include <string>

#include "bus/ahb_bus.h"

namespace tessera {

ParamGroup BusParams::parameters() {
  return {"bus",
          {
              param::real("bus.clock_mhz", 96.0, 1, 2000, "MHz", "AHB-style bus clock"),
              param::integer("bus.width_bits", 32, 32, 128, "bits", "data width: one beat per width (32, 64 or 128)"),
              param::choice("bus.arbitration", "fixed_priority", {"fixed_priority", "round_robin"},
                            "arbitration among requests made at the same bus cycle"),
              param::integer("bus.address_cycles", 1, 0, 16, "bus cycles", "address phase of a transfer"),
              param::integer("bus.error_cycles", 2, 1, 16, "bus cycles", "length of an error response"),
          },
          [](const Config& config) {
            const int64_t width = config.get_int("bus.width_bits");
            if (width != 32 && width != 64 && width != 128)
              throw ConfigError("configuration: 'bus.width_bits' expects 32, 64 or 128, got " + std::to_string(width));
          }};
}

BusParams BusParams::from_config(const Config& config) {
  BusParams p;
  p.clock_period = sc_core::sc_time(1e3 / config.get_real("bus.clock_mhz"), sc_core::SC_NS);
  p.arbitration = parse_arbitration(config.get_string("bus.arbitration"));
  p.width_bytes = static_cast<unsigned>(config.get_uint("bus.width_bits") / 8);
  p.address_cycles = static_cast<unsigned>(config.get_uint("bus.address_cycles"));
  p.error_cycles = static_cast<unsigned>(config.get_uint("bus.error_cycles"));
  return p;
}

BusParams BusParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
