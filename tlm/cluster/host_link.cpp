#include "cluster/host_link.h"

namespace tessera {

HostLink::HostLink(sc_core::sc_module_name name, const sc_core::sc_time& clock_period)
    : Peripheral(name, clock_period), m_frames_done(counter("frames_done", "frames reported complete")) {
  FRAME_DONE.on_write(this, &HostLink::write_FRAME_DONE);
}

void HostLink::write_FRAME_DONE(uint32_t value) {
  ++m_frames_done;
  FRAMES_DONE.set(static_cast<uint32_t>(m_frames_done.value));
  if (m_on_frame_done) m_on_frame_done(value, access_time());
}

SummaryRow HostLink::summary_row(const sc_core::sc_time& /*elapsed*/) const {
  return {std::nullopt, std::nullopt, std::to_string(m_frames_done.value) + " frames reported"};
}

}  // namespace tessera
