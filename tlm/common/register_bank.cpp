#include "common/register_bank.h"

#include <cstring>
#include <stdexcept>

#include "common/log.h"

namespace tessera {

void RegisterBank::add(const RegisterInfo& info, ReadHandler on_read, WriteHandler on_write) {
  if (info.offset % 4 != 0 || find(info.offset))
    throw std::logic_error(m_owner + ": register " + info.name + " at a bad or duplicate offset");
  m_entries.push_back({info, info.reset, std::move(on_read), std::move(on_write)});
}

RegisterBank::Entry* RegisterBank::find(uint64_t offset) {
  for (auto& entry : m_entries)
    if (entry.info.offset == offset) return &entry;
  return nullptr;
}

const RegisterBank::Entry* RegisterBank::find(uint64_t offset) const {
  return const_cast<RegisterBank*>(this)->find(offset);
}

uint32_t RegisterBank::get(uint32_t offset) const {
  const Entry* entry = find(offset);
  if (!entry) throw std::logic_error(m_owner + ": no register at " + log::hex(offset));
  return entry->value;
}

void RegisterBank::set(uint32_t offset, uint32_t value) {
  Entry* entry = find(offset);
  if (!entry) throw std::logic_error(m_owner + ": no register at " + log::hex(offset));
  entry->value = value;
}

void RegisterBank::reset() {
  for (auto& entry : m_entries) entry.value = entry.info.reset;
}

tlm::tlm_response_status RegisterBank::check(const tlm::tlm_generic_payload& gp, Entry*& entry) {
  entry = nullptr;
  if (gp.get_data_length() != 4 || gp.get_streaming_width() < 4) return tlm::TLM_BURST_ERROR_RESPONSE;
  if (gp.get_byte_enable_ptr()) return tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE;
  entry = find(gp.get_address());
  if (!entry) return tlm::TLM_ADDRESS_ERROR_RESPONSE;
  if (gp.is_write() && entry->info.access == RegAccess::ro) return tlm::TLM_COMMAND_ERROR_RESPONSE;
  if (gp.is_read() && entry->info.access == RegAccess::wo) return tlm::TLM_COMMAND_ERROR_RESPONSE;
  return tlm::TLM_OK_RESPONSE;
}

const char* RegisterBank::transport(tlm::tlm_generic_payload& gp, const sc_core::sc_time& delay) {
  Entry* entry = nullptr;
  auto status = check(gp, entry);
  if (status != tlm::TLM_OK_RESPONSE) {
    gp.set_response_status(status);
    log::warning(m_owner, std::string("bad register access: ") + (gp.is_write() ? "write" : "read") + " of " +
                              std::to_string(gp.get_data_length()) + " bytes at offset " + log::hex(gp.get_address()) +
                              " (" + log::response_text(gp.get_response_status()) + ")");
    return nullptr;
  }
  uint32_t data = 0;
  m_access_delay = delay;
  if (gp.is_read()) {
    data = entry->on_read ? entry->on_read() : entry->value;
    std::memcpy(gp.get_data_ptr(), &data, 4);
  } else if (gp.is_write()) {
    std::memcpy(&data, gp.get_data_ptr(), 4);
    if (entry->on_write)
      entry->on_write(data);
    else if (entry->info.access == RegAccess::w1c)
      entry->value &= ~data;
    else
      entry->value = data;
  }
  m_access_delay = sc_core::SC_ZERO_TIME;
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
  return entry->info.name;
}

unsigned RegisterBank::transport_dbg(tlm::tlm_generic_payload& gp) {
  Entry* entry = nullptr;
  if (check(gp, entry) != tlm::TLM_OK_RESPONSE && !(entry && gp.is_read())) return 0;
  if (gp.is_read()) {
    const uint32_t value = entry->on_read ? entry->on_read() : entry->value;
    std::memcpy(gp.get_data_ptr(), &value, 4);
  } else if (gp.is_write())
    std::memcpy(&entry->value, gp.get_data_ptr(), 4);
  return 4;
}

}  // namespace tessera
