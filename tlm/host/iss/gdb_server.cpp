#include "host/iss/gdb_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>

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

uint32_t word_from_hex(const std::string& text) {  // 8 hex digits, little-endian bytes
  uint32_t value = 0;
  for (int i = 0; i < 4; ++i)
    value |= static_cast<uint32_t>(nibble(text[2 * i]) << 4 | nibble(text[2 * i + 1])) << (8 * i);
  return value;
}

}  // namespace

unsigned GdbServer::listen(unsigned port) {
  m_listen_fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (m_listen_fd < 0) throw std::runtime_error("GDB server: cannot create a socket");
  const int yes = 1;
  ::setsockopt(m_listen_fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<uint16_t>(port));
  if (port > 65535 || ::bind(m_listen_fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(m_listen_fd, 1) != 0)
    throw std::runtime_error("GDB server: cannot listen on 127.0.0.1:" + std::to_string(port) + ": " +
                             std::strerror(errno));
  socklen_t length = sizeof address;
  ::getsockname(m_listen_fd, reinterpret_cast<sockaddr*>(&address), &length);
  return ntohs(address.sin_port);
}

std::string GdbServer::read_packet() {
  std::string data;
  char c = 0;
  while (true) {                                  // skip to the start of a packet (acks, Ctrl-C)
    if (::read(m_fd, &c, 1) != 1) return "\x04";  // the connection closed
    if (c == '$') break;
  }
  while (::read(m_fd, &c, 1) == 1 && c != '#') data += c;
  char checksum[2];
  if (::read(m_fd, checksum, 2) != 2) return "\x04";
  ::write(m_fd, "+", 1);
  return data;
}

void GdbServer::send_packet(const std::string& data) {
  unsigned sum = 0;
  for (char c : data) sum += static_cast<unsigned char>(c);
  std::string packet = "$" + data + "#";
  packet += HEX[(sum >> 4) & 15];
  packet += HEX[sum & 15];
  for (int attempt = 0; attempt < 3; ++attempt) {
    if (::write(m_fd, packet.data(), packet.size()) != static_cast<ssize_t>(packet.size())) return;
    char ack = 0;
    if (::read(m_fd, &ack, 1) != 1 || ack == '+') return;
  }
}

std::string GdbServer::registers() const {
  std::string out;
  for (unsigned n = 0; n < 16; ++n) out += hex_word(m_target.core.reg(n));
  return out + hex_word(m_target.core.cpsr());
}

std::string GdbServer::stop_reply() const {
  if (m_target.exited()) {
    char text[8];
    std::snprintf(text, sizeof text, "W%02x", m_target.status() & 0xffu);
    return text;
  }
  return "S05";  // SIGTRAP: a breakpoint, a step, or the start
}

bool GdbServer::run(bool single_step, uint64_t& budget) {
  do {
    if (budget == 0) return false;
    --budget;
    m_target.core.step();
  } while (!single_step && !m_target.exited() && !m_breakpoints.count(m_target.core.reg(15)));
  return true;
}

std::string GdbServer::handle(const std::string& packet, bool& resume, bool& step, bool& stop_serving) {
  ArmCore& core = m_target.core;
  const char kind = packet.empty() ? '\0' : packet[0];
  const std::string args = packet.size() > 1 ? packet.substr(1) : "";
  switch (kind) {
    case '?': return stop_reply();
    case 'g': return registers();
    case 'G':
      if (args.size() < 17 * 8) return "E01";
      for (unsigned n = 0; n < 16; ++n) core.set_reg(n, word_from_hex(args.substr(8 * n, 8)));
      core.set_cpsr(word_from_hex(args.substr(16 * 8, 8)));
      return "OK";
    case 'p': {
      uint64_t n = 0;
      if (!parse_hex(args, n) || n > 16) return "E01";
      return hex_word(n == 16 ? core.cpsr() : core.reg(static_cast<unsigned>(n)));
    }
    case 'P': {
      const size_t eq = args.find('=');
      uint64_t n = 0;
      if (eq == std::string::npos || !parse_hex(args.substr(0, eq), n) || n > 16 || args.size() < eq + 9) return "E01";
      const uint32_t value = word_from_hex(args.substr(eq + 1, 8));
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
          length > 0x1000 || address + length > (1ull << 32))
        return "E01";
      std::string out;
      for (uint64_t i = 0; i < length; ++i) {
        const auto at = static_cast<uint32_t>(address + i);
        if (kind == 'm') {
          uint32_t byte = 0;
          if (!m_target.memory.read(at, 1, byte)) return out.empty() ? "E01" : out;  // as far as memory goes
          out += HEX[(byte >> 4) & 15];
          out += HEX[byte & 15];
        } else {
          if (colon == std::string::npos || args.size() < colon + 1 + 2 * (i + 1)) return "E01";
          const int high = nibble(args[colon + 1 + 2 * i]), low = nibble(args[colon + 2 + 2 * i]);
          if (high < 0 || low < 0 || !m_target.memory.write(at, 1, static_cast<uint32_t>(high << 4 | low)))
            return "E01";
        }
      }
      return kind == 'm' ? out : "OK";
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
      if (!args.empty()) {
        uint64_t address = 0;
        if (!parse_hex(args, address)) return "E01";
        core.set_reg(15, static_cast<uint32_t>(address));
      }
      resume = true;
      step = kind == 's';
      return "";
    case 'k':
      m_killed = true;
      stop_serving = true;
      return "";
    case 'D': stop_serving = true; return "OK";
    case 'H': return "OK";
    case 'q':
      if (packet.rfind("qSupported", 0) == 0) return "PacketSize=4000;qXfer:features:read+";
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

bool GdbServer::serve(uint64_t instruction_limit) {
  m_fd = ::accept(m_listen_fd, nullptr, nullptr);
  if (m_fd < 0) throw std::runtime_error(std::string("GDB server: accept failed: ") + std::strerror(errno));
  uint64_t budget = instruction_limit;
  while (true) {
    const std::string packet = read_packet();
    if (packet == "\x04") break;  // GDB went away: the program runs on
    bool resume = false, step = false, stop_serving = false;
    const std::string reply = handle(packet, resume, step, stop_serving);
    if (resume) {
      if (!run(step, budget)) {
        send_packet("X18");  // SIGXCPU: the instruction limit
        break;
      }
      send_packet(stop_reply());
      if (m_target.exited()) break;
      continue;
    }
    if (!(packet == "k")) send_packet(reply);
    if (stop_serving) break;
  }
  ::close(m_fd);
  ::close(m_listen_fd);
  m_fd = m_listen_fd = -1;
  return !m_killed;
}

}  // namespace tessera::iss
