// How the sort-middle node program reaches its stripe and charges its
// work on the host-compiled model (README.md, "On the host-compiled
// model"): the stripe's memory through the host's spans, and the meter that
// turns the core's work counters into the cost table's rows.
#pragma once

#include <cstdint>

#include "cluster/rasterize.h"
#include "cluster/records.h"
#include "host/host_api.h"

namespace tessera {

// The stripe's buffers in the node's memory, through the host's spans
// (charged per cache line natively; plain memory on the ISS).
class HostStripeMemory : public cluster::StripeMemory {
 public:
  explicit HostStripeMemory(HostApi* host = nullptr) : m_host(host) {}
  const uint8_t* load(uint32_t address, unsigned size, unsigned count) override {
    return m_host->load_span(address, size, count);
  }
  uint8_t* store(uint32_t address, unsigned size, unsigned count) override {
    return m_host->store_span(address, size, count);
  }

 private:
  HostApi* m_host;
};

// Charges the work the core counted since the last call to the host-cost
// table's sort_middle_* rows (sw_driver/costs); nothing on the ISS, where
// the instructions take the time.
class CostMeter {
 public:
  void charge(HostApi& host, const cluster::WorkCounters& counters);

 private:
  cluster::WorkCounters m_charged;
};

}  // namespace tessera
