// The CIU's parameters: ciu.*. Both latencies are calibrated
// (docs/calibration.md, "The CIU"): fitted on the ISS (host.model=iss)
// running the driver's WriteMem32 / ReadMem32 loop of calib_ciu, they give,
// with the bus's address phase and the ARM's own code around each access,
// the board's 488 ns per write and 830 ns per read.
#include "array/ciu.h"

namespace tessera {

ParamGroup CiuParams::parameters() {
  using param::integer;
  return {"ciu",
          {
              integer("ciu.write_cycles", 46, 0, 10000, "array cycles",
                      "latency of one 32-bit CMEM write through the CIU (calibrated: docs/calibration.md)"),
              integer("ciu.read_cycles", 64, 0, 10000, "array cycles",
                      "latency of one 32-bit CMEM read through the CIU (calibrated: docs/calibration.md)"),
          },
          {}};
}

CiuParams CiuParams::from_config(const Config& config) {
  CiuParams p;
  p.write_cycles = static_cast<unsigned>(config.get_uint("ciu.write_cycles"));
  p.read_cycles = static_cast<unsigned>(config.get_uint("ciu.read_cycles"));
  return p;
}

CiuParams CiuParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
