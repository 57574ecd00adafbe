// Diagnostic applications: each exercises one failure path of the SoC on
// purpose, so that the path can be seen (and tested) from soc_sim.
//
// unmapped_access: the host reads an address that no region of the memory map
// covers. The bus answers with an address error and logs it naming the
// initiator; the host raises BusError into the software, and soc_sim reports
// the failed application and exits with status 1.
#include <cstdio>

#include "apps/apps.h"
#include "soc/memory_map.h"

namespace tessera {

namespace {

constexpr uint32_t UNMAPPED_ADDRESS = 0x80000000u;

constexpr bool mapped(uint32_t address) {
  for (const auto& region : memory_map::ALL_REGIONS)
    if (region.contains(address)) return true;
  return false;
}
static_assert(!mapped(UNMAPPED_ADDRESS), "the diagnostic's address must stay outside memory_map.def");

}  // namespace

int unmapped_access_app(AppEnvironment& env) {
  const uint32_t value = env.host->read32(UNMAPPED_ADDRESS);
  // Reached only if the bus failed to report the error.
  std::fprintf(stderr, "unmapped_access: read of 0x%08x returned 0x%08x instead of a bus error\n", UNMAPPED_ADDRESS,
               value);
  return 1;
}

}  // namespace tessera
