// A HostApi for unit tests of driver code (the display driver, the back
// ends' drivers): system memory is a byte vector from address 0, every
// other address is a device register answered by `read_register`, and every
// access is appended to a log in program order, so that a test can check
// what the driver did to the hardware, word for word. Nothing is charged
// but the operation counts; interrupts are always pending (wait_irq returns
// at once, and is logged).
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/host_api.h"

namespace tessera::test {

class RecordingHost : public HostApi {
 public:
  struct Access {
    enum class Kind { read, write, read_words, write_words, load_span, store_span, wait_irq };
    Kind kind;
    uint32_t address = 0;         // the irq line for wait_irq
    unsigned bytes = 0;           // of one element: 1, 2 or 4
    uint32_t value = 0;           // read and write
    std::vector<uint32_t> words;  // read_words and write_words
    unsigned count = 0;           // elements of a span or words of a burst
  };

  explicit RecordingHost(uint32_t memory_bytes) : m_memory(memory_bytes, 0) {}

  // Answers a read outside system memory; unset, such a read throws.
  std::function<uint32_t(uint32_t address)> read_register;

  const std::vector<Access>& log() const { return m_log; }
  void clear_log() { m_log.clear(); }
  // Words loaded and stored by read*, write*, read_words and write_words,
  // since construction (clear_log leaves it): where it is kept, for a
  // HostCore's counter locations.
  const uint64_t* words_accessed() const { return &m_words_accessed; }
  uint64_t operations(Op op) const { return m_operations[static_cast<size_t>(op)]; }
  uint8_t* memory(uint32_t address, uint32_t bytes) { return at(address, bytes); }

  void compute(Op op, uint64_t count) override { m_operations[static_cast<size_t>(op)] += count; }
  void compute_cycles(uint64_t cycles) override { m_measured_cycles += cycles; }
  uint64_t measured_cycles() const { return m_measured_cycles; }

  uint32_t read32(uint32_t address) override { return read(address, 4); }
  uint16_t read16(uint32_t address) override { return static_cast<uint16_t>(read(address, 2)); }
  uint8_t read8(uint32_t address) override { return static_cast<uint8_t>(read(address, 1)); }
  void write32(uint32_t address, uint32_t value) override { write(address, value, 4); }
  void write16(uint32_t address, uint16_t value) override { write(address, value, 2); }
  void write8(uint32_t address, uint8_t value) override { write(address, value, 1); }

  void read_words(uint32_t address, uint32_t* words, unsigned count) override {
    for (unsigned i = 0; i < count; ++i) words[i] = value_at(address + 4 * i, 4);
    m_log.push_back({Access::Kind::read_words, address, 4, 0, std::vector<uint32_t>(words, words + count), count});
    m_words_accessed += count;
  }
  void write_words(uint32_t address, const uint32_t* words, unsigned count) override {
    if (in_memory(address, 4 * count)) std::memcpy(at(address, 4 * count), words, 4 * count);
    m_log.push_back({Access::Kind::write_words, address, 4, 0, std::vector<uint32_t>(words, words + count), count});
    m_words_accessed += count;
  }

  const uint8_t* load_span(uint32_t address, unsigned size, unsigned count) override {
    m_log.push_back({Access::Kind::load_span, address, size, 0, {}, count});
    return at(address, size * count);
  }
  uint8_t* store_span(uint32_t address, unsigned size, unsigned count) override {
    m_log.push_back({Access::Kind::store_span, address, size, 0, {}, count});
    return at(address, size * count);
  }

  void wait_irq(unsigned line) override { m_log.push_back({Access::Kind::wait_irq, line, 0, 0, {}, 0}); }
  bool irq_pending(unsigned) override { return true; }
  double now_seconds() const override { return 0; }
  double clock_hz() const override { return 192e6; }

 private:
  bool in_memory(uint32_t address, uint64_t bytes) const { return uint64_t{address} + bytes <= m_memory.size(); }
  uint8_t* at(uint32_t address, uint64_t bytes) {
    if (!in_memory(address, bytes))
      throw std::out_of_range("recording host: " + std::to_string(bytes) + " bytes at " + std::to_string(address) +
                              " are not in system memory");
    return m_memory.data() + address;
  }
  uint32_t value_at(uint32_t address, unsigned bytes) {
    if (!in_memory(address, bytes)) {
      if (!read_register) throw std::out_of_range("recording host: no register at " + std::to_string(address));
      return read_register(address);
    }
    uint32_t value = 0;
    std::memcpy(&value, at(address, bytes), bytes);
    return value;
  }
  uint32_t read(uint32_t address, unsigned bytes) {
    const uint32_t value = value_at(address, bytes);
    m_log.push_back({Access::Kind::read, address, bytes, value, {}, 1});
    ++m_words_accessed;
    return value;
  }
  void write(uint32_t address, uint32_t value, unsigned bytes) {
    if (in_memory(address, bytes)) std::memcpy(at(address, bytes), &value, bytes);
    m_log.push_back({Access::Kind::write, address, bytes, value, {}, 1});
    ++m_words_accessed;
  }

  std::vector<uint8_t> m_memory;
  std::vector<Access> m_log;
  uint64_t m_words_accessed = 0;
  uint64_t m_operations[static_cast<size_t>(Op::count_)] = {};
  uint64_t m_measured_cycles = 0;
};

}  // namespace tessera::test
