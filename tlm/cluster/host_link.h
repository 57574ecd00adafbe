// A cluster node's host link (contract/cluster/host_link_regs.def): the
// node software's way to tell the platform that a frame is complete, as the
// iPSC's nodes reported to the host computer. A write of FRAME_DONE calls
// the platform's handler at once, in the writing host's thread, before the
// write returns: the node program writes it before it lets any node go on
// to the next frame (tlm/cluster/README.md, "Frames").
#pragma once

#include <functional>

#include "common/peripheral.h"

namespace tessera {

class HostLink : public Peripheral {
 public:
#define TESSERA_REGISTER_TABLE "cluster/host_link_regs.def"
#include "common/register_members.inc"

  HostLink(sc_core::sc_module_name name, const sc_core::sc_time& clock_period);

  // Called with the frame number and the access's time.
  void on_frame_done(std::function<void(unsigned frame, const sc_core::sc_time& when)> handler) {
    m_on_frame_done = std::move(handler);
  }

  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;

 private:
  void write_FRAME_DONE(uint32_t value);

  std::function<void(unsigned, const sc_core::sc_time&)> m_on_frame_done;
  ActivityCounter& m_frames_done;
};

}  // namespace tessera
