// Tests of tessera::protocol_checker.
//
// The SystemC kernel cannot be reset, so sc_main elaborates a pool of
// benches (initiator -> checker -> target) once and then runs GoogleTest.
// Each test takes a bench nobody has used, spawns its stimulus as SystemC
// threads and runs the simulation until it starves; time is therefore
// asserted relative to the moment a test started, never absolutely.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <systemc>
#include <tlm>

#include "checker/protocol_checker.h"

namespace {

using sc_core::SC_NS;
using sc_core::sc_time;
using tessera::ProtocolRule;

constexpr std::size_t MEMORY_SIZE = 256;
constexpr std::size_t BENCH_POOL_SIZE = 48;
constexpr double TARGET_LATENCY_NS = 10.0;
// tlm_command has no fixed underlying type, so only values that fit its
// two bits are representable (UBSan rejects 7); 3 is the one unused.
constexpr auto INVALID_COMMAND = static_cast<tlm::tlm_command>(3);

// The initiator mirrors the checker's target socket and records the
// invalidations that reach it.
class Initiator : public sc_core::sc_module {
 public:
  tlm_utils::simple_initiator_socket<Initiator> out;
  std::vector<std::pair<sc_dt::uint64, sc_dt::uint64>> invalidations;

  explicit Initiator(const sc_core::sc_module_name& name) : sc_core::sc_module(name), out("out") {
    out.register_invalidate_direct_mem_ptr(this, &Initiator::invalidate_direct_mem_ptr);
  }

 private:
  void invalidate_direct_mem_ptr(sc_dt::uint64 start, sc_dt::uint64 end) { invalidations.emplace_back(start, end); }
};

// Everything a misbehaving target can do wrong; `none` is a correct memory.
enum class Misbehaviour {
  none,
  rewrite_address,
  leave_incomplete,
  change_command,
  change_data_ptr,
  change_data_length,
  change_byte_enable_ptr,
  change_byte_enable_length,
  change_streaming_width,
  rewind_time,
  negative_delay,
  dbg_wait_delta,
  dbg_wait_time,
  dbg_overcount,
  dmi_reversed_range,
  dmi_denied_reversed_range,
  dmi_outside_range,
  dmi_no_access,
  dmi_null_ptr,
  dmi_denied,
};

class TagExtension : public tlm::tlm_extension<TagExtension> {
 public:
  explicit TagExtension(int tag) : value(tag) {}
  tlm::tlm_extension_base* clone() const override { return new TagExtension(value); }
  void copy_from(const tlm::tlm_extension_base& other) override {
    value = static_cast<const TagExtension&>(other).value;
  }
  int value;
};

// A memory that answers every request it can and errors the rest, with one
// deliberate fault selected by `fault`.
class Target : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<Target> in;
  Misbehaviour fault = Misbehaviour::none;
  sc_time stall = sc_core::SC_ZERO_TIME;
  std::array<unsigned char, MEMORY_SIZE> memory{};

  unsigned b_transport_calls = 0;
  unsigned transport_dbg_calls = 0;
  const tlm::tlm_generic_payload* received_payload = nullptr;
  sc_time received_delay;
  int received_tag = -1;

  explicit Target(const sc_core::sc_module_name& name) : sc_core::sc_module(name), in("in") {
    in.register_b_transport(this, &Target::b_transport);
    in.register_transport_dbg(this, &Target::transport_dbg);
    in.register_get_direct_mem_ptr(this, &Target::get_direct_mem_ptr);
  }

  void invalidate(sc_dt::uint64 start, sc_dt::uint64 end) { in->invalidate_direct_mem_ptr(start, end); }

 private:
  void b_transport(tlm::tlm_generic_payload& trans, sc_time& delay) {
    ++b_transport_calls;
    received_payload = &trans;
    received_delay = delay;
    if (const auto* tag = trans.get_extension<TagExtension>()) received_tag = tag->value;
    if (stall != sc_core::SC_ZERO_TIME) wait(stall);

    trans.set_response_status(execute(trans));
    trans.set_dmi_allowed(true);
    delay += sc_time(TARGET_LATENCY_NS, SC_NS);
    misbehave(trans, delay);
  }

  tlm::tlm_response_status execute(tlm::tlm_generic_payload& trans) {
    const tlm::tlm_command command = trans.get_command();
    if (command == tlm::TLM_IGNORE_COMMAND) return tlm::TLM_OK_RESPONSE;
    if (command != tlm::TLM_READ_COMMAND && command != tlm::TLM_WRITE_COMMAND) return tlm::TLM_COMMAND_ERROR_RESPONSE;
    const unsigned int length = trans.get_data_length();
    if (trans.get_data_ptr() == nullptr || length == 0) return tlm::TLM_GENERIC_ERROR_RESPONSE;
    if (trans.get_address() >= MEMORY_SIZE || length > MEMORY_SIZE - trans.get_address())
      return tlm::TLM_ADDRESS_ERROR_RESPONSE;
    if (trans.get_streaming_width() != length) return tlm::TLM_BURST_ERROR_RESPONSE;
    const unsigned char* enables = trans.get_byte_enable_ptr();
    const unsigned int enable_length = trans.get_byte_enable_length();
    if (enables != nullptr && enable_length == 0) return tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE;

    unsigned char* data = trans.get_data_ptr();
    unsigned char* cell = memory.data() + trans.get_address();
    for (unsigned int i = 0; i < length; ++i) {
      if (enables != nullptr && enables[i % enable_length] != TLM_BYTE_ENABLED) continue;
      if (command == tlm::TLM_READ_COMMAND)
        data[i] = cell[i];
      else
        cell[i] = data[i];
    }
    return tlm::TLM_OK_RESPONSE;
  }

  void misbehave(tlm::tlm_generic_payload& trans, sc_time& delay) {
    switch (fault) {
      case Misbehaviour::rewrite_address: trans.set_address(trans.get_address() + 0x1000); break;
      case Misbehaviour::leave_incomplete: trans.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE); break;
      case Misbehaviour::change_command: trans.set_command(tlm::TLM_IGNORE_COMMAND); break;
      case Misbehaviour::change_data_ptr: trans.set_data_ptr(m_scratch.data()); break;
      case Misbehaviour::change_data_length: trans.set_data_length(trans.get_data_length() - 1); break;
      case Misbehaviour::change_byte_enable_ptr: trans.set_byte_enable_ptr(m_scratch.data()); break;
      case Misbehaviour::change_byte_enable_length:
        trans.set_byte_enable_length(trans.get_byte_enable_length() + 1);
        break;
      case Misbehaviour::change_streaming_width: trans.set_streaming_width(1); break;
      case Misbehaviour::rewind_time:
        wait(sc_time(5, SC_NS));
        delay = sc_core::SC_ZERO_TIME;
        break;
      case Misbehaviour::negative_delay: delay -= sc_time(1, sc_core::SC_US); break;
      default: break;
    }
  }

  unsigned int transport_dbg(tlm::tlm_generic_payload& trans) {
    ++transport_dbg_calls;
    const tlm::tlm_command command = trans.get_command();
    if (command != tlm::TLM_READ_COMMAND && command != tlm::TLM_WRITE_COMMAND) return 0;
    if (trans.get_data_ptr() == nullptr || trans.get_address() >= MEMORY_SIZE) return 0;
    if (fault == Misbehaviour::dbg_wait_delta) wait(sc_core::SC_ZERO_TIME);
    if (fault == Misbehaviour::dbg_wait_time) wait(sc_time(1, SC_NS));
    const auto address = static_cast<std::size_t>(trans.get_address());
    const auto count = static_cast<unsigned int>(std::min<std::size_t>(trans.get_data_length(), MEMORY_SIZE - address));
    if (command == tlm::TLM_READ_COMMAND)
      std::memcpy(trans.get_data_ptr(), memory.data() + address, count);
    else
      std::memcpy(memory.data() + address, trans.get_data_ptr(), count);
    return fault == Misbehaviour::dbg_overcount ? count + 4 : count;
  }

  bool get_direct_mem_ptr(tlm::tlm_generic_payload& /*trans*/, tlm::tlm_dmi& dmi) {
    dmi.set_dmi_ptr(memory.data());
    dmi.set_start_address(0);
    dmi.set_end_address(MEMORY_SIZE - 1);
    dmi.allow_read_write();
    dmi.set_read_latency(sc_time(TARGET_LATENCY_NS, SC_NS));
    dmi.set_write_latency(sc_time(TARGET_LATENCY_NS, SC_NS));
    switch (fault) {
      case Misbehaviour::dmi_reversed_range:
        dmi.set_start_address(0x80);
        dmi.set_end_address(0x10);
        return true;
      case Misbehaviour::dmi_denied_reversed_range:
        dmi.allow_none();
        dmi.set_start_address(0x80);
        dmi.set_end_address(0x10);
        return false;
      case Misbehaviour::dmi_outside_range:
        dmi.set_dmi_ptr(memory.data() + 0x80);
        dmi.set_start_address(0x80);
        return true;
      case Misbehaviour::dmi_no_access: dmi.allow_none(); return true;
      case Misbehaviour::dmi_null_ptr: dmi.set_dmi_ptr(nullptr); return true;
      case Misbehaviour::dmi_denied:
        // The default a target without DMI gives: the whole range denied.
        dmi.init();
        return false;
      default: return true;
    }
  }

  std::array<unsigned char, 8> m_scratch{};
};

class Bench : public sc_core::sc_module {
 public:
  Initiator cpu;
  tessera::ProtocolChecker<> checker;
  Target memory;

  explicit Bench(const sc_core::sc_module_name& name)
      : sc_core::sc_module(name), cpu("cpu"), checker("checker"), memory("memory") {
    cpu.out.bind(checker.in);
    checker.out.bind(memory.in);
  }

  std::string report() const {
    std::string text;
    for (const auto& message : checker.messages()) text += "\n  " + message;
    return text;
  }
};

std::vector<std::unique_ptr<Bench>>& bench_pool() {
  static std::vector<std::unique_ptr<Bench>> pool;
  return pool;
}

// Every test gets a bench of its own, so its checker has seen nothing else.
Bench& fresh_bench() {
  static std::size_t next = 0;
  auto& pool = bench_pool();
  if (next == pool.size()) throw std::runtime_error("bench pool exhausted; raise BENCH_POOL_SIZE");
  return *pool[next++];
}

void run(const std::vector<std::function<void()>>& threads) {
  for (const auto& thread : threads) sc_core::sc_spawn(thread);
  sc_core::sc_start();
}

void run(const std::function<void()>& thread) {
  run(std::vector<std::function<void()>>{thread});
}

// A correct request: the attributes an initiator must set before each use.
void prepare(tlm::tlm_generic_payload& trans, tlm::tlm_command command, sc_dt::uint64 address, unsigned char* data,
             unsigned int length) {
  trans.set_command(command);
  trans.set_address(address);
  trans.set_data_ptr(data);
  trans.set_data_length(length);
  trans.set_streaming_width(length);
  trans.set_byte_enable_ptr(nullptr);
  trans.set_byte_enable_length(0);
  trans.set_dmi_allowed(false);
  trans.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
}

void expect_only(const Bench& b, ProtocolRule rule) {
  EXPECT_EQ(b.checker.violation_count(), 1u) << b.report();
  EXPECT_EQ(b.checker.violation_count(rule), 1u) << b.report();
  if (b.checker.violation_count() == 1) {
    const std::string& message = b.checker.violations().front().message;
    EXPECT_NE(message.find(std::string(b.checker.name()) + ": " + tessera::to_string(rule) + ": "), std::string::npos)
        << message;
  }
}

TEST(ProtocolChecker, WriteAndReadPassUnchangedWithoutViolations) {
  Bench& b = fresh_bench();
  std::array<unsigned char, 4> written{0xde, 0xad, 0xbe, 0xef};
  std::array<unsigned char, 4> read_back{};
  tlm::tlm_generic_payload trans;
  sc_time start, write_delay, read_delay, write_done;
  tlm::tlm_response_status write_status{}, read_status{};

  run([&] {
    start = sc_core::sc_time_stamp();
    prepare(trans, tlm::TLM_WRITE_COMMAND, 0x20, written.data(), 4);
    write_delay = sc_time(5, SC_NS);
    b.cpu.out->b_transport(trans, write_delay);
    write_status = trans.get_response_status();
    EXPECT_EQ(b.memory.received_payload, &trans);
    EXPECT_EQ(b.memory.received_delay, sc_time(5, SC_NS));
    wait(write_delay);
    write_done = sc_core::sc_time_stamp();

    prepare(trans, tlm::TLM_READ_COMMAND, 0x20, read_back.data(), 4);
    read_delay = sc_core::SC_ZERO_TIME;
    b.cpu.out->b_transport(trans, read_delay);
    read_status = trans.get_response_status();
  });

  EXPECT_EQ(b.checker.violation_count(), 0u) << b.report();
  EXPECT_EQ(write_status, tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(read_status, tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(write_delay, sc_time(5 + TARGET_LATENCY_NS, SC_NS));
  EXPECT_EQ(write_done, start + sc_time(5 + TARGET_LATENCY_NS, SC_NS));
  EXPECT_EQ(read_delay, sc_time(TARGET_LATENCY_NS, SC_NS));
  EXPECT_EQ(b.memory.b_transport_calls, 2u);
  EXPECT_EQ(b.memory.memory[0x20], 0xde);
  EXPECT_EQ(b.memory.memory[0x23], 0xef);
  EXPECT_EQ(read_back, written);
}

TEST(ProtocolChecker, ExtensionsByteEnablesAndAddressRewriteAreLegal) {
  Bench& b = fresh_bench();
  b.memory.fault = Misbehaviour::rewrite_address;
  std::array<unsigned char, 4> written{1, 2, 3, 4};
  std::array<unsigned char, 4> enables{TLM_BYTE_ENABLED, TLM_BYTE_DISABLED, TLM_BYTE_ENABLED, TLM_BYTE_DISABLED};
  tlm::tlm_generic_payload trans;
  tlm::tlm_response_status status{};

  run([&] {
    prepare(trans, tlm::TLM_WRITE_COMMAND, 0x40, written.data(), 4);
    trans.set_byte_enable_ptr(enables.data());
    trans.set_byte_enable_length(4);
    trans.set_extension(new TagExtension(42));
    sc_time delay = sc_core::SC_ZERO_TIME;
    b.cpu.out->b_transport(trans, delay);
    status = trans.get_response_status();
  });

  EXPECT_EQ(b.checker.violation_count(), 0u) << b.report();
  EXPECT_EQ(status, tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(b.memory.received_tag, 42);
  EXPECT_EQ(trans.get_address(), 0x40u + 0x1000u);
  EXPECT_EQ(b.memory.memory[0x40], 1);
  EXPECT_EQ(b.memory.memory[0x41], 0);
  EXPECT_EQ(b.memory.memory[0x42], 3);
  EXPECT_EQ(b.memory.memory[0x43], 0);
}

// One deliberate mistake per case, made either by the initiator (request)
// or by the target (fault); each must be reported exactly once and the
// transaction must still be forwarded.
struct RuleCase {
  const char* name;
  ProtocolRule rule;
  std::function<void(tlm::tlm_generic_payload&, sc_time&)> spoil_request;
  Misbehaviour fault;
};

void keep_request(tlm::tlm_generic_payload&, sc_time&) {}

std::vector<RuleCase> b_transport_cases() {
  using gp = tlm::tlm_generic_payload;
  static unsigned char spare_enables[8] = {0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff};
  return {
      {"StaleResponseStatus", ProtocolRule::response_incomplete_on_entry,
       [](gp& t, sc_time&) { t.set_response_status(tlm::TLM_OK_RESPONSE); }, Misbehaviour::none},
      {"InvalidCommand", ProtocolRule::command_valid, [](gp& t, sc_time&) { t.set_command(INVALID_COMMAND); },
       Misbehaviour::none},
      {"NullDataPointer", ProtocolRule::data_ptr_non_null, [](gp& t, sc_time&) { t.set_data_ptr(nullptr); },
       Misbehaviour::none},
      {"ZeroDataLength", ProtocolRule::data_length_non_zero, [](gp& t, sc_time&) { t.set_data_length(0); },
       Misbehaviour::none},
      {"ZeroStreamingWidth", ProtocolRule::streaming_width_non_zero, [](gp& t, sc_time&) { t.set_streaming_width(0); },
       Misbehaviour::none},
      {"ByteEnablePointerWithoutLength", ProtocolRule::byte_enable_length_non_zero,
       [](gp& t, sc_time&) { t.set_byte_enable_ptr(spare_enables); }, Misbehaviour::none},
      {"ByteEnablesLongerThanData", ProtocolRule::byte_enable_length_within_data,
       [](gp& t, sc_time&) {
         t.set_byte_enable_ptr(spare_enables);
         t.set_byte_enable_length(8);
       },
       Misbehaviour::none},
      {"DmiHintLeftSet", ProtocolRule::dmi_hint_false_on_entry, [](gp& t, sc_time&) { t.set_dmi_allowed(true); },
       Misbehaviour::none},
      {"NegativeDelayOnEntry", ProtocolRule::delay_not_negative,
       [](gp&, sc_time& d) { d = sc_time(5, SC_NS) - sc_time(10, SC_NS); }, Misbehaviour::none},
      {"ResponseLeftIncomplete", ProtocolRule::response_complete_on_return, keep_request,
       Misbehaviour::leave_incomplete},
      {"TargetChangesCommand", ProtocolRule::command_unchanged, keep_request, Misbehaviour::change_command},
      {"TargetChangesDataPointer", ProtocolRule::data_ptr_unchanged, keep_request, Misbehaviour::change_data_ptr},
      {"TargetChangesDataLength", ProtocolRule::data_length_unchanged, keep_request, Misbehaviour::change_data_length},
      {"TargetChangesByteEnablePointer", ProtocolRule::byte_enable_ptr_unchanged, keep_request,
       Misbehaviour::change_byte_enable_ptr},
      {"TargetChangesByteEnableLength", ProtocolRule::byte_enable_length_unchanged, keep_request,
       Misbehaviour::change_byte_enable_length},
      {"TargetChangesStreamingWidth", ProtocolRule::streaming_width_unchanged, keep_request,
       Misbehaviour::change_streaming_width},
      {"TargetRewindsTime", ProtocolRule::time_not_backwards, keep_request, Misbehaviour::rewind_time},
      {"NegativeDelayOnReturn", ProtocolRule::delay_not_negative, keep_request, Misbehaviour::negative_delay},
  };
}

void PrintTo(const RuleCase& c, std::ostream* os) {
  *os << c.name;
}

class BTransportRule : public ::testing::TestWithParam<RuleCase> {};

TEST_P(BTransportRule, ReportedExactlyOnceAndForwarded) {
  const RuleCase& c = GetParam();
  Bench& b = fresh_bench();
  b.memory.fault = c.fault;
  std::array<unsigned char, 4> data{1, 2, 3, 4};
  tlm::tlm_generic_payload trans;
  const auto warnings_before = sc_core::sc_report_handler::get_count(sc_core::SC_WARNING);

  run([&] {
    prepare(trans, tlm::TLM_WRITE_COMMAND, 0x10, data.data(), 4);
    sc_time delay(20, SC_NS);
    c.spoil_request(trans, delay);
    b.cpu.out->b_transport(trans, delay);
  });

  expect_only(b, c.rule);
  EXPECT_EQ(b.memory.b_transport_calls, 1u);
  EXPECT_EQ(sc_core::sc_report_handler::get_count(sc_core::SC_WARNING), warnings_before + 1);
}

INSTANTIATE_TEST_SUITE_P(ProtocolChecker, BTransportRule, ::testing::ValuesIn(b_transport_cases()),
                         [](const ::testing::TestParamInfo<RuleCase>& case_info) { return case_info.param.name; });

TEST(ProtocolChecker, PayloadReusedWhileInFlightIsReportedOnce) {
  Bench& b = fresh_bench();
  b.memory.stall = sc_time(10, SC_NS);
  std::array<unsigned char, 4> data{1, 2, 3, 4};
  tlm::tlm_generic_payload shared;
  prepare(shared, tlm::TLM_WRITE_COMMAND, 0x10, data.data(), 4);
  sc_time start;

  run({[&] {
         start = sc_core::sc_time_stamp();
         sc_time delay = sc_core::SC_ZERO_TIME;
         b.cpu.out->b_transport(shared, delay);
       },
       [&] {
         wait(sc_time(1, SC_NS));
         sc_time delay = sc_core::SC_ZERO_TIME;
         b.cpu.out->b_transport(shared, delay);
       }});

  expect_only(b, ProtocolRule::payload_not_in_use);
  EXPECT_EQ(b.memory.b_transport_calls, 2u);
  EXPECT_EQ(sc_core::sc_time_stamp(), start + sc_time(11, SC_NS));
}

TEST(ProtocolChecker, ErrorSeverityThrowsAndLeavesCheckerUsable) {
  Bench& b = fresh_bench();
  b.checker.set_severity(sc_core::SC_ERROR);
  b.memory.fault = Misbehaviour::leave_incomplete;
  std::array<unsigned char, 4> data{1, 2, 3, 4};
  tlm::tlm_generic_payload trans;
  bool thrown = false;
  sc_core::sc_severity severity = sc_core::SC_INFO;
  std::string msg_type;

  run([&] {
    prepare(trans, tlm::TLM_WRITE_COMMAND, 0x10, data.data(), 4);
    sc_time delay = sc_core::SC_ZERO_TIME;
    try {
      b.cpu.out->b_transport(trans, delay);
    } catch (const sc_core::sc_report& report) {
      thrown = true;
      severity = report.get_severity();
      msg_type = report.get_msg_type();
    }
    // The throw must not leave the payload marked as in use.
    b.memory.fault = Misbehaviour::none;
    prepare(trans, tlm::TLM_WRITE_COMMAND, 0x10, data.data(), 4);
    b.cpu.out->b_transport(trans, delay);
  });

  EXPECT_TRUE(thrown);
  EXPECT_EQ(severity, sc_core::SC_ERROR);
  EXPECT_EQ(msg_type, "tessera/checker");
  expect_only(b, ProtocolRule::response_complete_on_return);
}

TEST(ProtocolChecker, DebugTransportIsForwardedWithoutTimePassing) {
  Bench& b = fresh_bench();
  for (std::size_t i = 0; i < 8; ++i) b.memory.memory[0x40 + i] = static_cast<unsigned char>(0xa0 + i);
  std::array<unsigned char, 8> read_back{};
  tlm::tlm_generic_payload trans;
  unsigned int count = 0;
  sc_time time_before, time_after;
  sc_dt::uint64 delta_before = 0, delta_after = 0;

  run([&] {
    wait(sc_time(3, SC_NS));
    prepare(trans, tlm::TLM_READ_COMMAND, 0x40, read_back.data(), 8);
    time_before = sc_core::sc_time_stamp();
    delta_before = sc_core::sc_delta_count();
    count = b.cpu.out->transport_dbg(trans);
    time_after = sc_core::sc_time_stamp();
    delta_after = sc_core::sc_delta_count();
  });

  EXPECT_EQ(b.checker.violation_count(), 0u) << b.report();
  EXPECT_EQ(count, 8u);
  EXPECT_EQ(b.memory.transport_dbg_calls, 1u);
  EXPECT_EQ(b.memory.b_transport_calls, 0u);
  EXPECT_EQ(time_after, time_before);
  EXPECT_EQ(delta_after, delta_before);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(read_back[i], static_cast<unsigned char>(0xa0 + i)) << "byte " << i;
}

struct DbgCase {
  const char* name;
  ProtocolRule rule;
  std::function<void(tlm::tlm_generic_payload&)> spoil_request;
  Misbehaviour fault;
};

void PrintTo(const DbgCase& c, std::ostream* os) {
  *os << c.name;
}

class DebugTransportRule : public ::testing::TestWithParam<DbgCase> {};

TEST_P(DebugTransportRule, ReportedExactlyOnceAndForwarded) {
  const DbgCase& c = GetParam();
  Bench& b = fresh_bench();
  b.memory.fault = c.fault;
  std::array<unsigned char, 4> data{};
  tlm::tlm_generic_payload trans;

  run([&] {
    prepare(trans, tlm::TLM_READ_COMMAND, 0x10, data.data(), 4);
    c.spoil_request(trans);
    b.cpu.out->transport_dbg(trans);
  });

  expect_only(b, c.rule);
  EXPECT_EQ(b.memory.transport_dbg_calls, 1u);
}

INSTANTIATE_TEST_SUITE_P(
    ProtocolChecker, DebugTransportRule,
    ::testing::Values(DbgCase{"InvalidCommand", ProtocolRule::dbg_command_valid,
                              [](tlm::tlm_generic_payload& payload) { payload.set_command(INVALID_COMMAND); },
                              Misbehaviour::none},
                      DbgCase{"NullDataPointer", ProtocolRule::dbg_data_ptr_non_null,
                              [](tlm::tlm_generic_payload& payload) { payload.set_data_ptr(nullptr); },
                              Misbehaviour::none},
                      DbgCase{"CountAboveLength", ProtocolRule::dbg_count_within_length,
                              [](tlm::tlm_generic_payload&) {}, Misbehaviour::dbg_overcount},
                      DbgCase{"WaitsADelta", ProtocolRule::dbg_takes_no_time, [](tlm::tlm_generic_payload&) {},
                              Misbehaviour::dbg_wait_delta},
                      DbgCase{"WaitsForTime", ProtocolRule::dbg_takes_no_time, [](tlm::tlm_generic_payload&) {},
                              Misbehaviour::dbg_wait_time}),
    [](const ::testing::TestParamInfo<DbgCase>& case_info) { return case_info.param.name; });

TEST(ProtocolChecker, DmiPointerReachesInitiatorAndInvalidationComesBack) {
  Bench& b = fresh_bench();
  tlm::tlm_generic_payload trans;
  tlm::tlm_dmi dmi;
  trans.set_command(tlm::TLM_READ_COMMAND);
  trans.set_address(0x10);

  const bool granted = b.cpu.out->get_direct_mem_ptr(trans, dmi);
  b.memory.invalidate(0x0, MEMORY_SIZE - 1);

  EXPECT_EQ(b.checker.violation_count(), 0u) << b.report();
  EXPECT_TRUE(granted);
  EXPECT_EQ(dmi.get_dmi_ptr(), b.memory.memory.data());
  EXPECT_EQ(dmi.get_start_address(), 0u);
  EXPECT_EQ(dmi.get_end_address(), MEMORY_SIZE - 1);
  EXPECT_TRUE(dmi.is_read_write_allowed());
  EXPECT_EQ(dmi.get_read_latency(), sc_time(TARGET_LATENCY_NS, SC_NS));
  ASSERT_EQ(b.cpu.invalidations.size(), 1u);
  EXPECT_EQ(b.cpu.invalidations.front(), std::make_pair(sc_dt::uint64{0}, sc_dt::uint64{MEMORY_SIZE - 1}));
}

TEST(ProtocolChecker, DeniedDmiOverWholeRangeIsLegal) {
  Bench& b = fresh_bench();
  b.memory.fault = Misbehaviour::dmi_denied;
  tlm::tlm_generic_payload trans;
  tlm::tlm_dmi dmi;
  trans.set_address(0x10);

  EXPECT_FALSE(b.cpu.out->get_direct_mem_ptr(trans, dmi));
  EXPECT_EQ(b.checker.violation_count(), 0u) << b.report();
}

TEST(ProtocolChecker, ReversedInvalidationIsReportedAndStillForwarded) {
  Bench& b = fresh_bench();

  b.memory.invalidate(0x80, 0x10);

  expect_only(b, ProtocolRule::invalidate_range_ordered);
  ASSERT_EQ(b.cpu.invalidations.size(), 1u);
  EXPECT_EQ(b.cpu.invalidations.front(), std::make_pair(sc_dt::uint64{0x80}, sc_dt::uint64{0x10}));
}

struct DmiCase {
  const char* name;
  ProtocolRule rule;
  Misbehaviour fault;
  bool granted;
};

void PrintTo(const DmiCase& c, std::ostream* os) {
  *os << c.name;
}

class DmiRule : public ::testing::TestWithParam<DmiCase> {};

TEST_P(DmiRule, ReportedExactlyOnce) {
  const DmiCase& c = GetParam();
  Bench& b = fresh_bench();
  b.memory.fault = c.fault;
  tlm::tlm_generic_payload trans;
  tlm::tlm_dmi dmi;
  trans.set_command(tlm::TLM_READ_COMMAND);
  trans.set_address(0x10);

  EXPECT_EQ(b.cpu.out->get_direct_mem_ptr(trans, dmi), c.granted);
  expect_only(b, c.rule);
}

INSTANTIATE_TEST_SUITE_P(
    ProtocolChecker, DmiRule,
    ::testing::Values(
        DmiCase{"GrantedReversedRange", ProtocolRule::dmi_range_ordered, Misbehaviour::dmi_reversed_range, true},
        DmiCase{"DeniedReversedRange", ProtocolRule::dmi_range_ordered, Misbehaviour::dmi_denied_reversed_range, false},
        DmiCase{"AddressOutsideRange", ProtocolRule::dmi_address_in_range, Misbehaviour::dmi_outside_range, true},
        DmiCase{"NoAccessGranted", ProtocolRule::dmi_access_granted, Misbehaviour::dmi_no_access, true},
        DmiCase{"NullPointer", ProtocolRule::dmi_ptr_non_null, Misbehaviour::dmi_null_ptr, true}),
    [](const ::testing::TestParamInfo<DmiCase>& case_info) { return case_info.param.name; });

TEST(ProtocolChecker, NbTransportIsReportedAsUnsupported) {
  Bench& b = fresh_bench();
  std::array<unsigned char, 4> data{};
  tlm::tlm_generic_payload trans;
  prepare(trans, tlm::TLM_READ_COMMAND, 0x10, data.data(), 4);
  tlm::tlm_phase phase = tlm::BEGIN_REQ;
  sc_time delay = sc_core::SC_ZERO_TIME;

  EXPECT_EQ(b.cpu.out->nb_transport_fw(trans, phase, delay), tlm::TLM_COMPLETED);
  EXPECT_EQ(trans.get_response_status(), tlm::TLM_GENERIC_ERROR_RESPONSE);
  EXPECT_EQ(b.memory.b_transport_calls, 0u);
  expect_only(b, ProtocolRule::nb_transport_unsupported);

  phase = tlm::BEGIN_RESP;
  EXPECT_EQ(b.memory.in->nb_transport_bw(trans, phase, delay), tlm::TLM_COMPLETED);
  EXPECT_EQ(b.checker.violation_count(ProtocolRule::nb_transport_unsupported), 2u) << b.report();
}

}  // namespace

int sc_main(int argc, char* argv[]) {
  for (std::size_t i = 0; i < BENCH_POOL_SIZE; ++i)
    bench_pool().push_back(std::make_unique<Bench>(("bench_" + std::to_string(i)).c_str()));
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
