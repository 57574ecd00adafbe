#include "common/register_bank.h"

#include <cstring>
#include <stdexcept>

#include "common/log.h"

namespace tessera {

Register::Register(RegisterBank& bank, const RegisterInfo& info) : m_info(info), m_value(info.reset) {
  bank.attach(*this);
}

void Register::write(uint32_t value) {
  if (m_on_write)
    m_on_write(value);
  else if (m_info.access == RegAccess::w1c)
    m_value &= ~value;
  else
    m_value = value;
}

void RegisterBank::attach(Register& reg) {
  if (reg.info().offset % 4 != 0 || find(reg.info().offset))
    throw std::logic_error(m_owner + ": register " + reg.info().name + " at a bad or duplicate offset");
  m_registers.push_back(&reg);
}

Register& RegisterBank::add(const RegisterInfo& info, ReadHandler on_read, WriteHandler on_write) {
  auto reg = std::make_unique<Register>(*this, info);
  reg->on_read(std::move(on_read));
  reg->on_write(std::move(on_write));
  m_owned.push_back(std::move(reg));
  return *m_owned.back();
}

Register* RegisterBank::find(uint64_t offset) const {
  for (Register* reg : m_registers)
    if (reg->info().offset == offset) return reg;
  return nullptr;
}

uint32_t RegisterBank::get(uint32_t offset) const {
  const Register* reg = find(offset);
  if (!reg) throw std::logic_error(m_owner + ": no register at " + log::hex(offset));
  return reg->get();
}

void RegisterBank::set(uint32_t offset, uint32_t value) {
  Register* reg = find(offset);
  if (!reg) throw std::logic_error(m_owner + ": no register at " + log::hex(offset));
  reg->set(value);
}

void RegisterBank::reset() {
  for (Register* reg : m_registers) reg->reset();
}

tlm::tlm_response_status RegisterBank::check(const tlm::tlm_generic_payload& gp, Register*& reg) const {
  reg = nullptr;
  if (gp.get_data_length() != 4 || gp.get_streaming_width() < 4) return tlm::TLM_BURST_ERROR_RESPONSE;
  if (gp.get_byte_enable_ptr()) return tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE;
  reg = find(gp.get_address());
  if (!reg) return tlm::TLM_ADDRESS_ERROR_RESPONSE;
  if (gp.is_write() && reg->info().access == RegAccess::ro) return tlm::TLM_COMMAND_ERROR_RESPONSE;
  if (gp.is_read() && reg->info().access == RegAccess::wo) return tlm::TLM_COMMAND_ERROR_RESPONSE;
  return tlm::TLM_OK_RESPONSE;
}

const char* RegisterBank::transport(tlm::tlm_generic_payload& gp, const sc_core::sc_time& delay) {
  Register* reg = nullptr;
  auto status = check(gp, reg);
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
    data = reg->read();
    std::memcpy(gp.get_data_ptr(), &data, 4);
  } else if (gp.is_write()) {
    std::memcpy(&data, gp.get_data_ptr(), 4);
    reg->write(data);
  }
  m_access_delay = sc_core::SC_ZERO_TIME;
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
  return reg->info().name;
}

unsigned RegisterBank::transport_dbg(tlm::tlm_generic_payload& gp) {
  Register* reg = nullptr;
  if (check(gp, reg) != tlm::TLM_OK_RESPONSE && !(reg && gp.is_read())) return 0;
  uint32_t value = 0;
  if (gp.is_read()) {
    value = reg->read();
    std::memcpy(gp.get_data_ptr(), &value, 4);
  } else if (gp.is_write()) {
    std::memcpy(&value, gp.get_data_ptr(), 4);
    reg->set(value);
  }
  return 4;
}

}  // namespace tessera
