// A payload extension through which a target says that serving the access
// scheduled nothing in the kernel: no event notified, no process made
// runnable (the CIU's CMEM window: bytes moved, counters and time added),
// a traced signal's edge excepted (timed_trace.h: the host counts those
// apart, timed_signal_edges).
// The host, which runs ahead of the kernel's time while nothing is
// scheduled (docs/architecture.md, "Run-ahead"), attaches it to its payload
// and clears it before each access; set after one, the kernel's schedule is
// as it was, so the host keeps the answer it had instead of asking the
// kernel again (memory says the same by allowing DMI). A target that sets
// it wrongly would let the host run past a process it woke: set it only on
// a path that notifies nothing.
#pragma once

#include <tlm>

#include "common/value_extension.h"

namespace tessera {

struct ScheduleUntouched : ValueExtension<ScheduleUntouched> {
  bool untouched = false;
};

// For a target: this access scheduled nothing (no-op without the extension).
inline void mark_schedule_untouched(tlm::tlm_generic_payload& gp) {
  if (ScheduleUntouched* extension = gp.get_extension<ScheduleUntouched>()) extension->untouched = true;
}

}  // namespace tessera
