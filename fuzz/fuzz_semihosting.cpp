// Fuzz target: semihosting (tlm/host/iss/semihosting.h), the calls a
// program makes through the semihosting SWI, served over a 64 KiB memory
// with a file offered for reading and a sink for writing (never the host's
// files).
//
// Input: the first 1,024 bytes are the memory from address 0 (the rest
// of it zeros); then calls of 5 bytes each: the operation (a byte: one of
// semihosting.def's, or any number when its top bit is set) and the
// parameter (a 32-bit word; below 64 KiB unless its top bit is set, so
// that most blocks and buffers are in memory).
//
// Checks: nothing throws; the console and the sink get no more bytes than
// the writes asked for; SYS_WRITE and SYS_READ return at most the length
// asked (the bytes not written or not read) or -1; the memory outside
// the 64 KiB is never touched (the port refuses it); after SYS_EXIT the
// status is what was asked.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "host/iss/semihosting.h"

namespace {

namespace sh = tessera::iss::semihosting;

constexpr uint32_t MEMORY_BYTES = 1u << 16;
constexpr size_t IMAGE_BYTES = 1024;
constexpr uint32_t OPERATIONS[] = {
#define TESSERA_SEMIHOSTING(name, number) number,
#include "host/iss/semihosting.def"
#undef TESSERA_SEMIHOSTING
};

class Memory : public tessera::iss::SemihostingPort {
 public:
  std::vector<uint8_t> bytes = std::vector<uint8_t>(MEMORY_BYTES);
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
  uint64_t elapsed_cycles() override { return ++m_cycles * 1000; }
  uint32_t clock_hz() override { return 192'000'000; }

 private:
  uint64_t m_cycles = 0;
};

uint32_t word_at(const Memory& memory, uint32_t address) {
  if (uint64_t{address} + 4 > MEMORY_BYTES) return 0;
  uint32_t value;
  std::memcpy(&value, memory.bytes.data() + address, 4);
  return value;
}

}  // namespace

// NOLINTNEXTLINE(readability-identifier-naming): the name libFuzzer calls
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Memory memory;
  std::memcpy(memory.bytes.data(), data, std::min(size, IMAGE_BYTES));
  tessera::iss::Semihosting semihosting(memory);
  semihosting.host_files = false;
  semihosting.command_line = "fuzz --flag";
  uint64_t output = 0;
  semihosting.console = [&output](int, const std::string& text) { output += text.size(); };
  semihosting.warn = [](const std::string&) {};
  semihosting.offer_file(":fuzz/file", std::string(5000, 'f'));
  semihosting.offer_sink(":fuzz/sink", [&output](const std::string& text) { output += text.size(); });
  tessera::fuzz::ByteReader in(data + std::min(size, IMAGE_BYTES), size - std::min(size, IMAGE_BYTES));
  uint64_t asked = 0;
  while (!in.empty()) {
    const uint8_t pick = in.u8();
    const uint32_t op = pick & 0x80 ? pick & 0x7f : OPERATIONS[pick % (sizeof OPERATIONS / sizeof OPERATIONS[0])];
    const uint32_t raw = in.u32();
    const uint32_t parameter = raw & 0x80000000u ? raw : raw % MEMORY_BYTES;
    const uint32_t length = word_at(memory, parameter + 8);
    if (op == sh::write) asked += length;
    if (op == sh::writec) asked += 1;
    if (op == sh::write0) asked += MEMORY_BYTES;
    uint32_t result;
    try {
      result = semihosting.serve(op, parameter);
    } catch (const std::exception& error) {
      tessera::fuzz::fail(std::string("an exception escaped: ") + error.what());
    }
    if ((op == sh::write || op == sh::read) && result != 0xffffffffu && result > length)
      tessera::fuzz::fail("a write or read reports more bytes left than were asked for");
    if (output > asked) tessera::fuzz::fail("more output than the writes asked for");
    if (semihosting.exited()) break;
  }
  return 0;
}
