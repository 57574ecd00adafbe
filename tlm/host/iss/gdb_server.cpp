#include "host/iss/gdb_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

namespace tessera::iss {

namespace {

// r0-r12, sp, lr, pc, cpsr: GDB's org.gnu.gdb.arm.core feature, numbered
// 0-16 in this order (so the g packet is 17 little-endian words).
const std::string TARGET_XML = [] {
  std::string xml =
      "<?xml version=\"1.0\"?><!DOCTYPE target SYSTEM \"gdb-target.dtd\"><target><architecture>arm</architecture>"
      "<feature name=\"org.gnu.gdb.arm.core\">";
  for (int n = 0; n < 13; ++n) xml += "<reg name=\"r" + std::to_string(n) + "\" bitsize=\"32\"/>";
  xml +=
      "<reg name=\"sp\" bitsize=\"32\" type=\"data_ptr\"/><reg name=\"lr\" bitsize=\"32\"/>"
      "<reg name=\"pc\" bitsize=\"32\" type=\"code_ptr\"/><reg name=\"cpsr\" bitsize=\"32\"/></feature></target>";
  return xml;
}();

constexpr char HEX[] = "0123456789abcdef";

// GDB's signal numbers (its own numbering, the same as Linux's for these).
constexpr unsigned SIGNAL_INT = 2, SIGNAL_ILL = 4, SIGNAL_TRAP = 5, SIGNAL_ABRT = 6, SIGNAL_KILL = 9, SIGNAL_SEGV = 11,
                   SIGNAL_XCPU = 24;

// Instructions between two looks at the connection during a run (for
// GDB's Ctrl-C, or its going away): a poll() costs about a microsecond.
constexpr uint64_t POLL_INTERVAL = 1u << 16;

// The largest packet either side sends (qSupported's PacketSize): GDB
// sizes its memory reads and writes by it.
constexpr uint64_t PACKET_SIZE = 0x4000;

std::string hex_byte(unsigned value) {
  return {HEX[(value >> 4) & 15], HEX[value & 15]};
}

std::string hex_word(uint32_t value) {  // target byte order: little-endian
  std::string out;
  for (int i = 0; i < 4; ++i) {
    const auto byte = static_cast<uint8_t>(value >> (8 * i));
    out += HEX[byte >> 4];
    out += HEX[byte & 15];
  }
  return out;
}

int nibble(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool parse_hex(const std::string& text, uint64_t& value) {
  if (text.empty() || text.size() > 16) return false;
  value = 0;
  for (char c : text) {
    const int n = nibble(c);
    if (n < 0) return false;
    value = value << 4 | static_cast<uint64_t>(n);
  }
  return true;
}

// Eight hex digits at `at`, the word's bytes little-endian; false if any is
// not a hex digit or the text is too short.
bool word_from_hex(const std::string& text, size_t at, uint32_t& value) {
  if (text.size() < at + 8) return false;
  value = 0;
  for (unsigned i = 0; i < 8; ++i) {
    const int n = nibble(text[at + i]);
    if (n < 0) return false;
    value |= static_cast<uint32_t>(n) << (8 * (i / 2) + (i % 2 == 0 ? 4 : 0));
  }
  return true;
}

}  // namespace

GdbPacketReader::Event GdbPacketReader::feed(char c) {
  switch (m_state) {
    case State::between:
      if (c == '$') {
        m_state = State::data;
        m_data.clear();
        m_sum = 0;
        m_too_long = false;
      }
      return Event::none;
    case State::data:
      if (c == '#') {
        m_state = State::checksum_high;
      } else if (c == '$') {  // a packet begun again (the rest was lost)
        m_data.clear();
        m_sum = 0;
        m_too_long = false;
      } else {
        m_sum += static_cast<unsigned char>(c);
        if (m_data.size() < MAX_DATA)
          m_data += c;
        else
          m_too_long = true;
      }
      return Event::none;
    case State::checksum_high:
      m_bad_digit = nibble(c) < 0;
      m_checksum = m_bad_digit ? 0 : static_cast<unsigned>(nibble(c)) << 4;
      m_state = State::checksum_low;
      return Event::none;
    case State::checksum_low:
      m_state = State::between;
      m_bad_digit = m_bad_digit || nibble(c) < 0;
      if (!m_bad_digit) m_checksum |= static_cast<unsigned>(nibble(c));
      if (m_too_long) {
        m_data.clear();
        return Event::too_long;
      }
      if (m_bad_digit || m_checksum != (m_sum & 0xffu)) {
        m_data.clear();
        return Event::bad_checksum;
      }
      return Event::packet;
  }
  return Event::none;
}

GdbServer::~GdbServer() {
  close_connection();
}

unsigned GdbServer::listen(unsigned port) {
  m_listen_fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (m_listen_fd < 0)
    throw std::runtime_error("GDB server: cannot create a socket: " + std::string(std::strerror(errno)));
  const int yes = 1;
  ::setsockopt(m_listen_fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<uint16_t>(port));
  if (port > 65535 || ::bind(m_listen_fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(m_listen_fd, 1) != 0) {
    const std::string reason = port > 65535 ? "not a TCP port" : std::strerror(errno);
    close_connection();
    throw std::runtime_error("GDB server: cannot listen on 127.0.0.1:" + std::to_string(port) + ": " + reason);
  }
  socklen_t length = sizeof address;
  ::getsockname(m_listen_fd, reinterpret_cast<sockaddr*>(&address), &length);
  return ntohs(address.sin_port);
}

void GdbServer::close_connection() {
  if (m_fd >= 0) ::close(m_fd);
  if (m_listen_fd >= 0) ::close(m_listen_fd);
  m_fd = m_listen_fd = -1;
  m_connected = m_running = false;
}

bool GdbServer::receive(char& c) {
  ssize_t n;
  do n = ::recv(m_fd, &c, 1, 0);
  while (n < 0 && errno == EINTR);
  if (n != 1) m_connected = false;
  return n == 1;
}

std::string GdbServer::read_packet() {
  char c = 0;
  while (receive(c)) {
    switch (m_reader.feed(c)) {
      case GdbPacketReader::Event::none: break;
      case GdbPacketReader::Event::packet: ::send(m_fd, "+", 1, MSG_NOSIGNAL); return m_reader.packet();
      case GdbPacketReader::Event::bad_checksum:  // not executed: GDB sends it again
        ::send(m_fd, "-", 1, MSG_NOSIGNAL);
        break;
      case GdbPacketReader::Event::too_long:
        // Sending it again would not help: acknowledged, refused, dropped.
        std::fprintf(stderr, "GDB server: a packet of more than %zu bytes refused (the server offers %llu)\n",
                     GdbPacketReader::MAX_DATA, static_cast<unsigned long long>(PACKET_SIZE));
        ::send(m_fd, "+", 1, MSG_NOSIGNAL);
        send_packet("E01");
        break;
    }
  }
  return "";
}

void GdbServer::send_packet(const std::string& data) {
  if (!m_connected) return;
  unsigned sum = 0;
  for (char c : data) sum += static_cast<unsigned char>(c);
  const std::string packet = "$" + data + "#" + hex_byte(sum);
  for (int attempt = 0; attempt < 3; ++attempt) {
    // MSG_NOSIGNAL: a GDB gone away is an error here, not a SIGPIPE.
    if (::send(m_fd, packet.data(), packet.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(packet.size())) {
      m_connected = false;
      return;
    }
    char ack = 0;
    if (!receive(ack) || ack != '-') return;
  }
}

std::string GdbServer::registers() const {
  std::string out;
  for (unsigned n = 0; n < 16; ++n) out += hex_word(m_target->core.reg(n));
  return out + hex_word(m_target->core.cpsr());
}

std::string GdbServer::stop_reply() const {
  if (m_target->exited()) return "W" + hex_byte(m_target->status() & 0xffu);
  return "S" + hex_byte(m_signal);
}

std::string GdbServer::read_memory(uint32_t address, uint32_t length) const {
  std::vector<uint8_t> bytes(length);
  uint32_t got = length;
  if (!m_target->memory.debug_read(address, bytes.data(), length))  // as far as memory goes
    for (got = 0; got < length && m_target->memory.debug_read(address + got, &bytes[got], 1);) ++got;
  if (got == 0 && length > 0) return "E01";
  std::string out;
  for (uint32_t i = 0; i < got; ++i) out += hex_byte(bytes[i]);
  return out;
}

bool GdbServer::interrupted() {
  pollfd connection{m_fd, POLLIN, 0};
  if (::poll(&connection, 1, 0) <= 0) return false;
  char c = 0;
  return !receive(c) || c == '\x03';
}

bool GdbServer::run(bool single_step, uint64_t& budget) {
  ArmCore& core = m_target->core;
  uint64_t until_poll = POLL_INTERVAL;
  m_signal = SIGNAL_TRAP;
  do {
    if (budget == 0) return false;
    --budget;
    try {
      m_target->step();
    } catch (const ProgramFault& fault) {
      m_signal = fault.exception() == Exception::undefined ? SIGNAL_ILL : SIGNAL_SEGV;
      m_fault = std::current_exception();
      return true;
    } catch (const IssError&) {  // an unpredictable encoding
      m_signal = SIGNAL_ILL;
      m_fault = std::current_exception();
      return true;
    }
    if (--until_poll == 0) {
      until_poll = POLL_INTERVAL;
      if (interrupted()) {
        m_signal = SIGNAL_INT;
        return true;
      }
    }
  } while (!single_step && !m_target->exited() && (m_breakpoints.empty() || !m_breakpoints.count(core.reg(15))));
  return true;
}

std::string GdbServer::handle(const std::string& packet, bool& resume, bool& step, bool& stop_serving) {
  ArmCore& core = m_target->core;
  const char kind = packet.empty() ? '\0' : packet[0];
  const std::string args = packet.size() > 1 ? packet.substr(1) : "";
  switch (kind) {
    case '?': return stop_reply();
    case 'g': return registers();
    case 'G': {
      // Every word checked before any is set: a bad packet changes nothing.
      uint32_t words[17];
      for (unsigned n = 0; n < 17; ++n)
        if (!word_from_hex(args, 8 * n, words[n])) return "E01";
      for (unsigned n = 0; n < 16; ++n) core.set_reg(n, words[n]);
      core.set_cpsr(words[16]);
      return "OK";
    }
    case 'p': {
      uint64_t n = 0;
      if (!parse_hex(args, n) || n > 16) return "E01";
      return hex_word(n == 16 ? core.cpsr() : core.reg(static_cast<unsigned>(n)));
    }
    case 'P': {
      const size_t eq = args.find('=');
      uint64_t n = 0;
      uint32_t value = 0;
      if (eq == std::string::npos || !parse_hex(args.substr(0, eq), n) || n > 16 || !word_from_hex(args, eq + 1, value))
        return "E01";
      if (n == 16)
        core.set_cpsr(value);
      else
        core.set_reg(static_cast<unsigned>(n), value);
      return "OK";
    }
    case 'm':
    case 'M': {
      const size_t comma = args.find(',');
      const size_t colon = args.find(':');
      uint64_t address = 0, length = 0;
      if (comma == std::string::npos || !parse_hex(args.substr(0, comma), address) ||
          !parse_hex(args.substr(comma + 1, kind == 'M' ? colon - comma - 1 : std::string::npos), length) ||
          length > PACKET_SIZE / 2 || address + length > (1ull << 32))
        return "E01";
      if (kind == 'm') return read_memory(static_cast<uint32_t>(address), static_cast<uint32_t>(length));
      if (colon == std::string::npos || args.size() != colon + 1 + 2 * length) return "E01";
      std::vector<uint8_t> bytes(length);
      for (uint64_t i = 0; i < length; ++i) {
        const int high = nibble(args[colon + 1 + 2 * i]), low = nibble(args[colon + 2 + 2 * i]);
        if (high < 0 || low < 0) return "E01";
        bytes[i] = static_cast<uint8_t>(high << 4 | low);
      }
      const bool written = length == 0 || m_target->memory.debug_write(static_cast<uint32_t>(address), bytes.data(),
                                                                       static_cast<unsigned>(length));
      return written ? "OK" : "E01";
    }
    case 'Z':
    case 'z': {
      // Z0 (software) and Z1 (hardware) breakpoints alike: the simulator
      // checks the PC; watchpoints are not offered.
      if (args.size() < 3 || (args[0] != '0' && args[0] != '1') || args[1] != ',') return "";
      uint64_t address = 0;
      if (!parse_hex(args.substr(2, args.find(',', 2) - 2), address) || address > 0xffffffffu) return "E01";
      if (kind == 'Z')
        m_breakpoints.insert(static_cast<uint32_t>(address));
      else
        m_breakpoints.erase(static_cast<uint32_t>(address));
      return "OK";
    }
    case 'c':
    case 's':
    case 'C':  // with a signal (GDB passes on the one the program stopped
    case 'S':  // with): the ISS has none to deliver, so it is dropped
    {
      const size_t semicolon = args.find(';');
      const std::string at = kind == 'c' || kind == 's'       ? args
                             : semicolon == std::string::npos ? ""
                                                              : args.substr(semicolon + 1);
      if (!at.empty()) {
        uint64_t address = 0;
        if (!parse_hex(at, address)) return "E01";
        core.set_reg(15, static_cast<uint32_t>(address));
      }
      resume = true;
      step = kind == 's' || kind == 'S';
      return "";
    }
    case 'k': stop_serving = true; return "";
    case 'D': stop_serving = true; return "OK";
    case 'H': return "OK";
    case 'q':
      if (packet.rfind("qSupported", 0) == 0) {
        char features[64];
        std::snprintf(features, sizeof features, "PacketSize=%llx;qXfer:features:read+",
                      static_cast<unsigned long long>(PACKET_SIZE));
        return features;
      }
      // Attached to a running program: GDB leaving detaches rather than kills.
      if (packet == "qAttached") return "1";
      if (packet == "qC") return "QC1";
      if (packet == "qfThreadInfo") return "m1";
      if (packet == "qsThreadInfo") return "l";
      if (packet.rfind("qXfer:features:read:target.xml:", 0) == 0) {
        const std::string range = packet.substr(std::strlen("qXfer:features:read:target.xml:"));
        const size_t comma = range.find(',');
        uint64_t offset = 0, length = 0;
        if (comma == std::string::npos || !parse_hex(range.substr(0, comma), offset) ||
            !parse_hex(range.substr(comma + 1), length))
          return "E01";
        if (offset >= TARGET_XML.size()) return "l";
        const std::string chunk = TARGET_XML.substr(offset, length);
        return (offset + chunk.size() >= TARGET_XML.size() ? "l" : "m") + chunk;
      }
      return "";
    default: return "";  // not supported: GDB falls back or does without
  }
}

GdbServer::End GdbServer::serve(const Target& target, uint64_t instruction_limit) {
  if (m_listen_fd < 0) throw std::logic_error("GDB server: serve() before listen()");
  do m_fd = ::accept(m_listen_fd, nullptr, nullptr);
  while (m_fd < 0 && errno == EINTR);
  if (m_fd < 0) {
    const std::string reason = std::strerror(errno);
    close_connection();
    throw std::runtime_error("GDB server: accept failed: " + reason);
  }
  ::close(m_listen_fd);  // one debugger at a time
  m_listen_fd = -1;
  const int yes = 1;  // single steps are one small packet each way
  ::setsockopt(m_fd, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
  m_connected = true;
  m_target = &target;
  m_fault = nullptr;
  m_signal = SIGNAL_TRAP;
  uint64_t budget = instruction_limit;
  End end = End::detached;
  try {
    while (true) {
      const std::string packet = read_packet();
      if (!m_connected) {
        end = End::disconnected;
        break;
      }
      bool resume = false, step = false, stop_serving = false;
      const std::string reply = handle(packet, resume, step, stop_serving);
      if (resume && m_fault) {  // the program cannot go on from its fault
        send_packet("X" + hex_byte(m_signal));
        break;
      }
      if (resume) {
        m_running = true;
        const bool within_limit = run(step, budget);
        m_running = false;
        if (!within_limit) {
          send_packet("X" + hex_byte(SIGNAL_XCPU));
          end = End::limit;
          break;
        }
        if (!m_connected) {
          end = End::disconnected;
          break;
        }
        send_packet(stop_reply());
        if (target.exited()) {
          end = End::exited;
          break;
        }
        continue;
      }
      if (packet == "k") {
        end = End::killed;
        break;
      }
      send_packet(reply);
      if (stop_serving) break;
    }
  } catch (...) {
    // Not the program's fault (the launcher's or the simulation's own
    // error): GDB is told the program ended before it goes on up.
    if (m_running) send_packet("X" + hex_byte(SIGNAL_ABRT));
    close_connection();
    m_target = nullptr;
    throw;
  }
  close_connection();
  m_target = nullptr;
  if (m_fault && end != End::killed) std::rethrow_exception(std::exchange(m_fault, nullptr));
  return end;
}

std::string GdbServer::reply(const Target& target, const std::string& packet) {
  const Target* serving = std::exchange(m_target, &target);
  bool resume = false, step = false, stop_serving = false;
  std::string answer;
  try {
    answer = handle(packet, resume, step, stop_serving);
  } catch (...) {
    m_target = serving;
    throw;
  }
  m_target = serving;
  return answer;
}

void GdbServer::abandon() {
  if (m_running) send_packet("X" + hex_byte(SIGNAL_KILL));
  close_connection();
}

}  // namespace tessera::iss
