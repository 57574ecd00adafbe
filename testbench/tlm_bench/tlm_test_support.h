// Shared pieces of the TLM tests: an initiator that issues single
// transactions from a test's thread, a way to run a test body as a SystemC
// thread, and a capture of the warnings the models report.
//
// The SystemC kernel cannot be reset, so each test executable elaborates all
// its benches in sc_main, then runs GoogleTest; each test runs its stimulus
// with run_thread(), which starts after the previous test's traffic is over.
#pragma once

// run_thread() spawns a process: SystemC declares sc_spawn only when asked,
// and <systemc> may already have been included without it.
#ifndef SC_INCLUDE_DYNAMIC_PROCESSES
#define SC_INCLUDE_DYNAMIC_PROCESSES
#endif

#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tlm_utils/simple_initiator_socket.h>
#include <systemc>
#include <tlm>

namespace tessera::test {

class TestInitiator : public sc_core::sc_module {
 public:
  tlm_utils::simple_initiator_socket<TestInitiator, 32> out;

  explicit TestInitiator(sc_core::sc_module_name name) : sc_core::sc_module(name), out("out") {
    out.register_invalidate_direct_mem_ptr(this, &TestInitiator::invalidate);
  }

  struct Result {
    tlm::tlm_response_status status;
    sc_core::sc_time delay;  // as annotated on return
  };

  // One b_transport with local time offset `offset`; does not wait.
  Result transport(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned length,
                   sc_core::sc_time offset = sc_core::SC_ZERO_TIME) {
    tlm::tlm_generic_payload gp;
    gp.set_command(command);
    gp.set_address(address);
    gp.set_data_ptr(data);
    gp.set_data_length(length);
    gp.set_streaming_width(length);
    gp.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    sc_core::sc_time delay = offset;
    out->b_transport(gp, delay);
    return {gp.get_response_status(), delay};
  }
  Result read(uint64_t address, uint8_t* data, unsigned length, sc_core::sc_time offset = sc_core::SC_ZERO_TIME) {
    return transport(tlm::TLM_READ_COMMAND, address, data, length, offset);
  }
  Result write(uint64_t address, const uint8_t* data, unsigned length,
               sc_core::sc_time offset = sc_core::SC_ZERO_TIME) {
    return transport(tlm::TLM_WRITE_COMMAND, address, const_cast<uint8_t*>(data), length, offset);
  }
  Result write32(uint64_t address, uint32_t value) {
    return write(address, reinterpret_cast<const uint8_t*>(&value), 4);
  }
  uint32_t read32(uint64_t address, Result* result = nullptr) {
    uint32_t value = 0;
    Result r = read(address, reinterpret_cast<uint8_t*>(&value), 4);
    if (result) *result = r;
    return value;
  }
  unsigned debug(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned length) {
    tlm::tlm_generic_payload gp;
    gp.set_command(command);
    gp.set_address(address);
    gp.set_data_ptr(data);
    gp.set_data_length(length);
    gp.set_streaming_width(length);
    return out->transport_dbg(gp);
  }

  // Reads a word without time (usable outside a SystemC thread).
  uint32_t peek32(uint64_t address) {
    uint32_t value = 0;
    debug(tlm::TLM_READ_COMMAND, address, reinterpret_cast<uint8_t*>(&value), 4);
    return value;
  }

  std::vector<std::pair<uint64_t, uint64_t>> invalidations;

 private:
  void invalidate(sc_dt::uint64 start, sc_dt::uint64 end) { invalidations.emplace_back(start, end); }
};

// Runs `body` in a new SystemC thread, starting `settle` after the current
// time so that the previous test's bus reservations have expired, and
// simulates until nothing is left to do (or for `limit` if given, for
// benches with free-running processes). Returns the start time of the body.
inline sc_core::sc_time run_thread(const std::function<void()>& body, sc_core::sc_time limit = sc_core::SC_ZERO_TIME,
                                   sc_core::sc_time settle = sc_core::sc_time(100, sc_core::SC_US)) {
  const sc_core::sc_time start = sc_core::sc_time_stamp() + settle;
  sc_core::sc_spawn([=] {
    sc_core::wait(settle);
    body();
  });
  if (limit == sc_core::SC_ZERO_TIME)
    sc_core::sc_start();
  else
    sc_core::sc_start(settle + limit);
  return start;
}

// Collects warnings and errors instead of printing them.
class ReportCapture {
 public:
  ReportCapture() {
    messages().clear();
    sc_core::sc_report_handler::set_handler(&ReportCapture::handle);
  }
  ~ReportCapture() { sc_core::sc_report_handler::set_handler(sc_core::sc_report_handler::default_handler); }
  static std::vector<std::string>& messages() {
    static std::vector<std::string> list;
    return list;
  }
  bool contains(const std::string& text) const {
    for (const auto& m : messages())
      if (m.find(text) != std::string::npos) return true;
    return false;
  }

 private:
  static void handle(const sc_core::sc_report& report, const sc_core::sc_actions&) {
    if (report.get_severity() >= sc_core::SC_WARNING)
      messages().push_back(std::string(report.get_msg_type()) + ": " + report.get_msg());
  }
};

inline int run_all_tests(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

}  // namespace tessera::test
