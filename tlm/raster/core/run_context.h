// What every stage of one run of the tile table shares: the port to system
// memory, the configuration and cycle costs, the counters of RunResult and
// the run's first error. A read or write that the port refuses becomes the
// run's error (later stages see failed() and stop); every access adds its
// bytes to the counters. Cycles are charged to one of RunResult's buckets
// and reported to the port together, after every command and at the end of
// every tile (README.md, "Counters and cycle costs").
#pragma once

#include <cstdint>

#include "raster/core/raster_port.h"
#include "raster/core/tile_rasterizer.h"

namespace tessera::raster {

class RunContext {
 public:
  RunContext(RasterPort& port, const CycleCosts& costs, const RunConfig& config)
      : m_port(port), m_costs(costs), m_config(config) {}

  const RunConfig& config() const { return m_config; }
  const CycleCosts& costs() const { return m_costs; }
  RunResult& result() { return m_result; }

  bool failed() const { return m_result.error != RasterError::none; }
  // Records `error` at `address` unless the run has already failed.
  void fail(RasterError error, uint32_t address);

  // false when the port refuses the access; the run then fails with `error`.
  bool read(uint32_t address, void* data, unsigned bytes, RasterError error = RasterError::bus_error);
  bool write(uint32_t address, const void* data, unsigned bytes);

  // Adds `cycles` to a bucket of result() and to the cycles not yet reported.
  void charge(uint64_t& bucket, uint64_t cycles) {
    bucket += cycles;
    m_pending_cycles += cycles;
  }
  void report_cycles();

 private:
  RasterPort& m_port;
  const CycleCosts& m_costs;
  const RunConfig& m_config;
  RunResult m_result;
  uint64_t m_pending_cycles = 0;
};

}  // namespace tessera::raster
