// Fuzz target: the GDB server's packet layer (tlm/host/iss/gdb_server.h):
// the bytes a client sends, through GdbPacketReader's framing, and every
// packet it returns answered by GdbServer::reply against a core over the
// bare machine (1 MiB of RAM), as serve() answers it (a c or s packet is
// answered without running the program).
//
// Input: the bytes from the client, as on the wire (framed packets with
// their checksums, acknowledgements, Ctrl-C, noise).
//
// Checks: the reader never holds more than MAX_DATA bytes of a packet; a
// packet it returns had a matching checksum (framed again it reads back
// the same); every reply is one the framing can carry (no '$', '#', '}' or
// '*', which would need escaping) and reads back through a reader
// unchanged; nothing throws.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "fuzz_support.h"
#include "host/iss/arm_core.h"
#include "host/iss/bare_machine.h"
#include "host/iss/gdb_server.h"

namespace {

using tessera::iss::GdbPacketReader;

std::string framed(const std::string& data) {
  unsigned sum = 0;
  for (char c : data) sum += static_cast<unsigned char>(c);
  char checksum[3];
  std::snprintf(checksum, sizeof checksum, "%02x", sum & 0xffu);
  return "$" + data + "#" + checksum;
}

// The data framed and read back through a fresh reader.
std::string read_back(const std::string& data) {
  GdbPacketReader reader;
  std::string packet = "<none>";
  for (char c : framed(data))
    if (reader.feed(c) == GdbPacketReader::Event::packet) packet = reader.packet();
  return packet;
}

}  // namespace

// NOLINTNEXTLINE(readability-identifier-naming): the name libFuzzer calls
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tessera::iss::BareMachine machine;
  tessera::iss::ArmCore core(machine);
  core.reset();
  tessera::iss::GdbServer server;
  const tessera::iss::GdbServer::Target target{core, machine, [&core] { core.step(); },
                                               [&machine] { return machine.exited(); },
                                               [&machine] { return machine.status(); }};
  GdbPacketReader reader;
  for (size_t i = 0; i < size; ++i) {
    const GdbPacketReader::Event event = reader.feed(static_cast<char>(data[i]));
    if (reader.packet().size() > GdbPacketReader::MAX_DATA) tessera::fuzz::fail("the reader holds too much");
    if (event != GdbPacketReader::Event::packet) continue;
    const std::string packet = reader.packet();
    if (read_back(packet) != packet) tessera::fuzz::fail("a packet does not read back framed again");
    const std::string reply = server.reply(target, packet);
    if (reply.find_first_of("$#}*") != std::string::npos) tessera::fuzz::fail("a reply the framing cannot carry");
    if (read_back(reply) != reply) tessera::fuzz::fail("a reply does not read back");
  }
  return 0;
}
