// Semihosting (tlm/host/iss/semihosting.h) served over a plain memory, as
// the ISS serves a program's calls: the write path's lengths (once a
// SYS_WRITE of more than 4,096 bytes wrote nothing and returned -1 with
// errno 14), its bad handles and faults.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "host/iss/semihosting.h"

namespace {

using tessera::iss::Semihosting;
namespace sh = tessera::iss::semihosting;

class Memory : public tessera::iss::SemihostingPort {
 public:
  std::vector<uint8_t> bytes = std::vector<uint8_t>(1u << 20);
  bool read_memory(uint32_t address, uint8_t* data, unsigned count) override {
    if (uint64_t{address} + count > bytes.size()) return false;
    std::memcpy(data, bytes.data() + address, count);
    return true;
  }
  bool write_memory(uint32_t address, const uint8_t* data, unsigned count) override {
    if (uint64_t{address} + count > bytes.size()) return false;
    std::memcpy(bytes.data() + address, data, count);
    return true;
  }
  uint64_t elapsed_cycles() override { return 0; }
  uint32_t clock_hz() override { return 200'000'000; }
  void put_word(uint32_t address, uint32_t value) {
    for (unsigned i = 0; i < 4; ++i) bytes[address + i] = static_cast<uint8_t>(value >> (8 * i));
  }
};

constexpr uint32_t BLOCK = 0x100, NAME = 0x200, DATA = 0x10000;

struct Fixture : ::testing::Test {
  Memory memory;
  Semihosting semihosting{memory};
  std::string out, err;
  Fixture() {
    semihosting.console = [this](int stream, const std::string& text) { (stream == 2 ? err : out) += text; };
  }
  uint32_t open(const std::string& name, uint32_t mode) {
    std::memcpy(memory.bytes.data() + NAME, name.data(), name.size());
    memory.put_word(BLOCK, NAME);
    memory.put_word(BLOCK + 4, mode);
    memory.put_word(BLOCK + 8, static_cast<uint32_t>(name.size()));
    return semihosting.serve(sh::open, BLOCK);
  }
  uint32_t write(uint32_t handle, uint32_t address, uint32_t length) {
    memory.put_word(BLOCK, handle);
    memory.put_word(BLOCK + 4, address);
    memory.put_word(BLOCK + 8, length);
    return semihosting.serve(sh::write, BLOCK);
  }
  // `length` bytes of a pattern no two neighbouring 4 KB pieces share.
  std::string fill(uint32_t length) {
    std::string text(length, '\0');
    for (uint32_t i = 0; i < length; ++i) text[i] = static_cast<char>('a' + (i / 7 + i / 4096) % 26);
    std::memcpy(memory.bytes.data() + DATA, text.data(), length);
    return text;
  }
};

TEST_F(Fixture, AWriteOfAnyLengthReachesTheConsoleWhole) {
  const uint32_t stdout_handle = open(sh::CONSOLE, 4);
  const uint32_t stderr_handle = open(sh::CONSOLE, 8);
  ASSERT_NE(stdout_handle, 0xffffffffu);
  for (uint32_t length : {0u, 1u, 4095u, 4096u, 4097u, 10'000u, 300'000u}) {
    out.clear();
    const std::string text = fill(length);
    EXPECT_EQ(write(stdout_handle, DATA, length), 0u) << length << " bytes: all written";
    EXPECT_EQ(out.size(), text.size()) << length << " bytes";
    EXPECT_TRUE(out == text) << length << " bytes: not the bytes written";
  }
  const std::string text = fill(70'000);
  EXPECT_EQ(write(stderr_handle, DATA, 70'000), 0u);
  EXPECT_EQ(err.size(), text.size());
  EXPECT_TRUE(err == text);
}

TEST_F(Fixture, AWriteOfAnyLengthReachesASinkWhole) {
  std::string received;
  semihosting.offer_sink(":test/sink", [&](const std::string& data) { received += data; });
  const uint32_t handle = open(":test/sink", 4);
  ASSERT_NE(handle, 0xffffffffu);
  const std::string text = fill(200'000);
  EXPECT_EQ(write(handle, DATA, 200'000), 0u);
  EXPECT_EQ(received.size(), text.size());
  EXPECT_TRUE(received == text);
}

TEST_F(Fixture, AWriteFromMissingMemoryIsAFault) {
  const uint32_t handle = open(sh::CONSOLE, 4);
  EXPECT_EQ(write(handle, 0x200000, 16), 0xffffffffu);
  EXPECT_EQ(semihosting.serve(sh::errno_value, 0), uint32_t(sh::ERROR_FAULT));
  EXPECT_EQ(out, "");
  // Running off the end of memory part way: what could be read is written,
  // the rest is reported not written.
  const uint32_t start = static_cast<uint32_t>(memory.bytes.size()) - 5000;
  EXPECT_EQ(write(handle, start, 10'000), 10'000u - 4096u);
  EXPECT_EQ(out.size(), 4096u);
  EXPECT_EQ(semihosting.serve(sh::errno_value, 0), uint32_t(sh::ERROR_FAULT));
}

TEST_F(Fixture, AWriteToABadHandleFails) {
  EXPECT_EQ(write(7, DATA, 16), 0xffffffffu);
  EXPECT_EQ(semihosting.serve(sh::errno_value, 0), uint32_t(sh::ERROR_BAD_HANDLE));
}

}  // namespace
