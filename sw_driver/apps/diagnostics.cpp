// Diagnostic applications: each exercises one failure path of the SoC on
// purpose, so that the path can be seen (and tested) from soc_sim.
//
// unmapped_access: the host reads an address that no region of the memory map
// covers. The bus answers with an address error and logs it naming the
// initiator; the host raises BusError into the software, and soc_sim reports
// the failed application and exits with status 1.
//
// stuck_loop: after one frame, computes forever in its own code without
// calling the host model, so simulated time stands still and the SystemC
// kernel never runs again; soc_sim's watch (sim.stall_limit_s) ends the run,
// naming the frame and what the host was running.
//
// crash: after one frame, writes through a null pointer, as a buggy
// application would; soc_sim reports the crash with the frame reached.
#include <cinttypes>
#include <cstdint>
#include <cstdio>

#include "apps/apps.h"
#include "device/display_driver.h"
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
  std::fprintf(stderr, "unmapped_access: read of 0x%08" PRIx32 " returned 0x%08" PRIx32 " instead of a bus error\n",
               UNMAPPED_ADDRESS, value);
  return 1;
}

namespace {

// The one frame both diagnostics show first, so that their failure comes
// after a frame: the back buffer as it is (memory starts cleared).
void show_one_frame(AppEnvironment& env) {
  DisplayDriver display(env);
  display.present();
}

}  // namespace

// Exported (not static), so that the call stack soc_sim reports names it.
int stuck_loop_app(AppEnvironment& env) {
  show_one_frame(env);
  // A loop with an effect the compiler must keep (a loop without one may be
  // assumed to end), and none the simulation sees.
  volatile uint64_t turns = 0;
  for (;;) turns = turns + 1;
}

int crash_app(AppEnvironment& env) {
  show_one_frame(env);
  // Both volatile: a pointer the compiler cannot see is null (so the write
  // is not folded into a trap instruction), and a write it must not drop.
  volatile uint32_t* volatile pointer = nullptr;
  *pointer = 1;
  return 1;
}

}  // namespace tessera
