#include "host/iss/semihosting.h"

#include <algorithm>

#include "host/iss/arm_core.h"

namespace tessera::iss {

using namespace semihosting;

namespace {

constexpr uint32_t FAILED = 0xffffffffu;  // -1
// Semihosting's file modes, fopen's strings in order: 0-3 read, 4-7 write,
// 8-11 append.
constexpr uint32_t MODES = 12;
// SYS_WRITE reads the program's data and hands it on in pieces this large.
constexpr uint32_t WRITE_CHUNK = 4096;
bool reads(uint32_t mode) {
  return mode < 4;
}
bool appends(uint32_t mode) {
  return mode >= 8;
}

}  // namespace

bool Semihosting::is_call(uint32_t instruction, bool thumb) {
  if (thumb) return (instruction & 0xffffu) == (0xdf00u | THUMB_SWI);
  return (instruction & 0x0fffffffu) == (0x0f000000u | ARM_SWI);
}

void Semihosting::offer_file(const std::string& name, std::string content) {
  m_files[name] = std::move(content);
}

void Semihosting::offer_sink(const std::string& name, std::function<void(const std::string& data)> sink) {
  m_sinks[name] = std::move(sink);
}

uint32_t Semihosting::fail(int error) {
  m_errno = error;
  return FAILED;
}

bool Semihosting::words(uint32_t address, uint32_t* out, unsigned count) {
  uint8_t bytes[16];
  if (count > 4 || !m_port.read_memory(address, bytes, 4 * count)) return false;
  for (unsigned i = 0; i < count; ++i)
    out[i] = uint32_t{bytes[4 * i]} | uint32_t{bytes[4 * i + 1]} << 8 | uint32_t{bytes[4 * i + 2]} << 16 |
             uint32_t{bytes[4 * i + 3]} << 24;
  return true;
}

bool Semihosting::read_string(uint32_t address, uint32_t length, std::string& out) {
  constexpr uint32_t MAX_NAME = 4096;
  if (length > MAX_NAME) return false;
  out.resize(length);
  return length == 0 || m_port.read_memory(address, reinterpret_cast<uint8_t*>(out.data()), length);
}

Semihosting::Handle* Semihosting::handle(uint32_t number) {
  if (number == 0 || number > m_handles.size() || !m_handles[number - 1]) return nullptr;
  return m_handles[number - 1].get();
}

uint32_t Semihosting::serve(uint32_t op, uint32_t parameter) {
  switch (op) {
    case semihosting::open: return open(parameter);
    case semihosting::close: {
      uint32_t number = 0;
      if (!words(parameter, &number, 1)) return fail(ERROR_FAULT);
      if (!handle(number)) return fail(ERROR_BAD_HANDLE);
      m_handles[number - 1].reset();
      return 0;
    }
    case semihosting::writec: {
      uint8_t c = 0;
      if (!m_port.read_memory(parameter, &c, 1)) return fail(ERROR_FAULT);
      if (console) console(1, std::string(1, static_cast<char>(c)));
      return 0;
    }
    case semihosting::write0: {
      std::string text;
      for (uint8_t c = 0;; ++parameter) {
        if (!m_port.read_memory(parameter, &c, 1)) return fail(ERROR_FAULT);
        if (c == 0) break;
        text += static_cast<char>(c);
      }
      if (console) console(1, text);
      return 0;
    }
    case semihosting::write: return write(parameter);
    case semihosting::read: return read(parameter);
    case semihosting::iserror: {
      uint32_t status = 0;
      if (!words(parameter, &status, 1)) return fail(ERROR_FAULT);
      return static_cast<int32_t>(status) < 0 ? 1 : 0;
    }
    case semihosting::istty: {
      uint32_t number = 0;
      if (!words(parameter, &number, 1)) return fail(ERROR_FAULT);
      const Handle* h = handle(number);
      if (!h) return fail(ERROR_BAD_HANDLE);
      return h->kind == Handle::Kind::console_in || h->kind == Handle::Kind::console_out ||
                     h->kind == Handle::Kind::console_error
                 ? 1
                 : 0;
    }
    case semihosting::seek: return seek(parameter);
    case semihosting::flen: return length(parameter);
    case semihosting::clock: return static_cast<uint32_t>(m_port.elapsed_cycles() * 100 / m_port.clock_hz());
    case semihosting::time: return static_cast<uint32_t>(m_port.elapsed_cycles() / m_port.clock_hz());
    case semihosting::errno_value: return static_cast<uint32_t>(m_errno);
    case semihosting::get_cmdline: return get_command_line(parameter);
    case semihosting::exit:
      m_exited = true;
      m_exit_status = parameter == APPLICATION_EXIT ? 0 : 1;
      return 0;
    case semihosting::exit_extended: {
      uint32_t block[2] = {};
      if (!words(parameter, block, 2)) return fail(ERROR_FAULT);
      m_exited = true;
      m_exit_status = block[0] == APPLICATION_EXIT ? static_cast<int>(block[1]) : 1;
      return 0;
    }
    case semihosting::elapsed: {
      const uint64_t cycles = m_port.elapsed_cycles();
      uint8_t bytes[8];
      for (unsigned i = 0; i < 8; ++i) bytes[i] = static_cast<uint8_t>(cycles >> (8 * i));
      return m_port.write_memory(parameter, bytes, 8) ? 0 : fail(ERROR_FAULT);
    }
    case semihosting::tickfreq: return m_port.clock_hz();
    default:
      if (warn && std::find(m_warned.begin(), m_warned.end(), op) == m_warned.end()) {
        m_warned.push_back(op);
        warn("semihosting operation " + address_text(op) + " is not served (it returns -1)");
      }
      return fail(ERROR_NOT_IMPLEMENTED);
  }
}

uint32_t Semihosting::open(uint32_t block) {
  uint32_t w[3] = {};
  if (!words(block, w, 3)) return fail(ERROR_FAULT);
  std::string name;
  if (!read_string(w[0], w[2], name)) return fail(ERROR_FAULT);
  const uint32_t mode = w[1];
  if (mode >= MODES) return fail(ERROR_INVALID);
  auto h = std::make_unique<Handle>();
  if (name == CONSOLE) {
    h->kind = reads(mode)     ? Handle::Kind::console_in
              : appends(mode) ? Handle::Kind::console_error
                              : Handle::Kind::console_out;
  } else if (auto file = m_files.find(name); file != m_files.end()) {
    if (!reads(mode)) return fail(ERROR_ACCESS);
    h->kind = Handle::Kind::content;
    h->content = file->second;
  } else if (auto sink = m_sinks.find(name); sink != m_sinks.end()) {
    if (reads(mode)) return fail(ERROR_ACCESS);
    h->kind = Handle::Kind::sink;
    h->sink = sink->second;
  } else {
    if (!reads(mode) || !host_files) return fail(ERROR_ACCESS);
    h->kind = Handle::Kind::host_file;
    h->file = std::make_unique<std::ifstream>(name, std::ios::binary | std::ios::ate);
    if (!*h->file) return fail(ERROR_NO_ENTRY);
    h->file_length = static_cast<uint64_t>(h->file->tellg());
    h->file->seekg(0);
  }
  for (size_t i = 0; i < m_handles.size(); ++i)
    if (!m_handles[i]) {
      m_handles[i] = std::move(h);
      return static_cast<uint32_t>(i + 1);
    }
  m_handles.push_back(std::move(h));
  return static_cast<uint32_t>(m_handles.size());
}

uint32_t Semihosting::write(uint32_t block) {
  uint32_t w[3] = {};
  if (!words(block, w, 3)) return fail(ERROR_FAULT);
  Handle* h = handle(w[0]);
  if (!h) return fail(ERROR_BAD_HANDLE);
  std::function<void(const std::string&)> take;
  switch (h->kind) {
    case Handle::Kind::console_out:
      take = [this](const std::string& text) {
        if (console) console(1, text);
      };
      break;
    case Handle::Kind::console_error:
      take = [this](const std::string& text) {
        if (console) console(2, text);
      };
      break;
    case Handle::Kind::sink: take = h->sink; break;
    default: m_errno = ERROR_BAD_HANDLE; return w[2];  // opened for reading: nothing written
  }
  // Handed on a chunk at a time as it is read: any length is written, in
  // bounded memory.
  std::string chunk;
  for (uint32_t done = 0; done < w[2]; done += static_cast<uint32_t>(chunk.size())) {
    chunk.resize(std::min(WRITE_CHUNK, w[2] - done));
    if (!m_port.read_memory(w[1] + done, reinterpret_cast<uint8_t*>(chunk.data()),
                            static_cast<unsigned>(chunk.size()))) {
      if (done == 0) return fail(ERROR_FAULT);
      m_errno = ERROR_FAULT;
      return w[2] - done;  // the bytes not written
    }
    take(chunk);
  }
  return 0;
}

uint32_t Semihosting::read(uint32_t block) {
  uint32_t w[3] = {};
  if (!words(block, w, 3)) return fail(ERROR_FAULT);
  Handle* h = handle(w[0]);
  if (!h) return fail(ERROR_BAD_HANDLE);
  const uint32_t wanted = w[2];
  std::vector<uint8_t> data;
  if (h->kind == Handle::Kind::content) {
    const size_t n = std::min<size_t>(wanted, h->content.size() - std::min(h->position, h->content.size()));
    data.assign(h->content.begin() + static_cast<std::ptrdiff_t>(h->position),
                h->content.begin() + static_cast<std::ptrdiff_t>(h->position + n));
    h->position += n;
  } else if (h->kind == Handle::Kind::host_file) {
    data.resize(std::min<uint64_t>(wanted, 1u << 24));
    h->file->read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size()));
    data.resize(static_cast<size_t>(h->file->gcount()));
    h->file->clear();
  } else if (h->kind == Handle::Kind::console_in) {
    return wanted;  // no input: end of file at once
  } else {
    m_errno = ERROR_BAD_HANDLE;
    return wanted;
  }
  if (!data.empty() && !m_port.write_memory(w[1], data.data(), static_cast<unsigned>(data.size())))
    return fail(ERROR_FAULT);
  return wanted - static_cast<uint32_t>(data.size());
}

uint32_t Semihosting::seek(uint32_t block) {
  uint32_t w[2] = {};
  if (!words(block, w, 2)) return fail(ERROR_FAULT);
  Handle* h = handle(w[0]);
  if (!h) return fail(ERROR_BAD_HANDLE);
  if (h->kind == Handle::Kind::content) {
    if (w[1] > h->content.size()) return fail(ERROR_INVALID);
    h->position = w[1];
    return 0;
  }
  if (h->kind == Handle::Kind::host_file) {
    if (w[1] > h->file_length) return fail(ERROR_INVALID);
    h->file->seekg(w[1]);
    return 0;
  }
  return fail(ERROR_INVALID);
}

uint32_t Semihosting::length(uint32_t block) {
  uint32_t number = 0;
  if (!words(block, &number, 1)) return fail(ERROR_FAULT);
  Handle* h = handle(number);
  if (!h) return fail(ERROR_BAD_HANDLE);
  if (h->kind == Handle::Kind::content) return static_cast<uint32_t>(h->content.size());
  if (h->kind == Handle::Kind::host_file) return static_cast<uint32_t>(h->file_length);
  return fail(ERROR_INVALID);
}

uint32_t Semihosting::get_command_line(uint32_t block) {
  uint32_t w[2] = {};
  if (!words(block, w, 2)) return fail(ERROR_FAULT);
  if (command_line.size() + 1 > w[1]) return fail(ERROR_INVALID);
  if (!m_port.write_memory(w[0], reinterpret_cast<const uint8_t*>(command_line.c_str()),
                           static_cast<unsigned>(command_line.size() + 1)))
    return fail(ERROR_FAULT);
  const auto size = static_cast<uint32_t>(command_line.size());
  const uint8_t bytes[4] = {static_cast<uint8_t>(size), static_cast<uint8_t>(size >> 8),
                            static_cast<uint8_t>(size >> 16), static_cast<uint8_t>(size >> 24)};
  return m_port.write_memory(block + 4, bytes, 4) ? 0 : fail(ERROR_FAULT);
}

}  // namespace tessera::iss
