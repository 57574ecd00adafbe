// The GDB server (tlm/host/iss/gdb_server.h): its packet framing (once:
// checksums were never checked, packets had no size bound), its register
// and memory commands on bad data (non-hex register data set registers
// to 0xffffffff through a shift of -1), and the same over a socket as GDB
// speaks it, against the bare machine.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "host/iss/arm_core.h"
#include "host/iss/bare_machine.h"
#include "host/iss/gdb_server.h"

namespace {

using tessera::iss::ArmCore;
using tessera::iss::BareMachine;
using tessera::iss::GdbPacketReader;
using tessera::iss::GdbServer;
using Event = GdbPacketReader::Event;

// The packet as GDB frames it, its checksum computed here.
std::string framed(const std::string& data) {
  unsigned sum = 0;
  for (char c : data) sum += static_cast<unsigned char>(c);
  char checksum[3];
  std::snprintf(checksum, sizeof checksum, "%02x", sum & 0xffu);
  return "$" + data + "#" + checksum;
}

// The events of feeding `bytes`, one letter each: p packet, b bad checksum, t too long.
std::string events(GdbPacketReader& reader, const std::string& bytes, std::string* last_packet = nullptr) {
  std::string seen;
  for (char c : bytes) switch (reader.feed(c)) {
      case Event::none: break;
      case Event::packet:
        seen += 'p';
        if (last_packet) *last_packet = reader.packet();
        break;
      case Event::bad_checksum: seen += 'b'; break;
      case Event::too_long: seen += 't'; break;
    }
  return seen;
}

TEST(GdbPacketReader, AGoodPacketIsReturnedBetweenAcksAndInterrupts) {
  GdbPacketReader reader;
  std::string packet;
  EXPECT_EQ(events(reader, "+\x03-" + framed("m1000,4") + "+", &packet), "p");
  EXPECT_EQ(packet, "m1000,4");
  // "$g#67": GDB's own framing of g, checksum in either case of hex.
  EXPECT_EQ(events(reader, "$g#67$g#67", &packet), "pp");
  EXPECT_EQ(packet, "g");
  EXPECT_EQ(events(reader, "$?#3F", &packet), "p");
  EXPECT_EQ(packet, "?");
}

TEST(GdbPacketReader, ABadChecksumIsReportedNotReturned) {
  GdbPacketReader reader;
  std::string packet = "none";
  // An M packet with one data digit changed in transit: its checksum no longer matches.
  std::string corrupted = framed("M1000,4:01020304");
  corrupted[10] = '9';
  EXPECT_EQ(events(reader, corrupted, &packet), "b");
  EXPECT_EQ(packet, "none");
  EXPECT_EQ(events(reader, "$g#68", &packet), "b");
  EXPECT_EQ(events(reader, "$g#zz", &packet), "b");
  EXPECT_EQ(events(reader, "$g#6", &packet), "");  // incomplete: nothing yet
  EXPECT_EQ(events(reader, "7", &packet), "p");
  EXPECT_EQ(packet, "g");
}

TEST(GdbPacketReader, AnOversizePacketIsDroppedInBoundedMemory) {
  GdbPacketReader reader;
  std::string packet;
  const std::string huge(GdbPacketReader::MAX_DATA + 1, 'a');
  EXPECT_EQ(events(reader, framed(huge), &packet), "t");
  EXPECT_LE(reader.packet().capacity(), 2 * GdbPacketReader::MAX_DATA);
  // Far longer without an end: nothing grows, nothing is returned.
  for (int i = 0; i < 64; ++i) EXPECT_EQ(events(reader, (i == 0 ? "$" : "") + huge), "");
  EXPECT_LE(reader.packet().capacity(), 2 * GdbPacketReader::MAX_DATA);
  EXPECT_EQ(events(reader, "#00" + framed("g"), &packet), "tp");
  EXPECT_EQ(packet, "g");
  // Exactly the limit is a packet.
  const std::string largest(GdbPacketReader::MAX_DATA, 'b');
  EXPECT_EQ(events(reader, framed(largest), &packet), "p");
  EXPECT_EQ(packet, largest);
}

struct Machine {
  BareMachine memory;
  ArmCore core{memory};
  GdbServer server;
  GdbServer::Target target{core, memory, [this] { core.step(); }, [this] { return memory.exited(); },
                           [this] { return memory.status(); }};
  Machine() {
    core.reset();
    for (unsigned n = 0; n < 16; ++n) core.set_reg(n, 0x1000 + n);
  }
};

TEST(GdbServerCommands, NonHexRegisterDataIsAnErrorAndChangesNothing) {
  Machine m;
  const uint32_t cpsr = m.core.cpsr();
  std::string good;
  for (unsigned n = 0; n < 17; ++n) good += "78563412";
  std::string bad = good;
  bad[8 * 5 + 3] = 'z';
  EXPECT_EQ(m.server.reply(m.target, "G" + bad), "E01");
  for (unsigned n = 0; n < 16; ++n) EXPECT_EQ(m.core.reg(n), 0x1000 + n) << "r" << n;
  EXPECT_EQ(m.core.cpsr(), cpsr);
  EXPECT_EQ(m.server.reply(m.target, "G" + std::string(17 * 8, 'z')), "E01");
  EXPECT_EQ(m.core.reg(0), 0x1000u);
  EXPECT_EQ(m.server.reply(m.target, "P3=zz563412"), "E01");
  EXPECT_EQ(m.server.reply(m.target, "P3=785634"), "E01");  // too short
  EXPECT_EQ(m.core.reg(3), 0x1003u);
  EXPECT_EQ(m.server.reply(m.target, "P3=78563412"), "OK");
  EXPECT_EQ(m.core.reg(3), 0x12345678u);
  EXPECT_EQ(m.server.reply(m.target, "M100,2:0g"), "E01");
  EXPECT_EQ(m.server.reply(m.target, "m100,2"), "0000");
  // Good data still sets every register (little-endian words).
  std::string words;
  for (unsigned n = 0; n < 16; ++n) {
    char word[9];
    std::snprintf(word, sizeof word, "%02x000000", n + 1);
    words += word;
  }
  EXPECT_EQ(m.server.reply(m.target, "G" + words + "d3000000"), "OK");
  for (unsigned n = 0; n < 15; ++n) EXPECT_EQ(m.core.reg(n), n + 1) << "r" << n;
  EXPECT_EQ(m.core.cpsr() & 0xffu, 0xd3u);
}

// A client speaking to the server over TCP as GDB does.
class Client {
 public:
  explicit Client(unsigned port) {
    m_fd = ::socket(AF_INET, SOCK_STREAM, 0);
    timeval timeout{10, 0};  // a server that never answers fails the test instead of hanging it
    ::setsockopt(m_fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(static_cast<uint16_t>(port));
    connected = ::connect(m_fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  }
  ~Client() { ::close(m_fd); }
  void send(const std::string& bytes) {
    for (size_t sent = 0; sent < bytes.size();) {
      const ssize_t n = ::send(m_fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) return;
      sent += static_cast<size_t>(n);
    }
  }
  char byte() {
    char c = 0;
    return ::recv(m_fd, &c, 1, 0) == 1 ? c : '\0';
  }
  // The server's next reply packet's data (acknowledged).
  std::string reply() {
    char c;
    while ((c = byte()) != '$')
      if (c == '\0') return "<nothing>";
    std::string data;
    while ((c = byte()) != '#')
      if (c == '\0')
        return "<cut>";
      else
        data += c;
    byte();
    byte();
    send("+");
    return data;
  }
  bool connected = false;

 private:
  int m_fd;
};

TEST(GdbServerSession, BadChecksumsAreRefusedAndOversizePacketsDroppedOverTheWire) {
  Machine m;
  const unsigned port = m.server.listen(0);
  GdbServer::End end = GdbServer::End::exited;
  std::thread serving([&] { end = m.server.serve(m.target, 1000); });
  {
    Client gdb(port);
    ASSERT_TRUE(gdb.connected);
    // A corrupted M packet: '-' and memory unchanged; sent again intact: '+' and written.
    std::string corrupted = framed("M100,4:01020304");
    corrupted[12] = '9';
    gdb.send(corrupted);
    EXPECT_EQ(gdb.byte(), '-');
    gdb.send(framed("m100,4"));
    EXPECT_EQ(gdb.byte(), '+');
    EXPECT_EQ(gdb.reply(), "00000000");
    gdb.send(framed("M100,4:01020304"));
    EXPECT_EQ(gdb.byte(), '+');
    EXPECT_EQ(gdb.reply(), "OK");
    gdb.send(framed("m100,4"));
    EXPECT_EQ(gdb.byte(), '+');
    EXPECT_EQ(gdb.reply(), "01020304");
    // 1 MiB of data without an end, then its end: refused with an error, and the server serves on.
    gdb.send("$M200,4:" + std::string(1u << 20, '0') + "#00");
    EXPECT_EQ(gdb.byte(), '+');
    EXPECT_EQ(gdb.reply(), "E01");
    gdb.send(framed("m100,2"));
    EXPECT_EQ(gdb.byte(), '+');
    EXPECT_EQ(gdb.reply(), "0102");
    gdb.send(framed("D"));
    EXPECT_EQ(gdb.byte(), '+');
    EXPECT_EQ(gdb.reply(), "OK");
  }
  serving.join();
  EXPECT_EQ(end, GdbServer::End::detached);
}

}  // namespace
