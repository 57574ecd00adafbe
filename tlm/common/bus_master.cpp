#include "common/bus_master.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "common/log.h"

namespace tessera {

BusMaster::BusMaster(const char* name, ActivityCounters& counters)
    : tlm::tlm_initiator_socket<32>(name),
      m_transactions(counters.counter("bus.transactions", "bursts issued on the bus")),
      m_bytes_read(counters.counter("bus.bytes_read", "bytes read over the bus")),
      m_bytes_written(counters.counter("bus.bytes_written", "bytes written over the bus")),
      m_errors(counters.counter("bus.errors", "bursts that got an error response")) {
  m_export.bind(*this);
}

void BusMaster::configure(unsigned max_burst_bytes, OnError on_error) {
  if (max_burst_bytes == 0) throw std::invalid_argument(std::string(name()) + ": bursts of 0 bytes");
  m_max_burst_bytes = max_burst_bytes;
  m_on_error = on_error;
}

const char* BusMaster::owner_name() const {
  const sc_core::sc_object* owner = get_parent_object();
  return owner ? owner->name() : name();
}

bool BusMaster::transfer(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned bytes,
                         sc_core::sc_time& local, tlm_utils::tlm_quantumkeeper* keeper) {
  if (m_max_burst_bytes == 0) throw std::logic_error(std::string(name()) + ": transfer before configure");
  bool ok = true;
  for (unsigned offset = 0; offset < bytes;) {
    const unsigned length = std::min(m_max_burst_bytes, bytes - offset);
    m_payload.set_command(command);
    m_payload.set_address(address + offset);
    m_payload.set_data_ptr(data + offset);
    m_payload.set_data_length(length);
    m_payload.set_streaming_width(length);
    m_payload.set_byte_enable_ptr(nullptr);
    m_payload.set_byte_enable_length(0);
    m_payload.set_dmi_allowed(false);
    m_payload.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    const sc_core::sc_time issued = local;
    (*this)->b_transport(m_payload, local);
    m_bus_time += local - issued;
    if (keeper) keeper->set(local);
    ++m_transactions;
    if (m_payload.is_response_error()) {
      ++m_errors;
      ok = false;
      log::warning(owner_name(), std::string(command == tlm::TLM_READ_COMMAND ? "read" : "write") + " of " +
                                     std::to_string(length) + " bytes at " + log::hex(address + offset) + " failed (" +
                                     log::response_text(m_payload.get_response_status()) + ")");
      if (m_on_error == OnError::stop) return false;
      if (command == tlm::TLM_READ_COMMAND) std::memset(data + offset, 0, length);
    } else {
      (command == tlm::TLM_READ_COMMAND ? m_bytes_read : m_bytes_written) += length;
    }
    if (keeper && keeper->need_sync()) {
      keeper->sync();
      local = keeper->get_local_time();
    }
    offset += length;
  }
  return ok;
}

tlm::tlm_sync_enum BusMaster::nb_transport_bw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& phase,
                                              sc_core::sc_time& delay) {
  (void)phase;
  (void)delay;
  gp.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
  return tlm::TLM_COMPLETED;
}

void BusMaster::invalidate_direct_mem_ptr(sc_dt::uint64 start, sc_dt::uint64 end) {
  (void)start;
  (void)end;
}

}  // namespace tessera
