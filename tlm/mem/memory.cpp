#include "mem/memory.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "common/log.h"
#include "common/transfer_train.h"

namespace tessera {

Memory::Memory(sc_core::sc_module_name name, const MemoryParams& params)
    : Block(name),
      in("in"),
      m_params(params),
      m_data(params.size_bytes, 0),
      m_beats(std::max(1u, params.width_bytes)),  // checked below, with the memory's name in the message
      m_first_access_ticks(params.clock_period.value() * params.first_access_cycles),
      m_beat_ticks(params.clock_period.value() * params.beat_cycles),
      m_reads(counter("reads", "read transfers")),
      m_writes(counter("writes", "write transfers")),
      m_bytes_read(counter("bytes_read", "bytes read")),
      m_bytes_written(counter("bytes_written", "bytes written")),
      m_errors(counter("errors", "accesses answered with an error")) {
  if (params.size_bytes == 0) throw std::invalid_argument(std::string(this->name()) + ": size 0");
  if (params.width_bytes == 0) throw std::invalid_argument(std::string(this->name()) + ": zero width");
  in.register_b_transport(this, &Memory::b_transport);
  in.register_transport_dbg(this, &Memory::transport_dbg);
  in.register_get_direct_mem_ptr(this, &Memory::get_direct_mem_ptr);
}

bool Memory::check(tlm::tlm_generic_payload& gp) const {
  const uint64_t address = gp.get_address();
  const uint64_t length = gp.get_data_length();
  if (address >= m_data.size() || length > m_data.size() - address) {
    gp.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return false;
  }
  if (gp.get_streaming_width() < length) {
    gp.set_response_status(tlm::TLM_BURST_ERROR_RESPONSE);
    return false;
  }
  return true;
}

void Memory::b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  if (!check(gp)) {
    ++m_errors;
    const char* what = gp.get_response_status() == tlm::TLM_BURST_ERROR_RESPONSE
                           ? "streaming width shorter than the data (not supported): "
                           : "access outside memory: ";
    log::warning(name(), std::string(what) + (gp.is_write() ? "write" : "read") + " of " +
                             std::to_string(gp.get_data_length()) + " bytes at offset " + log::hex(gp.get_address()));
    return;
  }
  uint8_t* memory = m_data.data() + gp.get_address();
  const uint64_t length = gp.get_data_length();
  const uint8_t* enables = gp.get_byte_enable_ptr();
  const unsigned enable_length = gp.get_byte_enable_length();
  const unsigned transfers = transfers_of(gp);
  if (gp.is_read()) {
    if (enables) {
      for (uint64_t i = 0; i < length; ++i)
        if (enables[i % enable_length] == TLM_BYTE_ENABLED) gp.get_data_ptr()[i] = memory[i];
    } else {
      std::memcpy(gp.get_data_ptr(), memory, length);
    }
    m_reads += transfers;
    m_bytes_read += length;
  } else if (gp.is_write()) {
    if (enables) {
      for (uint64_t i = 0; i < length; ++i)
        if (enables[i % enable_length] == TLM_BYTE_ENABLED) memory[i] = gp.get_data_ptr()[i];
    } else {
      std::memmove(memory, gp.get_data_ptr(), length);
    }
    m_writes += transfers;
    m_bytes_written += length;
  }
  // Integer ticks: every transfer of a train takes the time of one access.
  const uint64_t ticks = transfers == 1 ? access_ticks(length) : access_ticks(length / transfers) * transfers;
  m_busy_ticks += ticks;
  if (ticks != m_last_access.value()) m_last_access = sc_core::sc_time::from_value(ticks);
  delay += m_last_access;
  gp.set_dmi_allowed(true);
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

unsigned Memory::transport_dbg(tlm::tlm_generic_payload& gp) {
  const uint64_t address = gp.get_address();
  if (address >= m_data.size()) {
    gp.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return 0;
  }
  const uint64_t length = std::min<uint64_t>(gp.get_data_length(), m_data.size() - address);
  if (gp.is_read())
    std::memcpy(gp.get_data_ptr(), m_data.data() + address, length);
  else if (gp.is_write())
    std::memcpy(m_data.data() + address, gp.get_data_ptr(), length);
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
  return static_cast<unsigned>(length);
}

bool Memory::get_direct_mem_ptr(tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi) {
  if (gp.get_address() >= m_data.size()) {
    dmi.allow_none();
    return false;
  }
  dmi.allow_read_write();
  dmi.set_dmi_ptr(m_data.data());
  dmi.set_start_address(0);
  dmi.set_end_address(m_data.size() - 1);
  // Latency of one single-beat access; initiators add per-beat time for bursts.
  dmi.set_read_latency(access_time(m_params.width_bytes));
  dmi.set_write_latency(access_time(m_params.width_bytes));
  return true;
}

void Memory::invalidate_dmi() {
  in->invalidate_direct_mem_ptr(0, m_data.size() - 1);
}

nlohmann::json Memory::stats_json(const sc_core::sc_time& elapsed) const {
  const double busy = static_cast<double>(m_busy_ticks);
  nlohmann::json stats = Block::stats_json(elapsed);
  stats["size_bytes"] = m_data.size();
  stats["busy_ns"] = sc_core::sc_time::from_value(m_busy_ticks).to_seconds() * 1e9;
  stats["utilisation"] = elapsed.value() ? busy / static_cast<double>(elapsed.value()) : 0.0;
  return stats;
}

SummaryRow Memory::summary_row(const sc_core::sc_time& elapsed) const {
  return busy_row(sc_core::sc_time::from_value(m_busy_ticks), elapsed,
                  std::to_string(m_reads.value) + " reads, " + std::to_string(m_writes.value) + " writes");
}

EnergyActivity Memory::energy_activity(const sc_core::sc_time& now) const {
  (void)now;
  return {{"memory", {{"transfers", static_cast<double>(m_reads.value + m_writes.value)}}}};
}

}  // namespace tessera
