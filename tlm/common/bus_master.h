// A block's bus-master port: an initiator socket that moves a block of data
// as bursts of at most `max_burst_bytes`, one after another, at the
// initiator's local time. The first burst is issued at the local time it is
// given and each next one at the completion of the one before (the master
// waits for its data, writes included), so arbitration can put another
// initiator's transfer between two bursts. It counts into its owner's
// activity counters (bus.transactions, bus.bytes_read, bus.bytes_written,
// bus.errors), adds up the time its bursts took, waits for the bus
// included, and reports each failed burst as a warning under its owner's
// name.
#pragma once

#include <cstdint>

#include <systemc>
#include <tlm>

#include <tlm_utils/tlm_quantumkeeper.h>

#include "common/activity_counters.h"

namespace tessera {

class BusMaster : public tlm::tlm_initiator_socket<32>, private tlm::tlm_bw_transport_if<> {
 public:
  enum class OnError {
    stop,               // the transfer ends at the failed burst (a pipeline cannot go on without its data)
    zeros_and_continue  // a failed read burst reads as zeros and the rest is still moved (a scan-out fills its line)
  };

  BusMaster(const char* name, ActivityCounters& counters);

  void configure(unsigned max_burst_bytes, OnError on_error);

  // Moves `bytes` at `address` (read into or written from `data`). `local`
  // is the initiator's local time, an offset from the kernel's time; on
  // return it is the completion of the last burst. With a quantum keeper,
  // the keeper takes the local time after each burst and synchronises when
  // its quantum is used up, so the next burst goes out at the local time
  // the keeper then gives. False if a burst failed.
  bool transfer(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned bytes, sc_core::sc_time& local,
                tlm_utils::tlm_quantumkeeper* keeper = nullptr);

  // Issue to completion of every burst, summed: waits for the bus included.
  const sc_core::sc_time& bus_time() const { return m_bus_time; }

 private:
  // The master uses b_transport only; the bus calls back for DMI, which it
  // does not use.
  tlm::tlm_sync_enum nb_transport_bw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& phase,
                                     sc_core::sc_time& delay) override;
  void invalidate_direct_mem_ptr(sc_dt::uint64 start, sc_dt::uint64 end) override;
  // The name warnings are reported under: the owning block's.
  const char* owner_name() const;

  unsigned m_max_burst_bytes = 0;
  OnError m_on_error = OnError::stop;
  tlm::tlm_generic_payload m_payload;
  sc_core::sc_time m_bus_time;
  ActivityCounter& m_transactions;
  ActivityCounter& m_bytes_read;
  ActivityCounter& m_bytes_written;
  ActivityCounter& m_errors;
};

}  // namespace tessera
