// The SDK's region of interest (include/tessera/roi.h): a write of the
// simulation control register, through the host the application runs on
// (a volatile store on the ISS).
#include <tessera/roi.h>

#include "gl/runtime.h"
#include "soc/memory_map.h"
#include "soc/sim_control_regs.h"

namespace {

void write_roi(uint32_t value) {
  tessera::gl::environment().host->write32(tessera::memory_map::sim_control.base + tessera::sim_control_regs::ROI,
                                           value);
}

}  // namespace

extern "C" void tessera_roi_begin(void) {
  write_roi(1);
}

extern "C" void tessera_roi_end(void) {
  write_roi(0);
}
