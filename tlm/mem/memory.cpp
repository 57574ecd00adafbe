#include "mem/memory.h"

#include <algorithm>
#include <cstring>
#include <new>
#include <stdexcept>

#include "common/log.h"
#include "common/loosely_timed.h"
#include "common/ticks_time.h"
#include "common/transfer_train.h"

namespace tessera {

Memory::Memory(sc_core::sc_module_name name, const MemoryParams& params)
    : Block(name),
      in("in"),
      m_params(params),
      m_data(params.size_bytes),
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
  in.bind(static_cast<tlm::tlm_fw_transport_if<>&>(*this));
}

Memory::Bytes::Bytes(uint64_t size)
    : m_bytes(static_cast<uint8_t*>(std::calloc(std::max<uint64_t>(size, 1), 1))), m_size(size) {
  if (!m_bytes) throw std::bad_alloc();
}

namespace {

// memmove (the data may overlap the memory), inline for the sizes of
// single transfers, where a call into the C library would cost more than
// the copy. A payload that is the memory's own bytes (a host's span,
// already in place through DMI) is not moved onto itself.
inline void move(uint8_t* to, const uint8_t* from, uint64_t length) {
  switch (length) {
    case 1: std::memmove(to, from, 1); break;
    case 2: std::memmove(to, from, 2); break;
    case 4: std::memmove(to, from, 4); break;
    case 8: std::memmove(to, from, 8); break;
    default:
      if (to != from) std::memmove(to, from, length);
  }
}

}  // namespace

void Memory::refuse(tlm::tlm_generic_payload& gp) {
  const bool outside = gp.get_address() >= m_data.size() || gp.get_data_length() > m_data.size() - gp.get_address();
  gp.set_response_status(outside ? tlm::TLM_ADDRESS_ERROR_RESPONSE : tlm::TLM_BURST_ERROR_RESPONSE);
  ++m_errors;
  const char* what = outside ? "access outside memory: " : "streaming width shorter than the data (not supported): ";
  log::warning(name(), std::string(what) + (gp.is_write() ? "write" : "read") + " of " +
                           std::to_string(gp.get_data_length()) + " bytes at offset " + log::hex(gp.get_address()));
}

void Memory::move_enabled(tlm::tlm_generic_payload& gp) {
  uint8_t* memory = m_data.data() + gp.get_address();
  const uint64_t length = gp.get_data_length();
  const uint8_t* enables = gp.get_byte_enable_ptr();
  const unsigned enable_length = gp.get_byte_enable_length();
  if (gp.is_read()) {
    for (uint64_t i = 0; i < length; ++i)
      if (enables[i % enable_length] == TLM_BYTE_ENABLED) gp.get_data_ptr()[i] = memory[i];
  } else if (gp.is_write()) {
    for (uint64_t i = 0; i < length; ++i)
      if (enables[i % enable_length] == TLM_BYTE_ENABLED) memory[i] = gp.get_data_ptr()[i];
  }
}

void Memory::b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  transport(gp, delay, transfers_of(gp));
}

void Memory::transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay, unsigned transfers) {
  const uint64_t address = gp.get_address();
  const uint64_t length = gp.get_data_length();
  const uint64_t size = m_data.size();
  if (address >= size || length > size - address || gp.get_streaming_width() < length) {
    refuse(gp);
    return;
  }
  if (gp.is_read()) {
    if (gp.get_byte_enable_ptr())
      move_enabled(gp);
    else
      move(gp.get_data_ptr(), m_data.data() + address, length);
    m_reads += transfers;
    m_bytes_read += length;
  } else if (gp.is_write()) {
    if (gp.get_byte_enable_ptr())
      move_enabled(gp);
    else
      move(m_data.data() + address, gp.get_data_ptr(), length);
    m_writes += transfers;
    m_bytes_written += length;
  }
  // Integer ticks: every transfer of a train takes the time of one access.
  const uint64_t ticks = transfers == 1 ? access_ticks(length) : access_ticks(length / transfers) * transfers;
  m_busy_ticks += ticks;
  delay += ticks_time(ticks);
  gp.set_dmi_allowed(true);
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

bool Memory::quote_accesses(tlm::tlm_command command, uint64_t address, unsigned bytes, size_t count,
                            unsigned transfers, uint64_t& latency_ticks, bool& untouched) {
  const uint64_t size = m_data.size();
  if ((command != tlm::TLM_READ_COMMAND && command != tlm::TLM_WRITE_COMMAND) || bytes == 0 || count == 0 ||
      transfers == 0 || address >= size || count > (size - address) / bytes)
    return false;
  latency_ticks = access_ticks(bytes) * transfers;  // transport()'s: each transfer the time of one access
  untouched = true;                                 // DMI granted (transport's set_dmi_allowed)
  return true;
}

void Memory::direct_accesses(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned bytes, size_t count) {
  // transport()'s steps for each access, summed: the bytes moved (none
  // where they are the memory's own, through DMI), the counters, the time.
  const uint64_t length = uint64_t{bytes} * count;
  if (command == tlm::TLM_READ_COMMAND) {
    move(data, m_data.data() + address, length);
    m_reads += count;
    m_bytes_read += length;
  } else {
    move(m_data.data() + address, data, length);
    m_writes += count;
    m_bytes_written += length;
  }
  m_busy_ticks += access_ticks(bytes) * count;
}

tlm::tlm_sync_enum Memory::nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& /*phase*/,
                                           sc_core::sc_time& /*delay*/) {
  ++m_errors;
  return refuse_non_blocking(name(), gp);
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

void Memory::describe_stats(StatsSchema& schema) const {
  Block::describe_stats(schema);
  schema.add_setting("size_bytes", "bytes", "size of the memory");
  schema.add("busy_ns", "ns", "time the memory served accesses");
  schema.add("utilisation", "fraction", "busy_ns over the simulated time");
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
