// What software running on the host model sees: the device layer, compiled
// one of two ways (tlm/host/README.md, "Two host models"):
//
// - host-compiled (host.model=native, the default): application and driver
//   code is native C++ that calls these functions for every operation whose
//   time matters; each call advances the host's local time by the cost model
//   (compute) or by the bus (memory and device accesses);
// - cross-compiled for the ARM922T and run on the instruction-set simulator
//   (host.model=iss; TESSERA_HOST_ISS defined): the same calls are plain
//   volatile loads and stores inlined into the code, compute() is nothing
//   (the instructions themselves take the time), and waiting for an
//   interrupt is the interrupt controller and CP15's wait-for-interrupt
//   (sw_driver/runtime).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace tessera {

// Operation classes of the ARM922T cost model. Loads and stores are not
// listed: they are charged by the memory functions below, which also model
// the data cache and the write buffer.
enum class Op {
  alu,       // data processing (ADD, SUB, MOV, logic, shifts, compares)
  load_use,  // interlock: a loaded value used by the next instruction
  mul,       // MUL/MLA
  branch,    // taken branch
  call,      // function call and return
  fadd,      // soft-float add/subtract
  fmul,      // soft-float multiply
  fdiv,      // soft-float divide
  fsqrt,     // soft-float square root
  fcmp,      // soft-float compare
  fconv,     // soft-float int <-> float conversion
  count_
};

const char* op_name(Op op);

// Raised into the software when a bus access gets an error response.
class BusError : public std::runtime_error {
 public:
  BusError(const std::string& what, uint32_t address) : std::runtime_error(what), m_address(address) {}
  uint32_t address() const { return m_address; }

 private:
  uint32_t m_address;
};

// Bad input the program finds as it starts (an executable that does not fit
// the memory it is for, say): the host's program ends with status 2, the
// status of bad input (soc_sim's own), and this message.
class ProgramInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

#if !defined(TESSERA_HOST_ISS)

class HostApi {
 public:
  virtual ~HostApi() = default;

  virtual void compute(Op op, uint64_t count = 1) = 0;
  // Whole host cycles of the ISS-measured cost table (sw_driver/costs):
  // the driver's code as the ARM922T runs it, charged as measured.
  virtual void compute_cycles(uint64_t cycles) = 0;

  virtual uint32_t read32(uint32_t address) = 0;
  virtual uint16_t read16(uint32_t address) = 0;
  virtual uint8_t read8(uint32_t address) = 0;
  virtual void write32(uint32_t address, uint32_t value) = 0;
  virtual void write16(uint32_t address, uint16_t value) = 0;
  virtual void write8(uint32_t address, uint8_t value) = 0;
  // LDM/STM of `count` words (one bus burst where the access misses the cache).
  virtual void read_words(uint32_t address, uint32_t* words, unsigned count) = 0;
  virtual void write_words(uint32_t address, const uint32_t* words, unsigned count) = 0;
  // A store train: for each k < count, compute_cycles(cycles[k]) (no call
  // when it is 0), then write32(address + k * stride, values[k]). Exactly
  // those calls, which is what it makes by default; a host model may
  // simulate the train as a unit, with the same times and counts
  // (tlm/host/README.md, "Store trains").
  virtual void write32_train(uint32_t address, uint32_t stride, const uint32_t* values, const uint64_t* cycles,
                             unsigned count) {
    for (unsigned k = 0; k < count; ++k) {
      if (cycles[k] != 0) compute_cycles(cycles[k]);
      write32(address + k * stride, values[k]);
    }
  }

  // A copy of `words` words from `from` (system memory, through the cache)
  // to `to` (a device), as LDM/STM of eight registers do it: for each block
  // k of up to eight words, load_span(from + 32 k, 4, n), write_words(to +
  // 32 k, those words, n), then compute_cycles(cycles[k]) when it is not 0.
  // Exactly those calls, which is what it makes by default; a host model
  // may simulate the copy as a unit, with the same times and counts
  // (tlm/host/README.md, "The frame copy").
  virtual void copy_words(uint32_t to, uint32_t from, uint32_t words, const uint64_t* cycles) {
    for (uint32_t k = 0; 8 * k < words; ++k) {
      const unsigned count = std::min<uint32_t>(8, words - 8 * k);
      const auto* data = reinterpret_cast<const uint32_t*>(load_span(from + 32 * k, 4, count));
      write_words(to + 32 * k, data, count);
      if (cycles[k] != 0) compute_cycles(cycles[k]);
    }
  }

  // Spans, for code that walks runs of consecutive elements (a software
  // rasterizer's spans): charged as `count` loads (stores) of `size` bytes at
  // consecutive addresses from `address`, through the cache and write buffer
  // like the single accesses above, but accounted once per cache line. They
  // return a pointer to the data in system memory, valid until the host's
  // next call, through which the caller reads (writes) the elements.
  // System memory only; anything else throws std::invalid_argument.
  virtual const uint8_t* load_span(uint32_t address, unsigned size, unsigned count) = 0;
  virtual uint8_t* store_span(uint32_t address, unsigned size, unsigned count) = 0;

  // Sleeps until interrupt line `line` is high (level-sensitive); the time
  // is counted as idle.
  virtual void wait_irq(unsigned line) = 0;
  virtual bool irq_pending(unsigned line) = 0;

  // Host's local time in seconds (simulated time plus its quantum offset).
  virtual double now_seconds() const = 0;
  virtual double clock_hz() const = 0;
  // The same in whole host cycles from some start (only differences mean
  // anything): what driver code that times itself reads, in integers as
  // the ARM922T would.
  virtual uint64_t now_cycles() const { return static_cast<uint64_t>(std::llround(now_seconds() * clock_hz())); }

  // The GL driver switches to `phase` (sw_driver/gl/frame_phases.h: a
  // static name) now, for a timeline; it costs the host nothing. Nothing by
  // default.
  virtual void driver_phase(const char* /*phase*/) {}
  // A GL or EGL entry point `name` (static) begins or ends, for a timeline;
  // it costs the host nothing. Nothing by default.
  virtual void driver_call(const char* /*name*/, bool /*begins*/) {}
};

#else

// On the ISS: every access is the instruction itself, through the core's
// data cache and write buffer to the bus; the out-of-line functions are in
// sw_driver/runtime/host_api_iss.cpp.
class HostApi {
 public:
  void compute(Op /*op*/, uint64_t /*count*/ = 1) {}
  void compute_cycles(uint64_t /*cycles*/) {}

  uint32_t read32(uint32_t address) { return *reinterpret_cast<const volatile uint32_t*>(address); }
  uint16_t read16(uint32_t address) { return *reinterpret_cast<const volatile uint16_t*>(address); }
  uint8_t read8(uint32_t address) { return *reinterpret_cast<const volatile uint8_t*>(address); }
  void write32(uint32_t address, uint32_t value) { *reinterpret_cast<volatile uint32_t*>(address) = value; }
  void write16(uint32_t address, uint16_t value) { *reinterpret_cast<volatile uint16_t*>(address) = value; }
  void write8(uint32_t address, uint8_t value) { *reinterpret_cast<volatile uint8_t*>(address) = value; }
  // LDM/STM, eight registers at a time.
  void read_words(uint32_t address, uint32_t* words, unsigned count);
  void write_words(uint32_t address, const uint32_t* words, unsigned count);

  const uint8_t* load_span(uint32_t address, unsigned /*size*/, unsigned /*count*/) {
    return reinterpret_cast<const uint8_t*>(address);
  }
  uint8_t* store_span(uint32_t address, unsigned /*size*/, unsigned /*count*/) {
    return reinterpret_cast<uint8_t*>(address);
  }

  void wait_irq(unsigned line);
  bool irq_pending(unsigned line);

  double now_seconds() const;
  double clock_hz() const;
  // Cycles since the program's start (the ISS's elapsed-cycles call).
  uint64_t now_cycles() const;
  // Nothing on the ISS: the phases are not handed out of the program.
  void driver_phase(const char* /*phase*/) {}
  void driver_call(const char* /*name*/, bool /*begins*/) {}
};

#endif

}  // namespace tessera
