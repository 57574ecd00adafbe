// Unit tests of the register bank (tlm/common/register_bank.h): each access
// kind (rw, ro, wo, w1c) through the bus path and the debug path, read and
// write handlers, every bad access with its TLM response and warning, the
// programming errors, and the access's annotated time handed to handlers.
// The bank has no time of its own: a bus access neither waits nor adds
// latency (that is the owner's), which the tests check too.
#include <cstring>
#include <stdexcept>
#include <string>

#include "common/register_bank.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;

namespace {

const RegisterInfo CTRL{"CTRL", 0x00, 0x5, RegAccess::rw};
const RegisterInfo ID{"ID", 0x04, 0x1234, RegAccess::ro};
const RegisterInfo KICK{"KICK", 0x08, 0x0, RegAccess::wo};
const RegisterInfo PENDING{"PENDING", 0x0C, 0xF, RegAccess::w1c};
const RegisterInfo LEVEL{"LEVEL", 0x10, 0x0, RegAccess::ro};
const RegisterInfo MODE{"MODE", 0x14, 0x0, RegAccess::rw};

// One access as a bus would make it; `delay` is the annotated time.
struct Access {
  tlm::tlm_generic_payload gp;
  uint32_t data = 0;
  const char* touched = nullptr;

  Access(tlm::tlm_command command, uint64_t offset, uint32_t value = 0, unsigned length = 4) : data(value) {
    gp.set_command(command);
    gp.set_address(offset);
    gp.set_data_ptr(reinterpret_cast<uint8_t*>(&data));
    gp.set_data_length(length);
    gp.set_streaming_width(length);
    gp.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  }
  tlm::tlm_response_status on(RegisterBank& bank, const sc_time& delay = sc_core::SC_ZERO_TIME) {
    touched = bank.transport(gp, delay);
    return gp.get_response_status();
  }
  unsigned debug_on(RegisterBank& bank) { return bank.transport_dbg(gp); }
};

uint32_t read(RegisterBank& bank, uint64_t offset, tlm::tlm_response_status* status = nullptr) {
  Access a(tlm::TLM_READ_COMMAND, offset);
  const tlm::tlm_response_status s = a.on(bank);
  if (status) *status = s;
  return a.data;
}

tlm::tlm_response_status write(RegisterBank& bank, uint64_t offset, uint32_t value) {
  return Access(tlm::TLM_WRITE_COMMAND, offset, value).on(bank);
}

// A bank with one register of each kind, plus LEVEL (a read handler) and
// MODE (a write handler that keeps only the low two bits and counts calls).
struct Bank {
  RegisterBank bank{"test.bank"};
  uint32_t level = 0;
  unsigned mode_writes = 0;
  sc_time seen_delay;
  Bank() {
    bank.add(CTRL);
    bank.add(ID);
    bank.add(KICK);
    bank.add(PENDING);
    bank.add(LEVEL, [this] { return level; });
    bank.add(MODE, {}, [this](uint32_t value) {
      ++mode_writes;
      seen_delay = bank.access_delay();
      bank.set(MODE.offset, value & 3);
    });
  }
};

}  // namespace

TEST(RegisterBank, ResetValuesReadBackAndRwStoresWhatIsWritten) {
  Bank b;
  const sc_time start = sc_core::sc_time_stamp();
  EXPECT_EQ(read(b.bank, CTRL.offset), 0x5u);
  EXPECT_EQ(read(b.bank, ID.offset), 0x1234u);
  EXPECT_EQ(write(b.bank, CTRL.offset, 0xCAFE), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(read(b.bank, CTRL.offset), 0xCAFEu);
  EXPECT_EQ(b.bank.get(CTRL.offset), 0xCAFEu);
  b.bank.reset();
  EXPECT_EQ(read(b.bank, CTRL.offset), 0x5u);
  // The bank takes no time: the kernel has not moved.
  EXPECT_EQ(sc_core::sc_time_stamp(), start);
}

TEST(RegisterBank, TransportNamesTheRegisterTouchedAndLeavesTheDelayToTheOwner) {
  Bank b;
  Access a(tlm::TLM_WRITE_COMMAND, CTRL.offset, 1);
  const sc_time delay(30, sc_core::SC_NS);
  EXPECT_EQ(a.on(b.bank, delay), tlm::TLM_OK_RESPONSE);
  EXPECT_STREQ(a.touched, "CTRL");
  Access bad(tlm::TLM_WRITE_COMMAND, 0x40, 1);
  test::ReportCapture quiet;
  EXPECT_EQ(bad.on(b.bank, delay), tlm::TLM_ADDRESS_ERROR_RESPONSE);
  EXPECT_EQ(bad.touched, nullptr);
}

TEST(RegisterBank, ReadOnlyRefusesWritesWithACommandError) {
  Bank b;
  test::ReportCapture reports;
  EXPECT_EQ(write(b.bank, ID.offset, 0), tlm::TLM_COMMAND_ERROR_RESPONSE);
  EXPECT_EQ(read(b.bank, ID.offset), 0x1234u);
  EXPECT_TRUE(reports.contains("test.bank")) << reports.messages().front();
  EXPECT_TRUE(reports.contains("bad register access: write of 4 bytes at offset 0x00000004 (command error)"));
  // The hardware side may still change it.
  b.bank.set(ID.offset, 0x99);
  EXPECT_EQ(read(b.bank, ID.offset), 0x99u);
}

TEST(RegisterBank, WriteOnlyRefusesReadsWithACommandError) {
  Bank b;
  test::ReportCapture reports;
  EXPECT_EQ(write(b.bank, KICK.offset, 7), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(b.bank.get(KICK.offset), 7u);
  tlm::tlm_response_status status;
  read(b.bank, KICK.offset, &status);
  EXPECT_EQ(status, tlm::TLM_COMMAND_ERROR_RESPONSE);
  EXPECT_TRUE(reports.contains("bad register access: read of 4 bytes at offset 0x00000008 (command error)"));
}

TEST(RegisterBank, WriteOneToClearClearsOnlyTheBitsWrittenAsOne) {
  Bank b;
  EXPECT_EQ(read(b.bank, PENDING.offset), 0xFu);
  EXPECT_EQ(write(b.bank, PENDING.offset, 0x5), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(read(b.bank, PENDING.offset), 0xAu);
  EXPECT_EQ(write(b.bank, PENDING.offset, 0), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(read(b.bank, PENDING.offset), 0xAu);
  // The source sets bits through the hardware side.
  b.bank.set(PENDING.offset, b.bank.get(PENDING.offset) | 0x10);
  EXPECT_EQ(read(b.bank, PENDING.offset), 0x1Au);
}

TEST(RegisterBank, ReadHandlerComputesTheValueAndWriteHandlerReplacesTheStore) {
  Bank b;
  b.level = 42;
  EXPECT_EQ(read(b.bank, LEVEL.offset), 42u);
  b.level = 43;
  EXPECT_EQ(read(b.bank, LEVEL.offset), 43u);
  EXPECT_EQ(write(b.bank, MODE.offset, 0xFF), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(b.mode_writes, 1u);
  EXPECT_EQ(read(b.bank, MODE.offset), 3u);
}

TEST(RegisterBank, HandlersSeeTheAccessesAnnotatedTime) {
  Bank b;
  const sc_time delay(250, sc_core::SC_NS);
  Access a(tlm::TLM_WRITE_COMMAND, MODE.offset, 1);
  EXPECT_EQ(a.on(b.bank, delay), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(b.seen_delay, delay);
  // Outside an access there is no annotated time.
  EXPECT_EQ(b.bank.access_delay(), sc_core::SC_ZERO_TIME);
}

TEST(RegisterBank, BadAccessesGetErrorResponsesAndWarnings) {
  Bank b;
  test::ReportCapture reports;
  // Not 32 bits.
  uint16_t half = 0;
  Access short_access(tlm::TLM_READ_COMMAND, CTRL.offset, 0, 2);
  short_access.gp.set_data_ptr(reinterpret_cast<uint8_t*>(&half));
  EXPECT_EQ(short_access.on(b.bank), tlm::TLM_BURST_ERROR_RESPONSE);
  EXPECT_TRUE(reports.contains("read of 2 bytes at offset 0x00000000 (burst error)"));
  // Streaming width below the data.
  Access streaming(tlm::TLM_WRITE_COMMAND, CTRL.offset, 1);
  streaming.gp.set_streaming_width(2);
  EXPECT_EQ(streaming.on(b.bank), tlm::TLM_BURST_ERROR_RESPONSE);
  EXPECT_EQ(b.bank.get(CTRL.offset), 0x5u);
  // Byte enables.
  uint8_t enables[4] = {0xff, 0, 0xff, 0};
  Access enabled(tlm::TLM_WRITE_COMMAND, CTRL.offset, 1);
  enabled.gp.set_byte_enable_ptr(enables);
  enabled.gp.set_byte_enable_length(4);
  EXPECT_EQ(enabled.on(b.bank), tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
  EXPECT_EQ(b.bank.get(CTRL.offset), 0x5u);
  // No register at the offset, aligned or not.
  tlm::tlm_response_status status;
  read(b.bank, 0x100, &status);
  EXPECT_EQ(status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  read(b.bank, 0x2, &status);
  EXPECT_EQ(status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  EXPECT_TRUE(reports.contains("read of 4 bytes at offset 0x00000002 (address error)"));
  EXPECT_EQ(b.mode_writes, 0u);
}

TEST(RegisterBank, DebugReadsRunReadHandlersAndAreAllowedOnWriteOnlyRegisters) {
  Bank b;
  b.level = 9;
  Access level(tlm::TLM_READ_COMMAND, LEVEL.offset);
  EXPECT_EQ(level.debug_on(b.bank), 4u);
  EXPECT_EQ(level.data, 9u);
  b.bank.set(KICK.offset, 0x77);
  Access kick(tlm::TLM_READ_COMMAND, KICK.offset);
  EXPECT_EQ(kick.debug_on(b.bank), 4u);
  EXPECT_EQ(kick.data, 0x77u);
}

TEST(RegisterBank, DebugWritesStoreWithoutHandlersAndAreRefusedOnReadOnlyRegisters) {
  Bank b;
  Access mode(tlm::TLM_WRITE_COMMAND, MODE.offset, 0xFF);
  EXPECT_EQ(mode.debug_on(b.bank), 4u);
  EXPECT_EQ(b.mode_writes, 0u);
  EXPECT_EQ(b.bank.get(MODE.offset), 0xFFu);
  // A debug write of a w1c register stores the value as it is.
  Access pending(tlm::TLM_WRITE_COMMAND, PENDING.offset, 0x3);
  EXPECT_EQ(pending.debug_on(b.bank), 4u);
  EXPECT_EQ(b.bank.get(PENDING.offset), 0x3u);
  Access id(tlm::TLM_WRITE_COMMAND, ID.offset, 0);
  EXPECT_EQ(id.debug_on(b.bank), 0u);
  EXPECT_EQ(b.bank.get(ID.offset), 0x1234u);
}

TEST(RegisterBank, BadDebugAccessesTransferNothing) {
  Bank b;
  test::ReportCapture reports;
  Access missing(tlm::TLM_READ_COMMAND, 0x100);
  EXPECT_EQ(missing.debug_on(b.bank), 0u);
  Access short_write(tlm::TLM_WRITE_COMMAND, CTRL.offset, 1, 2);
  EXPECT_EQ(short_write.debug_on(b.bank), 0u);
  EXPECT_EQ(b.bank.get(CTRL.offset), 0x5u);
  // The debug path reports nothing: a debugger's probe is not a bad access.
  EXPECT_TRUE(reports.messages().empty());
}

TEST(RegisterBank, DeclaringABadRegisterOrTouchingAMissingOneIsAProgrammingError) {
  RegisterBank bank("test.errors");
  bank.add(CTRL);
  EXPECT_THROW(bank.add({"TWICE", CTRL.offset, 0, RegAccess::rw}), std::logic_error);
  EXPECT_THROW(bank.add({"ODD", 0x22, 0, RegAccess::rw}), std::logic_error);
  EXPECT_THROW(bank.get(0x40), std::logic_error);
  EXPECT_THROW(bank.set(0x40, 1), std::logic_error);
  try {
    bank.add({"ODD", 0x22, 0, RegAccess::rw});
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("test.errors: register ODD"), std::string::npos) << e.what();
  }
}

int sc_main(int argc, char* argv[]) {
  return test::run_all_tests(argc, argv);
}
